// KTX 2.0 writer/reader: round trips, byte layout checked against values worked out by
// hand from the KTX 2.0 and Khronos Data Format specifications, and rejection of bad files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include <facet/io/ktx2.h>

namespace fs = std::filesystem;
using facet::Ktx2Image;

namespace {

class Ktx2Test : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("facet_ktx2_test_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    fs::path dir_;
};

std::vector<std::byte> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::byte> bytes(chars.size());
    std::memcpy(bytes.data(), chars.data(), chars.size());
    return bytes;
}

void write_bytes(const std::string& path, const std::vector<std::byte>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

uint32_t le32(const std::vector<std::byte>& b, size_t at) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(b.at(at + i)) << (8 * i);
    return v;
}
uint64_t le64(const std::vector<std::byte>& b, size_t at) { return le32(b, at) | (uint64_t{le32(b, at + 4)} << 32); }
void put32(std::vector<std::byte>& b, size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) b.at(at + i) = std::byte(v >> (8 * i));
}
void put64(std::vector<std::byte>& b, size_t at, uint64_t v) {
    put32(b, at, uint32_t(v));
    put32(b, at + 4, uint32_t(v >> 32));
}

// Distinct, recognisable texel bytes: every level/face/texel differs.
Ktx2Image make_image(VkFormat format, uint32_t width, uint32_t height, uint32_t faces, uint32_t levels) {
    Ktx2Image image;
    image.format = format;
    image.width = width;
    image.height = height;
    image.faces = faces;
    image.levels = levels;
    std::mt19937 rng(width * 131 + faces * 7 + levels);
    for (uint32_t l = 0; l < levels; ++l) {
        std::vector<std::byte> level(facet::ktx2_level_size(image, l));
        for (auto& b : level) b = std::byte(rng());
        image.level_data.push_back(std::move(level));
    }
    image.key_values = {{"KTXwriter", "facet 0.1.0"}};
    return image;
}

void expect_same(const Ktx2Image& a, const Ktx2Image& b) {
    EXPECT_EQ(a.format, b.format);
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.faces, b.faces);
    EXPECT_EQ(a.levels, b.levels);
    ASSERT_EQ(a.level_data.size(), b.level_data.size());
    for (size_t l = 0; l < a.level_data.size(); ++l) EXPECT_TRUE(a.level_data[l] == b.level_data[l]) << "level " << l;
    EXPECT_EQ(a.key_values, b.key_values);
}

constexpr size_t kLevelIndex = 80;  // 48-byte header + 32-byte index

}  // namespace

TEST_F(Ktx2Test, RoundTripRg16fLut) {
    Ktx2Image lut = make_image(VK_FORMAT_R16G16_SFLOAT, 32, 32, 1, 1);
    auto* halves = reinterpret_cast<uint16_t*>(lut.level_data[0].data());
    for (size_t i = 0; i < 32 * 32 * 2; ++i) halves[i] = facet::float_to_half(float(i) / 2048.0f);
    ASSERT_TRUE(facet::write_ktx2(path("lut.ktx2"), lut).ok());
    auto back = facet::read_ktx2(path("lut.ktx2"));
    ASSERT_TRUE(back.ok()) << back.error().message;
    expect_same(lut, *back);
}

TEST_F(Ktx2Test, RoundTripRgba16fCubeFullMipChain) {
    Ktx2Image cube = make_image(VK_FORMAT_R16G16B16A16_SFLOAT, 16, 16, 6, 5);
    ASSERT_TRUE(facet::write_ktx2(path("specular.ktx2"), cube).ok());
    auto back = facet::read_ktx2(path("specular.ktx2"));
    ASSERT_TRUE(back.ok()) << back.error().message;
    expect_same(cube, *back);
}

TEST_F(Ktx2Test, RoundTripRgba32fCubeAndRg32f) {
    Ktx2Image cube = make_image(VK_FORMAT_R32G32B32A32_SFLOAT, 8, 8, 6, 4);
    ASSERT_TRUE(facet::write_ktx2(path("cube32.ktx2"), cube).ok());
    auto back = facet::read_ktx2(path("cube32.ktx2"));
    ASSERT_TRUE(back.ok()) << back.error().message;
    expect_same(cube, *back);

    Ktx2Image rg = make_image(VK_FORMAT_R32G32_SFLOAT, 5, 3, 1, 3);  // non-square, odd sizes
    rg.key_values.clear();
    ASSERT_TRUE(facet::write_ktx2(path("rg32.ktx2"), rg).ok());
    auto rg_back = facet::read_ktx2(path("rg32.ktx2"));
    ASSERT_TRUE(rg_back.ok()) << rg_back.error().message;
    expect_same(rg, *rg_back);
}

TEST_F(Ktx2Test, HeaderIndexAndLevelLayout) {
    Ktx2Image cube = make_image(VK_FORMAT_R16G16B16A16_SFLOAT, 16, 16, 6, 5);
    cube.key_values = {{"zz", "1"}, {"KTXwriter", "facet 0.1.0"}, {"KTXorientation", "rd"}};
    ASSERT_TRUE(facet::write_ktx2(path("c.ktx2"), cube).ok());
    auto b = read_bytes(path("c.ktx2"));

    const unsigned char id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    for (int i = 0; i < 12; ++i) EXPECT_EQ(uint8_t(b[i]), id[i]) << "identifier byte " << i;
    EXPECT_EQ(le32(b, 12), 97u);  // VK_FORMAT_R16G16B16A16_SFLOAT
    EXPECT_EQ(le32(b, 16), 2u);   // typeSize
    EXPECT_EQ(le32(b, 20), 16u);
    EXPECT_EQ(le32(b, 24), 16u);
    EXPECT_EQ(le32(b, 28), 0u);  // pixelDepth
    EXPECT_EQ(le32(b, 32), 0u);  // layerCount
    EXPECT_EQ(le32(b, 36), 6u);
    EXPECT_EQ(le32(b, 40), 5u);
    EXPECT_EQ(le32(b, 44), 0u);  // no supercompression

    const uint32_t dfd_offset = 80 + 5 * 24, dfd_length = 4 + 24 + 4 * 16;
    EXPECT_EQ(le32(b, 48), dfd_offset);
    EXPECT_EQ(le32(b, 52), dfd_length);
    // Entries sorted by key bytes: "KTXorientation" < "KTXwriter" < "zz".
    // 4 + "KTXorientation\0rd\0" (18) -> 22 -> 24; 4 + "KTXwriter\0facet 0.1.0\0" (22) -> 26 -> 28;
    // 4 + "zz\0" "1\0" (5) -> 9 -> 12.
    const uint32_t kvd_offset = dfd_offset + dfd_length;
    EXPECT_EQ(le32(b, 56), kvd_offset);
    EXPECT_EQ(le32(b, 60), 24u + 28u + 12u);
    EXPECT_EQ(le32(b, kvd_offset), 18u);
    EXPECT_EQ(std::memcmp(&b[kvd_offset + 4], "KTXorientation\0rd\0", 18), 0);
    EXPECT_EQ(le32(b, kvd_offset + 24), 22u);
    EXPECT_EQ(std::memcmp(&b[kvd_offset + 28], "KTXwriter\0facet 0.1.0\0", 22), 0);
    EXPECT_EQ(le32(b, kvd_offset + 52), 5u);
    EXPECT_EQ(std::memcmp(&b[kvd_offset + 56], "zz\0" "1\0", 5), 0);
    EXPECT_EQ(le64(b, 64), 0u);  // sgdByteOffset
    EXPECT_EQ(le64(b, 72), 0u);  // sgdByteLength

    // Level 4 (1x1) first in the file, level 0 last; offsets multiples of lcm(8, 4) = 8.
    uint64_t expected_offset = kvd_offset + 64;
    for (int l = 4; l >= 0; --l) {
        size_t entry = kLevelIndex + 24 * size_t(l);
        uint64_t side = 16u >> l;
        uint64_t length = 6 * side * side * 8;
        expected_offset = (expected_offset + 7) / 8 * 8;
        EXPECT_EQ(le64(b, entry), expected_offset) << "level " << l;
        EXPECT_EQ(le64(b, entry) % 8, 0u);
        EXPECT_EQ(le64(b, entry + 8), length);
        EXPECT_EQ(le64(b, entry + 16), length);
        EXPECT_EQ(std::memcmp(&b[le64(b, entry)], cube.level_data[l].data(), length), 0);
        expected_offset += length;
    }
    EXPECT_EQ(expected_offset, b.size());
    // The bytes of a cube level are face-major: face 1 of level 0 starts 16*16 texels in.
    EXPECT_EQ(std::memcmp(&b[le64(b, kLevelIndex) + 16 * 16 * 8], &cube.level_data[0][16 * 16 * 8], 8), 0);
}

TEST_F(Ktx2Test, Rgba32fLevelsAlignedTo16) {
    Ktx2Image cube = make_image(VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4, 6, 3);
    cube.key_values = {{"a", ""}};  // 4 + "a\0\0" -> 7 -> 8 bytes
    ASSERT_TRUE(facet::write_ktx2(path("c.ktx2"), cube).ok());
    auto b = read_bytes(path("c.ktx2"));
    EXPECT_EQ(le32(b, 16), 4u);  // typeSize
    // DFD at 80 + 3*24 = 152, 4 + 24 + 4*16 = 92 bytes; kvd 244..252; 252 rounds up to 256.
    EXPECT_EQ(le32(b, 56), 244u);
    EXPECT_EQ(le32(b, 60), 8u);
    EXPECT_EQ(le64(b, kLevelIndex + 2 * 24), 256u);
    for (int l = 0; l < 3; ++l) EXPECT_EQ(le64(b, kLevelIndex + 24 * size_t(l)) % 16, 0u) << "level " << l;
    EXPECT_LT(le64(b, kLevelIndex + 2 * 24), le64(b, kLevelIndex + 24));
    EXPECT_LT(le64(b, kLevelIndex + 24), le64(b, kLevelIndex));
}

// Khronos Basic Data Format Descriptor for R16G16B16A16_SFLOAT, each word worked out
// from the Data Format Specification 1.3 layout.
TEST_F(Ktx2Test, DfdForRgba16fFieldByField) {
    ASSERT_TRUE(facet::write_ktx2(path("d.ktx2"), make_image(VK_FORMAT_R16G16B16A16_SFLOAT, 2, 2, 1, 1)).ok());
    auto b = read_bytes(path("d.ktx2"));
    size_t d = le32(b, 48);
    ASSERT_EQ(le32(b, 52), 92u);
    EXPECT_EQ(le32(b, d + 0), 92u);           // dfdTotalSize
    EXPECT_EQ(le32(b, d + 4), 0u);            // vendorId 0 (Khronos), descriptorType 0 (basic)
    EXPECT_EQ(le32(b, d + 8), 0x00580002u);   // versionNumber 2 (1.3), descriptorBlockSize 24 + 4*16 = 88
    EXPECT_EQ(le32(b, d + 12), 0x00010101u);  // model RGBSDA 1, primaries BT709 1, transfer LINEAR 1, flags 0
    EXPECT_EQ(le32(b, d + 16), 0u);           // texelBlockDimension0..3 = 1 (stored minus one)
    EXPECT_EQ(le32(b, d + 20), 8u);           // bytesPlane0 = 8, planes 1..3 = 0
    EXPECT_EQ(le32(b, d + 24), 0u);           // bytesPlane4..7
    // bitOffset (16 bits) | bitLength-1 (8 bits) | channelType = id | FLOAT 0x80 | SIGNED 0x40.
    const uint32_t sample_word0[4] = {0xC00F0000u, 0xC10F0010u, 0xC20F0020u, 0xCF0F0030u};
    for (size_t s = 0; s < 4; ++s) {
        size_t at = d + 28 + 16 * s;
        EXPECT_EQ(le32(b, at + 0), sample_word0[s]) << "sample " << s;
        EXPECT_EQ(le32(b, at + 4), 0u) << "samplePosition";
        EXPECT_EQ(le32(b, at + 8), 0xBF800000u) << "sampleLower = -1.0f";
        EXPECT_EQ(le32(b, at + 12), 0x3F800000u) << "sampleUpper = 1.0f";
    }
}

TEST(HalfFloat, KnownValues) {
    using facet::float_to_half;
    EXPECT_EQ(float_to_half(1.0f), 0x3C00);
    EXPECT_EQ(float_to_half(-2.0f), 0xC000);
    EXPECT_EQ(float_to_half(0.0f), 0x0000);
    EXPECT_EQ(float_to_half(-0.0f), 0x8000);
    EXPECT_EQ(float_to_half(65504.0f), 0x7BFF);
    EXPECT_EQ(float_to_half(std::ldexp(1.0f, -24)), 0x0001);  // smallest denormal
    EXPECT_EQ(float_to_half(std::ldexp(1.0f, -14)), 0x0400);  // smallest normal
    EXPECT_EQ(float_to_half(std::ldexp(1023.0f, -24)), 0x03FF);
    EXPECT_EQ(float_to_half(65520.0f), 0x7C00);  // tie between 65504 and 2^16: to even, inf
    EXPECT_EQ(float_to_half(65519.996f), 0x7BFF);
    EXPECT_EQ(float_to_half(1e6f), 0x7C00);
    EXPECT_EQ(float_to_half(-1e6f), 0xFC00);
    EXPECT_EQ(float_to_half(std::numeric_limits<float>::infinity()), 0x7C00);
    EXPECT_EQ(float_to_half(-std::numeric_limits<float>::infinity()), 0xFC00);
    uint16_t nan = float_to_half(std::numeric_limits<float>::quiet_NaN());
    EXPECT_EQ(nan & 0x7C00, 0x7C00);
    EXPECT_NE(nan & 0x03FF, 0);
    // Round to nearest even: 1 + 2^-11 is halfway between 1 and 1 + 2^-10.
    EXPECT_EQ(float_to_half(1.0f + std::ldexp(1.0f, -11)), 0x3C00);
    EXPECT_EQ(float_to_half(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3C02);
    EXPECT_EQ(float_to_half(1.0f + std::ldexp(1.0f, -11) + std::ldexp(1.0f, -20)), 0x3C01);
    // Denormal ties: 2^-25 is half the smallest denormal (to 0), 3 * 2^-25 goes to 2 * 2^-24.
    EXPECT_EQ(float_to_half(std::ldexp(1.0f, -25)), 0x0000);
    EXPECT_EQ(float_to_half(std::ldexp(1.0f, -25) * 1.0000001f), 0x0001);
    EXPECT_EQ(float_to_half(std::ldexp(3.0f, -25)), 0x0002);
    EXPECT_EQ(float_to_half(std::ldexp(1.0f, -40)), 0x0000);  // underflow keeps sign
    EXPECT_EQ(float_to_half(-std::ldexp(1.0f, -40)), 0x8000);
    EXPECT_EQ(float_to_half(std::numeric_limits<float>::denorm_min()), 0x0000);
    // Rounding up out of the largest denormal gives the smallest normal.
    EXPECT_EQ(float_to_half(std::ldexp(1023.75f, -24)), 0x0400);

    EXPECT_EQ(facet::half_to_float(0x3C00), 1.0f);
    EXPECT_EQ(facet::half_to_float(0x7BFF), 65504.0f);
    EXPECT_EQ(facet::half_to_float(0x0001), std::ldexp(1.0f, -24));
    EXPECT_EQ(facet::half_to_float(0xFC00), -std::numeric_limits<float>::infinity());
    EXPECT_TRUE(std::signbit(facet::half_to_float(0x8000)));
}

TEST(HalfFloat, AllHalvesRoundTripExactly) {
    for (uint32_t h = 0; h <= 0xFFFF; ++h) {
        float f = facet::half_to_float(uint16_t(h));
        bool is_nan = (h & 0x7C00) == 0x7C00 && (h & 0x03FF) != 0;
        if (is_nan) {
            EXPECT_TRUE(std::isnan(f)) << std::hex << h;
            uint16_t back = facet::float_to_half(f);
            EXPECT_TRUE((back & 0x7C00) == 0x7C00 && (back & 0x03FF) != 0) << std::hex << h;
            continue;
        }
        ASSERT_EQ(facet::float_to_half(f), h) << std::hex << h;
        // Midpoints to the next half up must round to the even one of the two.
        if ((h & 0x7FFF) < 0x7BFF) {
            float next = facet::half_to_float(uint16_t(h + 1));
            float mid = (f + next) * 0.5f;  // exact: one bit more than a half's precision
            uint16_t even = (h & 1) ? uint16_t(h + 1) : uint16_t(h);
            ASSERT_EQ(facet::float_to_half(mid), even) << std::hex << h;
        }
    }
}

// --- rejection of bad input: every error names the file ---------------------------------

namespace {
void expect_rejected(const std::string& path, const std::string& reason) {
    auto result = facet::read_ktx2(path);
    ASSERT_FALSE(result.ok()) << "accepted " << path;
    EXPECT_NE(result.error().message.find(path), std::string::npos) << result.error().message;
    EXPECT_NE(result.error().message.find(reason), std::string::npos) << result.error().message;
}
}  // namespace

TEST_F(Ktx2Test, RejectsWrongIdentifierEmptyAndMissing) {
    ASSERT_TRUE(facet::write_ktx2(path("a.ktx2"), make_image(VK_FORMAT_R16G16_SFLOAT, 4, 4, 1, 3)).ok());
    auto b = read_bytes(path("a.ktx2"));
    b[5] = std::byte{'1'};  // "KTX 10"
    write_bytes(path("bad.ktx2"), b);
    expect_rejected(path("bad.ktx2"), "identifier");
    write_bytes(path("empty.ktx2"), {});
    expect_rejected(path("empty.ktx2"), "too short");
    expect_rejected(path("missing.ktx2"), "cannot open");
}

TEST_F(Ktx2Test, RejectsTruncatedFilesAtEveryLength) {
    Ktx2Image cube = make_image(VK_FORMAT_R16G16B16A16_SFLOAT, 4, 4, 6, 3);
    ASSERT_TRUE(facet::write_ktx2(path("c.ktx2"), cube).ok());
    auto b = read_bytes(path("c.ktx2"));
    for (size_t length = 0; length < b.size(); ++length) {
        write_bytes(path("t.ktx2"), std::vector<std::byte>(b.begin(), b.begin() + std::ptrdiff_t(length)));
        expect_rejected(path("t.ktx2"), "");
    }
}

TEST_F(Ktx2Test, RejectsInconsistentFields) {
    Ktx2Image image = make_image(VK_FORMAT_R16G16B16A16_SFLOAT, 8, 8, 6, 2);
    ASSERT_TRUE(facet::write_ktx2(path("c.ktx2"), image).ok());
    const auto good = read_bytes(path("c.ktx2"));
    auto patched = [&](auto&& patch, const std::string& reason) {
        auto b = good;
        patch(b);
        write_bytes(path("p.ktx2"), b);
        expect_rejected(path("p.ktx2"), reason);
    };
    patched([](auto& b) { put64(b, kLevelIndex + 8, le64(b, kLevelIndex + 8) + 8); }, "byte length");
    patched([](auto& b) { put64(b, kLevelIndex + 16, 1); }, "byte length");
    patched([&](auto& b) { put64(b, kLevelIndex, good.size()); }, "outside the file");
    patched([](auto& b) { put64(b, kLevelIndex, ~uint64_t{0} - 4); }, "outside the file");
    patched([](auto& b) { put64(b, kLevelIndex, le64(b, kLevelIndex) - 4); }, "aligned");
    patched([](auto& b) { put32(b, 12, 37); }, "unsupported vkFormat");  // R8G8B8A8_UNORM
    patched([](auto& b) { put32(b, 16, 4); }, "typeSize");
    patched([](auto& b) { put32(b, 20, 16); }, "square");
    patched([](auto& b) { put32(b, 36, 2); }, "faceCount");
    patched([](auto& b) { put32(b, 40, 5); }, "levelCount");
    patched([](auto& b) { put32(b, 44, 2); }, "supercompression");
    patched([](auto& b) { put32(b, 28, 4); }, "3D");
    patched([](auto& b) { put32(b, 32, 2); }, "array");
    patched([&](auto& b) { put32(b, 48, uint32_t(good.size()) - 8); }, "outside the file");
    patched([](auto& b) { put32(b, le32(b, 48), 80); }, "total size");
    patched([](auto& b) { put32(b, le32(b, 56), 4000); }, "key/value");
    patched([](auto& b) { put64(b, 72, 16); }, "global data");
}

TEST_F(Ktx2Test, LevelCountZeroMeansOneLevel) {
    ASSERT_TRUE(facet::write_ktx2(path("z.ktx2"), make_image(VK_FORMAT_R16G16_SFLOAT, 4, 4, 1, 1)).ok());
    auto b = read_bytes(path("z.ktx2"));
    put32(b, 40, 0);
    write_bytes(path("z.ktx2"), b);
    auto image = facet::read_ktx2(path("z.ktx2"));
    ASSERT_TRUE(image.ok()) << image.error().message;
    EXPECT_EQ(image->levels, 1u);
}

TEST_F(Ktx2Test, RandomAndCorruptedBytesNeverCrash) {
    std::mt19937 rng(20240611);
    ASSERT_TRUE(facet::write_ktx2(path("c.ktx2"), make_image(VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4, 6, 3)).ok());
    const auto good = read_bytes(path("c.ktx2"));
    for (int trial = 0; trial < 400; ++trial) {
        std::vector<std::byte> b;
        if (trial % 2 == 0) {
            b.resize(rng() % 1500);
            for (auto& x : b) x = std::byte(rng());
            if (trial % 4 == 0 && b.size() >= 12) std::memcpy(b.data(), good.data(), 12);  // get past the identifier
        } else {
            b = good;
            for (int flips = 1 + int(rng() % 8); flips-- > 0;) b[12 + rng() % (b.size() - 12)] = std::byte(rng());
        }
        write_bytes(path("r.ktx2"), b);
        auto result = facet::read_ktx2(path("r.ktx2"));
        if (!result.ok()) {
            EXPECT_NE(result.error().message.find(path("r.ktx2")), std::string::npos);
        }
    }
}

// --- writer errors ----------------------------------------------------------------------

TEST_F(Ktx2Test, UnwritablePathGivesErrorAndNoFile) {
    Ktx2Image image = make_image(VK_FORMAT_R16G16_SFLOAT, 4, 4, 1, 1);
    std::string nowhere = path("no/such/dir/lut.ktx2");
    auto status = facet::write_ktx2(nowhere, image);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find(nowhere), std::string::npos) << status.error().message;
    EXPECT_FALSE(fs::exists(nowhere));

    fs::create_directory(path("taken.ktx2"));  // the target name is a directory: the rename fails
    status = facet::write_ktx2(path("taken.ktx2"), image);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find(path("taken.ktx2")), std::string::npos) << status.error().message;
    EXPECT_TRUE(fs::is_directory(path("taken.ktx2")));
    for (const auto& entry : fs::directory_iterator(dir_))
        EXPECT_EQ(entry.path().filename().string().find("partial"), std::string::npos) << entry.path();
}

TEST_F(Ktx2Test, WriterRejectsInvalidImages) {
    auto expect_refused = [&](Ktx2Image image, const std::string& reason) {
        auto status = facet::write_ktx2(path("w.ktx2"), image);
        ASSERT_FALSE(status.ok()) << reason;
        EXPECT_NE(status.error().message.find(path("w.ktx2")), std::string::npos) << status.error().message;
        EXPECT_NE(status.error().message.find(reason), std::string::npos) << status.error().message;
        EXPECT_FALSE(fs::exists(path("w.ktx2")));
    };
    Ktx2Image good = make_image(VK_FORMAT_R16G16B16A16_SFLOAT, 8, 8, 6, 2);
    Ktx2Image bad = good;
    bad.level_data[1].pop_back();
    expect_refused(bad, "level 1");
    bad = good;
    bad.format = VK_FORMAT_R8G8B8A8_UNORM;
    expect_refused(bad, "unsupported");
    bad = make_image(VK_FORMAT_R16G16B16A16_SFLOAT, 8, 4, 1, 1);
    bad.faces = 6;
    expect_refused(bad, "square");
    bad = good;
    bad.levels = 5;
    expect_refused(bad, "level count");
    bad = good;
    bad.key_values.push_back({"KTXwriter", "twice"});
    expect_refused(bad, "twice");
}
