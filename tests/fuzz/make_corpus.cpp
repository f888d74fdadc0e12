// fuzz_make_corpus DIR: writes the seed corpora of every fuzz target into DIR/<target>
// (make_corpus.h). The committed corpus is its output; run it again after changing it.
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <utility>

#include <facet/io/image_io.h>
#include <facet/io/ktx2.h>
#include "make_corpus.h"

namespace facet::fuzz {

namespace fs = std::filesystem;

namespace {

fs::path scratch() {
    static const fs::path dir = [] {
        fs::path d = fs::temp_directory_path() / ("facet-make-corpus-" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

void require(bool ok, const std::string& what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_make_corpus: %s\n", what.c_str());
    std::exit(1);
}

// A small file through OpenImageIO, as bytes.
ByteVector image_file(const std::string& name, int width, int height, int channels, OIIO::TypeDesc type,
                      const std::string& compression, const std::vector<float>& texels, bool tiled = false) {
    const fs::path path = scratch() / name;
    OIIO::ImageSpec spec(width, height, channels, type);
    if (!compression.empty()) spec.attribute("compression", compression);
    if (tiled) spec.tile_width = spec.tile_height = 8;
    auto out = OIIO::ImageOutput::create(path.string());
    require(out && out->open(path.string(), spec) &&
                out->write_image(OIIO::TypeDesc::FLOAT, texels.data()) && out->close(),
            name + ": " + OIIO::geterror());
    return read_bytes(path);
}

std::vector<float> gradient(int width, int height, int channels) {
    std::vector<float> texels(size_t(width) * height * channels);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = float(i % 97) * 0.25f;
    return texels;
}

ByteVector with_header(const std::string& header, const ByteVector& body) {
    ByteVector out(header.begin(), header.end());
    out.insert(out.end(), body.begin(), body.end());
    return out;
}

ByteVector first_half(const ByteVector& bytes) { return ByteVector(bytes.begin(), bytes.begin() + bytes.size() / 2); }

void make_environment_corpus(const fs::path& dir) {
    const OIIO::TypeDesc f32 = OIIO::TypeDesc::FLOAT, f16 = OIIO::TypeDesc::HALF, u8 = OIIO::TypeDesc::UINT8;
    const ByteVector rle_hdr = image_file("rle.hdr", 16, 8, 3, f32, "", gradient(16, 8, 3));
    write_seed(dir, "rle_16x8.hdr", rle_hdr);
    write_seed(dir, "flat_4x2.hdr", image_file("flat.hdr", 4, 2, 3, f32, "", gradient(4, 2, 3)));
    const ByteVector zip_exr = image_file("zip.exr", 16, 8, 4, f32, "zip", gradient(16, 8, 4));
    write_seed(dir, "zip_16x8.exr", zip_exr);
    write_seed(dir, "half_piz_8x4.exr", image_file("piz.exr", 8, 4, 3, f16, "piz", gradient(8, 4, 3)));
    write_seed(dir, "grey_rle_8x4.exr", image_file("grey.exr", 8, 4, 1, f16, "rle", gradient(8, 4, 1)));
    write_seed(dir, "tiled_16x8.exr", image_file("tiled.exr", 16, 8, 4, f16, "none", gradient(16, 8, 4), true));
    const ByteVector png = image_file("rgba.png", 8, 4, 4, u8, "", std::vector<float>(8 * 4 * 4, 0.5f));
    write_seed(dir, "rgba_8x4.png", png);
    write_seed(dir, "grey16_8x4.png", image_file("grey16.png", 8, 4, 1, OIIO::TypeDesc::UINT16, "", gradient(8, 4, 1)));

    std::vector<float> bad = gradient(4, 2, 4);
    bad[5] = std::numeric_limits<float>::quiet_NaN();
    write_seed(dir, "bad_nan_texel.exr", image_file("nan.exr", 4, 2, 4, f32, "none", bad));
    bad[5] = -1.0f;
    write_seed(dir, "bad_negative_texel.exr", image_file("negative.exr", 4, 2, 4, f16, "zip", bad));
    bad[5] = INFINITY;
    write_seed(dir, "bad_inf_texel.exr", image_file("inf.exr", 4, 2, 4, f32, "rle", bad));
    write_seed(dir, "bad_two_channels.exr", image_file("two.exr", 4, 2, 2, f32, "none", gradient(4, 2, 2)));
    write_seed(dir, "bad_zero_height.hdr", with_header("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 16\n", {}));
    write_seed(dir, "bad_huge_size.hdr", with_header("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 60000 +X 90000\n",
                                                     ByteVector(64, 0x80)));
    write_seed(dir, "bad_truncated.hdr", first_half(rle_hdr));
    write_seed(dir, "bad_truncated.exr", first_half(zip_exr));
    write_seed(dir, "bad_truncated.png", first_half(png));
    write_seed(dir, "bad_garbage.image", std::string("P6\n2 2\n255\n\x01\x02"));
}

ByteVector ktx2_file(const std::string& name, const Ktx2Image& image) {
    const fs::path path = scratch() / name;
    Status written = write_ktx2(path.string(), image);
    require(written.ok(), written.ok() ? "" : written.error().message);
    return read_bytes(path);
}

Ktx2Image ktx2_image(VkFormat format, uint32_t width, uint32_t height, uint32_t faces, uint32_t levels) {
    Ktx2Image image;
    image.format = format;
    image.width = width;
    image.height = height;
    image.faces = faces;
    image.levels = levels;
    for (uint32_t l = 0; l < levels; ++l) {
        image.level_data.emplace_back(ktx2_level_size(image, l));
        for (size_t i = 0; i < image.level_data.back().size(); ++i) image.level_data.back()[i] = std::byte(i * 7 + l);
    }
    return image;
}

void put32(ByteVector& bytes, size_t at, uint32_t value) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = uint8_t(value >> (8 * i));
}

void make_ktx2_corpus(const fs::path& dir) {
    Ktx2Image mips = ktx2_image(VK_FORMAT_R16G16B16A16_SFLOAT, 4, 4, 1, 3);
    mips.key_values = {{"KTXwriter", "facet fuzz seeds"}, {"a", "1"}, {"b", "2"}};
    const ByteVector two_d = ktx2_file("mips.ktx2", mips);
    write_seed(dir, "rgba16f_4x4_mips.ktx2", two_d);
    write_seed(dir, "rg16f_cube_2x2.ktx2", ktx2_file("cube.ktx2", ktx2_image(VK_FORMAT_R16G16_SFLOAT, 2, 2, 6, 2)));
    write_seed(dir, "rgba32f_1x1.ktx2", ktx2_file("one.ktx2", ktx2_image(VK_FORMAT_R32G32B32A32_SFLOAT, 1, 1, 1, 1)));
    write_seed(dir, "rg32f_8x2.ktx2", ktx2_file("rg.ktx2", ktx2_image(VK_FORMAT_R32G32_SFLOAT, 8, 2, 1, 4)));

    // Header fields (KTX 2.0 section 3): 12 identifier, 16 typeSize, 20 width, 24 height,
    // 36 faceCount, 40 levelCount, 44 supercompressionScheme, 48 dfd offset, 56 kvd
    // offset, 60 kvd length, 80 the level index (offset, length, uncompressed length).
    auto edited = [&](const char* name, size_t at, uint32_t value) {
        ByteVector bytes = two_d;
        put32(bytes, at, value);
        write_seed(dir, name, bytes);
    };
    edited("level_count_zero.ktx2", 40, 0);
    edited("bad_level_count.ktx2", 40, 9);
    edited("bad_huge_width.ktx2", 20, 1u << 20);
    edited("bad_zero_width.ktx2", 20, 0);
    edited("bad_faces.ktx2", 36, 6);
    edited("bad_supercompression.ktx2", 44, 1);
    edited("bad_type_size.ktx2", 16, 4);
    edited("bad_dfd_offset.ktx2", 48, 0xFFFFFFF0u);
    edited("bad_kvd_length.ktx2", 60, 0x7FFFFFFF);
    edited("bad_level_offset.ktx2", 80, 0xFFFFFF00u);
    edited("bad_level_unaligned.ktx2", 80, 0x102);
    edited("bad_level_length.ktx2", 88, 12345);
    ByteVector duplicate = two_d;  // key "b" renamed "a": two entries with one key
    for (size_t i = 0; i + 3 < duplicate.size(); ++i)
        if (duplicate[i] == 'b' && duplicate[i + 1] == 0 && duplicate[i + 2] == '2') duplicate[i] = 'a';
    write_seed(dir, "bad_duplicate_key.ktx2", duplicate);
    write_seed(dir, "bad_truncated.ktx2", first_half(two_d));
    write_seed(dir, "bad_identifier.ktx2", std::string("\xABKTX 11\xBB\r\n\x1A\n") + std::string(80, '\0'));
}

void make_cli_corpus(const fs::path& dir) {
    const std::pair<const char*, const char*> seeds[] = {
        {"bake_all", "facet-bake\nbuiltin:sky\n--out\nout/sky\n--irradiance\nsh9\n--sh9-no-window\n--specular\n"
                     "filtered\n--samples\n64\n--size\n32\n--levels\n4\n--irradiance-size\n8\n--lut-size\n16\n"
                     "--lut-samples\n32\n--brdf\nthesis\n--width\n64\n--exposure\n0.5\n--sanitize\n"
                     "--target-error\n0.02\n--roughness\n0.2,0.8\n--force\n--device\n0\n--validation\n--graph-dot\ng.dot"},
        {"bake_inline", "facet-bake\nenv.hdr\n--out=dir\n--irradiance=riemann\n--specular=mips"},
        {"bake_help", "facet-bake\n--help"},
        {"render_all", "facet-render\n--out\na.png\n--aov\nall\n--model\nbuiltin:sphere\n--env\nbuiltin:white\n"
                       "--width\n64\n--height\n32\n--camera\norbit:30,20,3\n--target\n0,0.5,0\n--fov\n60\n--exposure\n2\n"
                       "--tonemap\naces\n--gamma\n2.2\n--preset\ngold\n--light\ndirectional dir=-1,-1,-1 intensity=3\n"
                       "--light\npoint pos=1,2,3 intensity=100 range=5 color=1,0.5,0\n--light\n"
                       "spot pos=0,2,0 dir=0,-1,0 inner=10 outer=30\n--no-skybox\n--samples\n8\n--brdf\nthesis\n"
                       "--extract-lights\n--multiscatter\n--specular-dir\ndominant\n--ibl-intensity\n0.5\n"
                       "--env-width\n64\n--ibl-size\n16\n--ibl-samples\n32\n--sanitize\n--reference\n"
                       "--reference-noise\n0.05\n--reference-samples\n64\n--device\nlavapipe\n--validation"},
        {"render_gltf_camera", "facet-render\n--out=x.exr\n--camera=gltf\n--aov=D,F,G,normal\n--env=none"},
        {"viewer_script", "facet-viewer\n--model\nbuiltin:spheres\n--script\nview normal; size 64x32; tonemap none; "
                          "exposure 2; skybox off; preset copper; material 1,0,0,0.5,0.3,1,on; model builtin:sphere; "
                          "env builtin:white; frames 2; screenshot a.png\n--frames\n3\n--screenshot\nb.exr"},
        {"bench_bake", "facet-bench\nbake\nbuiltin:sky\nbuiltin:white\n--runs\n2\n--bake-args\n--size 16\n--csv\nb.csv"},
        {"bench_render", "facet-bench\nrender\n--model\nbuiltin:sphere\n--width\n32\n--height\n16\n--frames\n2\n"
                         "--light\ndirectional dir=0,-1,0"},
        {"bench_sweep", "facet-bench\nsweep\nbuiltin:sky\n--env-width\n64\n--runs\n1\n--stages\nlut\n--out\nbench"},
        {"light_spot", "light\nspot pos=0,1,0 dir=0,-1,0 inner=10 outer=30 color=1,0.5,0 intensity=100 range=5"},
        {"light_directional", "light\ndirectional dir=1e-3,-2e3,0.5"},
        {"views", "views\nnormal,,position,basecolor,metallic,roughness,occlusion,emissive,D,F,G,diffuse,specular,"
                  "irradiance,prefiltered,f0"},
        {"bad_unknown_option", "facet-render\n--out\na.png\n--bogus"},
        {"bad_missing_value", "facet-bake\nbuiltin:sky\n--out"},
        {"bad_numbers", "facet-render\n--out\na.png\n--width\n0\n--fov\nnan\n--exposure\n1e999\n--samples\n3"},
        {"bad_camera", "facet-render\n--out\na.png\n--camera\norbit:1,2,-3\n--target\n1,2"},
        {"bad_light", "light\nspot pos=0,1,0 dir=0,0,0 inner=40 outer=30"},
        {"bad_twice", "facet-bake\nenv.hdr\n--out\na\n--out\nb\n--flag=x"},
        {"bad_script", "facet-viewer\n--script\nsize 0x9999; material 1,2; frames -1; view bogus"},
        {"bad_bench", "facet-bench\nrender\nextra\n--runs\n0"},
    };
    for (const auto& [name, text] : seeds) write_seed(dir, name, std::string(text));
}

}  // namespace

void write_seed(const fs::path& dir, const std::string& name, const ByteVector& bytes) {
    std::ofstream out(dir / name, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    require(bool(out), (dir / name).string() + ": cannot write");
}

void write_seed(const fs::path& dir, const std::string& name, const std::string& text) {
    write_seed(dir, name, ByteVector(text.begin(), text.end()));
}

ByteVector read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return ByteVector((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

ByteVector png_bytes(uint32_t width, uint32_t height) {
    std::vector<uint8_t> texels(size_t(width) * height * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint8_t(i * 37);
    const fs::path path = scratch() / "texture.png";
    Status written = write_ldr_image(path.string(), width, height, texels);
    require(written.ok(), written.ok() ? "" : written.error().message);
    return read_bytes(path);
}

}  // namespace facet::fuzz

int main(int argc, char** argv) {
    using namespace facet::fuzz;
    if (argc != 2) {
        std::fprintf(stderr, "usage: fuzz_make_corpus DIR (tests/fuzz/corpus)\n");
        return 2;
    }
    const fs::path root = argv[1];
    const std::pair<const char*, void (*)(const fs::path&)> targets[] = {
        {"gltf", make_gltf_corpus}, {"environment", make_environment_corpus}, {"ktx2", make_ktx2_corpus},
        {"cli", make_cli_corpus}};
    for (const auto& [name, make] : targets) {
        fs::create_directories(root / name);
        make(root / name);
    }
    std::error_code ec;
    fs::remove_all(scratch(), ec);
    return 0;
}
