// Facet's own image codecs (io/image_codecs.h), with OpenImageIO as the independent
// decoder: the PNG and EXR files we write decode to exactly our texels, the .hdr files to
// what our reader reads and within RGBE's precision; our Radiance reader reads what
// OpenImageIO reads, bit for bit; damaged files are errors saying where; and reading a
// .hdr environment or writing any of the three formats loads no image module.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <vector>

#include <facet/io/environment_image.h>
#include <facet/io/image_io.h>
#include "io/image_codecs.h"
#include "support/output_files.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

struct Size {
    uint32_t width, height;
};

template <class T>
struct Decoded {
    int width = 0, height = 0, channels = 0;
    std::vector<T> values;
    OIIO::ImageSpec spec;
};

// The whole file as OpenImageIO decodes it, stored values (alpha not applied).
template <class T>
Decoded<T> oiio_read(const std::string& path) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
    Decoded<T> d;
    if (!in) return d;
    d.spec = in->spec();
    d.width = d.spec.width;
    d.height = d.spec.height;
    d.channels = d.spec.nchannels;
    d.values.resize(size_t(d.width) * d.height * d.channels);
    EXPECT_TRUE(in->read_image(0, 0, 0, d.channels, OIIO::BaseTypeFromC<T>::value, d.values.data())) << in->geterror();
    return d;
}

// Every row as our reader reads it, or the first error.
Result<std::vector<float>> our_read(const std::string& path) {
    auto opened = codec::RgbeReader::open(path);
    if (!opened) return opened.error();
    if (!*opened) return Error{"declined"};
    codec::RgbeReader& in = **opened;
    std::vector<float> rgb(size_t(in.width()) * in.height() * 3);
    for (uint64_t y = 0; y < in.height(); ++y)
        if (Status s = in.read_row(&rgb[size_t(y) * in.width() * 3]); !s) return s.error();
    return rgb;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

std::string rgbe_header(uint32_t width, uint32_t height) {
    return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
}

float rgbe_value(uint8_t m, uint8_t e) { return e == 0 ? 0.0f : std::ldexp(float(m), int(e) - 136); }

const Size kSizes[] = {{1, 1}, {7, 3}, {1023, 17}, {5, 16}, {3, 32}, {9, 33}, {64, 40}};

TEST(ImageCodecs, PngDecodesToExactlyTheInput) {
    TempDir dir("image_codecs_test");
    std::mt19937 random(1);
    for (Size s : kSizes) {
        std::vector<uint8_t> rgba(size_t(s.width) * s.height * 4);
        for (uint8_t& v : rgba) v = uint8_t(random());
        const std::string path = dir.file("a.png");
        ASSERT_TRUE(write_ldr_image(path, s.width, s.height, rgba));
        auto back = oiio_read<uint8_t>(path);
        ASSERT_EQ(back.width, int(s.width));
        ASSERT_EQ(back.height, int(s.height));
        ASSERT_EQ(back.channels, 4);
        EXPECT_EQ(back.values, rgba) << s.width << "x" << s.height;
    }
}

// Large images are deflated in parts on several threads: each part count gives a stream
// that decodes to the input (libpng checks the zlib stream's adler32 and every chunk's CRC).
TEST(ImageCodecs, PngInPartsDecodesToExactlyTheInput) {
    TempDir dir("image_codecs_test");
    std::mt19937 random(2);
    for (Size s : {Size{700, 300}, Size{333, 7}, Size{1024, 512}}) {
        std::vector<uint8_t> noise(size_t(s.width) * s.height * 4), smooth(noise.size());
        for (uint8_t& v : noise) v = uint8_t(random());
        for (size_t i = 0; i < smooth.size(); ++i) smooth[i] = uint8_t((i / 4) % s.width * 255 / s.width + i % 4);
        for (const std::vector<uint8_t>* rgba : {&noise, &smooth})
            for (uint32_t parts : {0u, 1u, 2u, 3u, 4u, 9u}) {
                std::vector<uint8_t> bytes;
                codec::ByteSink sink(bytes);
                ASSERT_TRUE(codec::write_png(sink, s.width, s.height, rgba->data(), parts));
                const std::string path = dir.file("parts.png");
                write_bytes(path, std::string(bytes.begin(), bytes.end()));
                auto back = oiio_read<uint8_t>(path);
                ASSERT_EQ(back.width, int(s.width));
                ASSERT_EQ(back.height, int(s.height));
                EXPECT_EQ(back.values, *rgba) << s.width << "x" << s.height << " in " << parts << " parts";
            }
    }
}

// An EXR's chunks compressed in parts on several threads: the same bytes for every count.
TEST(ImageCodecs, ExrInPartsIsTheSameFile) {
    std::mt19937 random(3);
    std::uniform_real_distribution<float> value(0.0f, 4.0f);
    for (Size s : {Size{300, 200}, Size{64, 17}, Size{1, 1}}) {
        std::vector<float> rgba(size_t(s.width) * s.height * 4);
        for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = i % 7 == 0 ? value(random) : float(i % 97) * 0.25f;
        std::vector<uint8_t> one;
        codec::ByteSink first(one);
        ASSERT_TRUE(codec::write_exr(first, s.width, s.height, rgba.data(), 1));
        for (uint32_t parts : {0u, 2u, 3u, 4u, 16u}) {
            std::vector<uint8_t> bytes;
            codec::ByteSink sink(bytes);
            ASSERT_TRUE(codec::write_exr(sink, s.width, s.height, rgba.data(), parts));
            EXPECT_TRUE(bytes == one) << s.width << "x" << s.height << " in " << parts << " parts";
        }
    }
}

// Formats other than PNG are written through the image module, as the extension says.
TEST(ImageCodecs, OtherLdrFormatsGoThroughTheModule) {
    TempDir dir("image_codecs_test");
    std::vector<uint8_t> rgba(7 * 3 * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = uint8_t(i * 11);
    ASSERT_TRUE(write_ldr_image(dir.file("a.tif"), 7, 3, rgba));
    auto back = oiio_read<uint8_t>(dir.file("a.tif"));
    const std::string magic = read_file(dir.file("a.tif")).substr(0, 4);
    EXPECT_TRUE(magic == std::string("II*\0", 4) || magic == std::string("MM\0*", 4)) << "a TIFF";
    EXPECT_EQ(back.values, rgba);
}

// The EXR's chunk sizes, from its offset table (the header walked as the file layout
// gives it: name, type, int32 size, value; an empty name ends it).
std::vector<int32_t> exr_chunk_sizes(const std::string& bytes, uint32_t height) {
    size_t at = 8;
    while (bytes[at] != '\0') {
        at = bytes.find('\0', at) + 1;  // name
        at = bytes.find('\0', at) + 1;  // type
        int32_t size;
        std::memcpy(&size, &bytes[at], 4);
        at += 4 + size_t(size);
    }
    ++at;
    std::vector<int32_t> sizes;
    for (uint32_t k = 0; k < (height + 15) / 16; ++k) {
        uint64_t offset;
        std::memcpy(&offset, &bytes[at + k * 8], 8);
        int32_t y, size;
        std::memcpy(&y, &bytes[offset], 4);
        std::memcpy(&size, &bytes[offset + 4], 4);
        EXPECT_EQ(y, int32_t(k * 16));
        sizes.push_back(size);
    }
    return sizes;
}

TEST(ImageCodecs, ExrDecodesToEveryBitOfTheInput) {
    TempDir dir("image_codecs_test");
    std::mt19937 random(2);
    const float specials[] = {0.0f, -0.0f, 65504.0f, 65505.0f, 1e5f, 3e38f, 1e-30f, 1e-40f, -2.5f,
                              std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()};
    for (bool smooth : {true, false}) {
        for (Size s : kSizes) {
            std::vector<float> rgba(size_t(s.width) * s.height * 4);
            for (size_t i = 0; i < rgba.size(); ++i) {
                // Smooth: few distinct bytes, so ZIP shrinks every chunk; random bits: none shrinks.
                if (smooth) rgba[i] = i % 13 == 0 ? specials[(i / 13) % std::size(specials)] : float(i % 64) * 0.25f;
                else rgba[i] = std::bit_cast<float>(uint32_t(random()));
            }
            const std::string path = dir.file("a.exr");
            ASSERT_TRUE(write_hdr_image(path, s.width, s.height, rgba));
            auto back = oiio_read<float>(path);
            ASSERT_EQ(back.width, int(s.width));
            ASSERT_EQ(back.height, int(s.height));
            ASSERT_EQ(back.channels, 4);
            EXPECT_EQ(back.spec.get_string_attribute("compression"), "zip");
            EXPECT_EQ(back.spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
            EXPECT_TRUE(same_bits(back.values, rgba)) << s.width << "x" << s.height << (smooth ? " smooth" : " random");
            // Encoded in memory (a file made ahead of writing it): the same bytes.
            auto encoded = encode_hdr_image(path, s.width, s.height, rgba);
            ASSERT_TRUE(encoded) << encoded.error().message;
            EXPECT_EQ(std::string(encoded->begin(), encoded->end()), read_file(path)) << s.width << "x" << s.height;
            // Both kinds of chunk: compressed when that shrinks it, stored otherwise.
            const std::vector<int32_t> sizes = exr_chunk_sizes(read_file(path), s.height);
            for (uint32_t k = 0; k < sizes.size(); ++k) {
                const int32_t raw = int32_t(std::min(16u, s.height - k * 16) * s.width * 16);
                if (smooth && raw > 200) EXPECT_LT(sizes[k], raw) << "chunk " << k;
                if (!smooth) EXPECT_EQ(sizes[k], raw) << "chunk " << k;
            }
        }
    }
    // The same texels, the same bytes.
    std::vector<float> rgba(64 * 40 * 4, 0.5f);
    ASSERT_TRUE(write_hdr_image(dir.file("b.exr"), 64, 40, rgba));
    ASSERT_TRUE(write_hdr_image(dir.file("c.exr"), 64, 40, rgba));
    EXPECT_EQ(read_file(dir.file("b.exr")), read_file(dir.file("c.exr")));
}

// Radiance files encoded in memory are the bytes written to a file; anything but .exr and
// .hdr is refused by name.
TEST(ImageCodecs, HdrEncodedInMemoryIsTheFilesBytes) {
    TempDir dir("image_codecs_memory");
    for (Size s : kSizes) {
        std::vector<float> rgba(size_t(s.width) * s.height * 4);
        for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = float((i * 7919) % 1000) * 0.37f;
        const std::string path = dir.file("a.hdr");
        ASSERT_TRUE(write_hdr_image(path, s.width, s.height, rgba));
        auto encoded = encode_hdr_image(path, s.width, s.height, rgba);
        ASSERT_TRUE(encoded) << encoded.error().message;
        EXPECT_EQ(std::string(encoded->begin(), encoded->end()), read_file(path)) << s.width << "x" << s.height;
    }
    std::vector<float> rgba(4 * 4 * 4, 1.0f);
    auto png = encode_hdr_image("preview.png", 4, 4, rgba);
    ASSERT_FALSE(png);
    EXPECT_NE(png.error().message.find("preview.png: HDR output must be .exr or .hdr"), std::string::npos)
        << png.error().message;
    auto short_buffer = encode_hdr_image("a.exr", 8, 4, rgba);
    ASSERT_FALSE(short_buffer);
    EXPECT_NE(short_buffer.error().message.find("a.exr"), std::string::npos) << short_buffer.error().message;
}

TEST(ImageCodecs, HdrDecodesAsOurReaderAndWithinRgbePrecision) {
    TempDir dir("image_codecs_test");
    std::mt19937 random(3);
    std::uniform_real_distribution<float> exponent(-40.0f, 40.0f);
    const Size sizes[] = {{1, 1}, {7, 3}, {8, 2}, {1023, 17}, {32767, 1}, {32768, 1}, {40, 5}};
    for (Size s : sizes) {
        std::vector<float> rgba(size_t(s.width) * s.height * 4);
        for (size_t i = 0; i < rgba.size(); ++i) {
            const size_t texel = i / 4;
            if (s.width == 40) rgba[i] = float(texel / 40 + 1);  // constant rows: runs
            else if (texel % 17 == 0) rgba[i] = 0.0f;
            else if (texel % 19 == 0) rgba[i] = 1e-35f;  // below RGBE's 1e-32: 0
            else rgba[i] = std::exp2(exponent(random));
        }
        const std::string path = dir.file("a.hdr");
        ASSERT_TRUE(write_hdr_image(path, s.width, s.height, rgba));
        auto theirs = oiio_read<float>(path);
        ASSERT_EQ(theirs.width, int(s.width));
        ASSERT_EQ(theirs.height, int(s.height));
        ASSERT_EQ(theirs.channels, 3);
        auto ours = our_read(path);
        ASSERT_TRUE(ours) << ours.error().message;
        EXPECT_TRUE(same_bits(*ours, theirs.values)) << s.width << "x" << s.height;
        for (size_t t = 0; t < size_t(s.width) * s.height; ++t) {
            const float* in = &rgba[t * 4];
            const float max = std::max({in[0], in[1], in[2]});
            for (int c = 0; c < 3; ++c) {
                const float back = (*ours)[t * 3 + c];
                if (max < 1e-32f) ASSERT_EQ(back, 0.0f) << "texel " << t;
                else ASSERT_NEAR(back, in[c], max / 128) << "texel " << t << " channel " << c;
                ASSERT_LE(back, in[c]) << "RGBE truncates";
            }
        }
    }
    // What RGBE cannot hold: negative and NaN as 0, beyond its largest value as that.
    const float odd[8] = {-1.0f, std::numeric_limits<float>::quiet_NaN(), 2.0f, 1.0f,
                          std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 1.0f};
    ASSERT_TRUE(write_hdr_image(dir.file("odd.hdr"), 2, 1, odd));
    auto back = our_read(dir.file("odd.hdr"));
    ASSERT_TRUE(back);
    EXPECT_EQ(*back, (std::vector<float>{0.0f, 0.0f, 2.0f, std::ldexp(255.0f, 119), 0.0f, 0.0f}));
}

TEST(ImageCodecs, ReaderEqualsOpenImageIOOnTheSharedEnvironments) {
    int files = 0;
    for (const auto& entry : fs::directory_iterator(std::string(FACET_SHARED_DATA_DIR) + "/env")) {
        if (entry.path().extension() != ".hdr") continue;
        const std::string path = entry.path().string();
        auto ours = our_read(path);
        ASSERT_TRUE(ours) << path << ": " << ours.error().message;
        auto theirs = oiio_read<float>(path);
        EXPECT_TRUE(same_bits(*ours, theirs.values)) << path;
        ++files;
    }
    EXPECT_GE(files, 4);
}

// New-style run-length rows and flat ones, mixed in one file, and files too narrow or
// too wide for run-length rows.
TEST(ImageCodecs, ReaderEqualsOpenImageIOOnFlatAndRunLengthRows) {
    TempDir dir("image_codecs_test");
    std::mt19937 random(4);
    auto byte = [&](int low, int high) { return char(std::uniform_int_distribution<int>(low, high)(random)); };
    // A flat texel that is neither a run-length row's start (2, 2) nor an old-style repeat (1, 1, 1).
    auto flat_texel = [&] { return std::string{byte(3, 255), byte(0, 255), byte(0, 255), byte(100, 160)}; };
    const uint32_t w = 300;
    std::string rle_row = {2, 2, char(w >> 8), char(w & 255)};
    auto literal = [&](int n, int low, int high) {
        rle_row += char(n);
        for (int i = 0; i < n; ++i) rle_row += byte(low, high);
    };
    auto run = [&](int n, char value) { rle_row += {char(128 + n), value}; };
    // R, G, B, then E (100 texels of exponent 0 at the end: 0).
    literal(128, 0, 255);
    run(127, char(200));
    literal(45, 0, 255);
    run(127, 7);
    run(127, char(250));
    run(46, 0);
    literal(128, 0, 255);
    literal(128, 0, 255);
    literal(44, 0, 255);
    run(100, char(130));
    literal(100, 120, 140);
    run(100, 0);
    std::string flat_row;
    for (uint32_t x = 0; x < w; ++x) flat_row += flat_texel();
    write_bytes(dir.file("mixed.hdr"), rgbe_header(w, 4) + rle_row + flat_row + flat_row + rle_row);
    for (uint32_t narrow_or_wide : {5u, 40000u}) {
        std::string bytes = rgbe_header(narrow_or_wide, 2);
        for (uint32_t x = 0; x < narrow_or_wide * 2; ++x) bytes += flat_texel();
        write_bytes(dir.file(std::to_string(narrow_or_wide) + ".hdr"), bytes);
    }
    for (const char* name : {"mixed.hdr", "5.hdr", "40000.hdr"}) {
        auto ours = our_read(dir.file(name));
        ASSERT_TRUE(ours) << name << ": " << ours.error().message;
        EXPECT_TRUE(same_bits(*ours, oiio_read<float>(dir.file(name)).values)) << name;
    }
    // And the values themselves: a flat row's first texel.
    auto mixed = our_read(dir.file("mixed.hdr"));
    EXPECT_EQ((*mixed)[w * 3], rgbe_value(uint8_t(flat_row[0]), uint8_t(flat_row[3])));
    EXPECT_EQ((*mixed)[w * 3 - 1], 0.0f) << "exponent 0";
}

// Old-style runs as Radiance's own reader takes them (OpenImageIO 2.4 reads the
// markers as texels, so it is no reference here): 1, 1, 1, n repeats the texel before
// n times, each further marker in a row of them shifting its count by 8 more bits.
TEST(ImageCodecs, OldStyleRunsRepeatTheTexelBefore) {
    TempDir dir("image_codecs_test");
    const std::string a = {char(128), 64, 32, char(129)}, b = {10, 20, char(200), char(120)};
    const std::string row = a + std::string{1, 1, 1, 2} + std::string{1, 1, 1, 1} + b + std::string{1, 1, 1, 40};
    write_bytes(dir.file("old.hdr"), rgbe_header(300, 2) + row + row);
    auto back = our_read(dir.file("old.hdr"));
    ASSERT_TRUE(back) << back.error().message;
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 300; ++x) {
            const std::string& texel = x < 259 ? a : b;  // a, 2 copies, 1 << 8 copies; b, 40 copies
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ((*back)[(y * 300 + x) * 3 + c], rgbe_value(uint8_t(texel[c]), uint8_t(texel[3])))
                    << x << ", " << y;
        }
}

TEST(ImageCodecs, DamagedFilesAreErrorsSayingWhere) {
    TempDir dir("image_codecs_test");
    auto error_of = [&](const std::string& bytes) {
        write_bytes(dir.file("bad.hdr"), bytes);
        auto read = our_read(dir.file("bad.hdr"));
        return read ? std::string("no error") : read.error().message;
    };
    const std::string h16 = rgbe_header(16, 1);
    EXPECT_EQ(error_of(h16 + std::string{2, 2, 0, 17}), "row 0 of 1: it declares width 17, not the header's 16");
    EXPECT_EQ(error_of(h16 + std::string{2, 2, 0, 16, 0, 5}), "row 0 of 1: a span of 0 at texel 0 of component 0 (width 16)");
    EXPECT_EQ(error_of(h16 + std::string{2, 2, 0, 16, char(128 + 10), 5, char(128 + 7), 5}),
              "row 0 of 1: a run of 7 at texel 10 of component 0 (width 16)");
    EXPECT_EQ(error_of(rgbe_header(4, 1) + std::string{1, 1, 1, 2}), "row 0 of 1: a repeat of 2 texels at texel 0 (width 4)");
    EXPECT_EQ(error_of(rgbe_header(4, 1) + std::string{9, 9, 9, 9, 1, 1, 1, 4}),
              "row 0 of 1: a repeat of 4 texels at texel 1 (width 4)");
    EXPECT_EQ(error_of("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n"), "the Radiance header is cut short (no blank line ends it)");
    EXPECT_EQ(error_of("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n"),
              "the Radiance header ends before its size line (-Y height +X width)");

    // A file we wrote, cut anywhere past its header: the row it ends in is named.
    std::vector<float> rgba(size_t(1023) * 17 * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = float(i % 97) * 0.01f;
    ASSERT_TRUE(write_hdr_image(dir.file("whole.hdr"), 1023, 17, rgba));
    const std::string whole = read_file(dir.file("whole.hdr"));
    const size_t header = rgbe_header(1023, 17).size();
    for (size_t cut = header; cut < whole.size(); cut += (whole.size() - header) / 37) {
        const std::string message = error_of(whole.substr(0, cut));
        EXPECT_EQ(message.rfind("row ", 0), 0u) << message;
        EXPECT_NE(message.find("cut short (the file ends)"), std::string::npos) << message;
    }
    // Garbage after a good header: an error or some texels, never a crash or a hang.
    std::mt19937 random(5);
    for (int i = 0; i < 300; ++i) {
        std::string bytes = rgbe_header(16, 8);
        const size_t n = random() % 400;
        for (size_t k = 0; k < n; ++k) bytes += char(i % 2 ? random() : random() % 4);  // small bytes: markers
        (void)error_of(bytes);
    }

    // Through load_environment, in the messages the image module's reading gives.
    write_bytes(dir.file("cut.hdr"), whole.substr(0, whole.size() / 2));
    auto cut = load_environment(dir.file("cut.hdr"));
    ASSERT_FALSE(cut);
    EXPECT_EQ(cut.error().message.rfind(dir.file("cut.hdr") + ": the image data is damaged or truncated: row ", 0), 0u)
        << cut.error().message;
    write_bytes(dir.file("headless.hdr"), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n");
    auto headless = load_environment(dir.file("headless.hdr"));
    ASSERT_FALSE(headless);
    EXPECT_EQ(headless.error().message, dir.file("headless.hdr") +
                                            ": cannot read the image: the Radiance header ends before its size line "
                                            "(-Y height +X width)");
}

// Files this reader does not take are declined (load_environment gives them to the image
// module, which reads them as before).
TEST(ImageCodecs, ReaderDeclinesWhatItDoesNotTake) {
    TempDir dir("image_codecs_test");
    const std::string texels(4 * 2 * 4, char(100));
    const std::string declined[] = {
        "this is not an image\n",
        std::string("\x76\x2f\x31\x01", 4) + "an EXR",
        "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 4\n" + texels,
        "#?RADIANCE\n\n-Y 2 +X 4\n" + texels,  // no FORMAT
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 2 +X 4\n" + texels,
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2  +X 4\n" + texels,
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 4\n" + texels,
        "#?PHOTOSHOP\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n" + texels,
    };
    for (const std::string& bytes : declined) {
        write_bytes(dir.file("x.hdr"), bytes);
        auto opened = codec::RgbeReader::open(dir.file("x.hdr"));
        ASSERT_TRUE(opened) << opened.error().message;
        EXPECT_FALSE(*opened) << bytes.substr(0, 40);
    }
    write_bytes(dir.file("x.hdr"), "#?RGBE\n# a comment\nEXPOSURE=2\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n" + texels);
    auto opened = codec::RgbeReader::open(dir.file("x.hdr"));
    ASSERT_TRUE(opened && *opened);
    EXPECT_EQ((*opened)->width(), 4u);
    EXPECT_EQ((*opened)->height(), 2u);
}

bool image_module_loaded() {
    std::ifstream maps("/proc/self/maps");
    std::string text((std::istreambuf_iterator<char>(maps)), {});
    return text.find("libfacet_image_io") != std::string::npos;
}

// Run in a process of its own (gtest's "threadsafe" death tests start the test anew), so
// that nothing else in this executable loaded the module first: 0 when it stayed unloaded.
int load_hdr_and_write_every_format() {
    TempDir dir("image_codecs_test");
    auto env = load_environment(std::string(FACET_SHARED_DATA_DIR) + "/env/royal_esplanade_1k.hdr", {false, 512});
    if (!env) return 2;
    write_bytes(dir.file("huge.hdr"), rgbe_header(200000, 100000));
    auto huge = load_environment(dir.file("huge.hdr"));
    if (huge || huge.error().message.find("refused before reading it") == std::string::npos) return 3;
    std::vector<uint8_t> ldr(env->rgba.size(), 128);
    if (!write_hdr_image(dir.file("e.exr"), env->width, env->height, env->rgba) ||
        !write_hdr_image(dir.file("e.hdr"), env->width, env->height, env->rgba) ||
        !write_ldr_image(dir.file("e.png"), env->width, env->height, ldr))
        return 4;
    return image_module_loaded() ? 1 : 0;
}

// The control: 7 when reading an EXR (through the module) shows the module loaded.
int load_exr() {
    TempDir dir("image_codecs_test");
    const std::vector<float> rgba(8 * 4, 1.0f);
    const bool read = write_hdr_image(dir.file("e.exr"), 4, 2, rgba) && load_environment(dir.file("e.exr"));
    return read && image_module_loaded() ? 7 : 0;
}

TEST(ImageCodecs, ReadingHdrAndWritingLoadNoImageModule) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(std::exit(load_hdr_and_write_every_format()), testing::ExitedWithCode(0), "");
    // The check sees the module once something loads it.
    EXPECT_EXIT(std::exit(load_exr()), testing::ExitedWithCode(7), "");
}

}  // namespace
}  // namespace facet
