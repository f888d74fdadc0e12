// Very large models (README, "Large inputs"): a GLB of two million triangles generated
// here loads and renders within the memory budget; an 8192 x 8192 texture is
// downsampled while it is decoded, keeping its mean (in linear light) and its features;
// and models over a limit are refused from their headers and declared counts, with an
// error naming the file, what exceeds and the limit, before anything large is read.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <facet/scene/gltf_loader.h>
#include "support/sanitizers.h"
#include "support/large_models.h"
#include "support/measured_process.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_large_model_test_" + std::to_string(::getpid()) + "_" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

test::Measured render(const std::string& args) {
    return test::run_measured(std::string(FACET_RENDER_PATH) + " --env none --width 64 --height 48 --samples 1 " +
                              "--light 'directional dir=0,0,-1 intensity=3' " + args);
}

// The texture: a one-texel checkerboard of sRGB codes 200 and 40 (each 2 x 2 box holds
// two of each), with a 64 x 64 red patch at (1024, 6144).
constexpr uint32_t kTexture = 8192, kPatchX = 1024, kPatchY = 6144, kPatch = 64;

void write_large_texture(const std::string& path) {
    ASSERT_TRUE(test::write_png_rows(path, kTexture, kTexture, [](uint32_t y, std::vector<uint8_t>& rgb) {
        for (uint32_t x = 0; x < kTexture; ++x) {
            const bool patch = x >= kPatchX && x < kPatchX + kPatch && y >= kPatchY && y < kPatchY + kPatch;
            const uint8_t grey = (x + y) % 2 ? 200 : 40;
            rgb[x * 3] = patch ? 255 : grey;
            rgb[x * 3 + 1] = rgb[x * 3 + 2] = patch ? 0 : grey;
        }
    }));
}

double srgb_to_linear(double code) {
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST(LargeModel, TwoMillionTrianglesLoadAndRenderWithinTheBudget) {
    TempDir dir;
    const std::string glb = dir.file("grid.glb");
    ASSERT_TRUE(test::write_grid_glb(glb, 1000));  // 1002001 vertices, 2000000 triangles, 48 MB
    const std::string out = dir.file("grid.png");
    test::Measured r = render("--model " + glb + " --out " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("2000000 triangles"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(out));
    std::printf("facet-render of 2000000 triangles at 64x48: peak RSS %.0f MiB\n", r.peak_rss_mib());
    EXPECT_LT(r.peak_rss_mib(), 768 + facet::test::sanitizer_rss_slack_mib()) << "the budget stated in the README";
}

TEST(LargeModel, An8kTextureIsDownsampledWhileDecodedKeepingItsMeanAndFeatures) {
    TempDir dir;
    write_large_texture(dir.file("big.png"));
    test::write_textured_quad(dir.file("quad.gltf"), "quad.bin", "big.png");
    auto scene = load_gltf(dir.file("quad.gltf"));  // default: at most 4096 a side
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_EQ(scene->images.size(), 1u);
    const TextureImage& t = scene->images[0];
    EXPECT_EQ(t.source_width, kTexture);
    EXPECT_EQ(t.source_height, kTexture);
    ASSERT_EQ(t.width, 4096u);
    ASSERT_EQ(t.height, 4096u);
    // Base colour is sRGB: the mean is kept in linear light, to the output's 8-bit rounding.
    double mean = 0;
    for (size_t p = 0; p < size_t(t.width) * t.height; ++p) mean += srgb_to_linear(t.rgba[p * 4 + 1]);
    mean /= double(t.width) * t.height;
    const double patch_share = double(kPatch) * kPatch / (double(kTexture) * kTexture);
    const double expected = (1 - patch_share) * (srgb_to_linear(200) + srgb_to_linear(40)) / 2;
    EXPECT_NEAR(mean, expected, 0.004);
    auto at = [&](uint32_t x, uint32_t y, int c) { return int(t.rgba[(size_t(y) * t.width + x) * 4 + c]); };
    for (uint32_t y = kPatchY / 2; y < (kPatchY + kPatch) / 2; ++y)
        for (uint32_t x = kPatchX / 2; x < (kPatchX + kPatch) / 2; ++x) {
            ASSERT_EQ(at(x, y, 0), 255) << x << ", " << y;
            ASSERT_EQ(at(x, y, 1), 0) << x << ", " << y;
        }
    EXPECT_EQ(at(kPatchX / 2 - 1, kPatchY / 2, 0), at(kPatchX / 2 - 1, kPatchY / 2, 1)) << "grey left of the patch";
    EXPECT_EQ(at(kPatchX / 2, kPatchY / 2 - 1, 0), at(kPatchX / 2, kPatchY / 2 - 1, 1)) << "grey above the patch";
    EXPECT_EQ(t.rgba[3], 255);

    // facet-render decodes it row by row: its peak is far below the 256 MiB one whole
    // RGBA8 copy of the source would take, let alone stb_image's several. The baseline's
    // small texture is downsampled too, so that it takes the same path (the image module
    // and its libraries, which writing a PNG no longer loads).
    test::write_png_rows(dir.file("small.png"), 128, 128, [](uint32_t, std::vector<uint8_t>& rgb) {
        std::fill(rgb.begin(), rgb.end(), 128);
    });
    test::write_textured_quad(dir.file("small.gltf"), "small.bin", "small.png");
    test::Measured small = render("--model " + dir.file("small.gltf") + " --max-texture-size 64 --out " +
                                  dir.file("small_out.png"));
    ASSERT_EQ(small.status, 0) << small.output;
    test::Measured large = render("--model " + dir.file("quad.gltf") + " --max-texture-size 1024 --out " +
                                  dir.file("large_out.png"));
    ASSERT_EQ(large.status, 0) << large.output;
    EXPECT_NE(large.output.find("image 'big.png' 8192x8192 downsampled to 1024x1024"), std::string::npos)
        << large.output;
    std::printf("facet-render with a 128x128 texture kept at 64: peak RSS %.0f MiB; with an 8192x8192 one kept at "
                "1024: %.0f MiB\n",
                small.peak_rss_mib(), large.peak_rss_mib());
    EXPECT_LT(large.peak_rss_mib() - small.peak_rss_mib(), 64);
}

// Every kind of image above the limit takes the row-by-row path: baseline and
// progressive JPEG, grey + alpha and 16-bit PNG, each keeping its values and its alpha.
TEST(LargeModel, JpegAndOtherPngKindsAreDownsampledToo) {
    TempDir dir;
    struct Case {
        const char* name;
        int channels;
        OIIO::TypeDesc type;
        const char* attribute;
        std::array<int, 4> expected;  // RGBA codes after decoding
        int tolerance;
    };
    const Case cases[] = {
        {"baseline.jpg", 3, OIIO::TypeDesc::UINT8, nullptr, {128, 64, 32, 255}, 3},
        {"progressive.jpg", 3, OIIO::TypeDesc::UINT8, "jpeg:progressive", {128, 64, 32, 255}, 3},
        {"grey_alpha.png", 2, OIIO::TypeDesc::UINT8, nullptr, {128, 128, 128, 64}, 0},
        {"rgba16.png", 4, OIIO::TypeDesc::UINT16, nullptr, {128, 64, 32, 64}, 0},
    };
    for (const Case& c : cases) {
        const std::string path = dir.file(c.name);
        auto out = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(4200, 64, c.channels, c.type);
        spec.attribute("oiio:UnassociatedAlpha", 1);  // write the colour as given, not divided by alpha
        if (c.attribute) spec.attribute(c.attribute, 1);
        ASSERT_TRUE(out->open(path, spec));
        const float rgba[4] = {128 / 255.0f, 64 / 255.0f, 32 / 255.0f, 64 / 255.0f};
        const float grey_alpha[2] = {128 / 255.0f, 64 / 255.0f};
        std::vector<float> pixels;
        for (int p = 0; p < 4200 * 64; ++p)
            for (int k = 0; k < c.channels; ++k) pixels.push_back(c.channels == 2 ? grey_alpha[k] : rgba[k]);
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        out->close();
        test::write_textured_quad(dir.file("quad.gltf"), "quad.bin", c.name);
        auto scene = load_gltf(dir.file("quad.gltf"));
        ASSERT_TRUE(scene) << scene.error().message;
        const TextureImage& t = scene->images.at(0);
        EXPECT_EQ(t.width, 4096u) << c.name;
        EXPECT_EQ(t.height, 62u) << c.name;
        EXPECT_EQ(t.source_width, 4200u) << c.name;
        for (size_t p : {size_t(0), size_t(t.width) * t.height / 2 + 7, size_t(t.width) * t.height - 1})
            for (int k = 0; k < 4; ++k)
                EXPECT_NEAR(int(t.rgba[p * 4 + k]), c.expected[k], c.tolerance) << c.name << " texel " << p << " " << k;
    }
}

TEST(LargeModel, GeometryOverTheBudgetIsRefusedFromTheDeclaredCounts) {
    TempDir dir;
    ASSERT_TRUE(test::write_grid_glb(dir.file("grid.glb"), 16));  // 289 vertices, 512 triangles
    GltfLimits limits;
    limits.max_vertices = 288;
    auto few_vertices = load_gltf(dir.file("grid.glb"), limits);
    ASSERT_FALSE(few_vertices);
    EXPECT_NE(few_vertices.error().message.find(dir.file("grid.glb") +
                                                ": the scene's primitives have 289 vertices, more than the limit of 288"),
              std::string::npos)
        << few_vertices.error().message;
    limits = {};
    limits.max_indices = 1535;
    auto few_indices = load_gltf(dir.file("grid.glb"), limits);
    ASSERT_FALSE(few_indices);
    EXPECT_NE(few_indices.error().message.find("1536 list indices, more than the limit of 1535"),
              std::string::npos)
        << few_indices.error().message;
    limits = {};
    limits.max_file_bytes = 1000;
    auto few_bytes = load_gltf(dir.file("grid.glb"), limits);
    ASSERT_FALSE(few_bytes);
    EXPECT_NE(few_bytes.error().message.find("more than the limit of"), std::string::npos) << few_bytes.error().message;

    // A small file declaring 20 million vertices (its accessor would not even fit its
    // buffer): refused at the defaults before anything is converted.
    test::write_textured_quad(dir.file("forged.gltf"), "forged.bin", "none.png");
    std::ifstream in(dir.file("forged.gltf"));
    std::string json((std::istreambuf_iterator<char>(in)), {});
    const std::string count = R"("count": 4, "type": "VEC3")";
    ASSERT_NE(json.find(count), std::string::npos);
    json.replace(json.find(count), count.size(), R"("count": 20000000, "type": "VEC3")");
    std::ofstream(dir.file("forged.gltf")) << json;
    test::Measured r = render("--model " + dir.file("forged.gltf") + " --out " + dir.file("forged.png"));
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("facet-render: error: " + dir.file("forged.gltf") +
                            ": the scene's primitives have 20000000 vertices, more than the limit of 16777216"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir.file("forged.png")));
    EXPECT_LT(r.peak_rss_mib(), 400 + facet::test::sanitizer_rss_slack_mib());
}

// Files whose size alone breaks the budget (sparse here: no disk is used) are refused
// before a byte of them is read: the model itself, or a buffer it names.
TEST(LargeModel, FilesOverTheBudgetAreRefusedBeforeTheyAreRead) {
    TempDir dir;
    const uint64_t size = uint64_t(1536) << 20;
    {
        std::ofstream glb(dir.file("huge.glb"), std::ios::binary);
        glb.write("glTF", 4);
        test::put_u32(glb, 2);
        test::put_u32(glb, uint32_t(size));
    }
    fs::resize_file(dir.file("huge.glb"), size);
    test::Measured glb = render("--model " + dir.file("huge.glb") + " --out " + dir.file("a.png"));
    EXPECT_EQ(glb.status, 1) << glb.output;
    EXPECT_NE(glb.output.find(dir.file("huge.glb") + ": the file is 1.5 GiB, more than the limit of 1.0 GiB"),
              std::string::npos)
        << glb.output;

    test::write_textured_quad(dir.file("quad.gltf"), "quad.bin", "none.png");
    std::ifstream in(dir.file("quad.gltf"));
    std::string json((std::istreambuf_iterator<char>(in)), {});
    const std::string buffer = R"("uri": "quad.bin", "byteLength": 92)";
    ASSERT_NE(json.find(buffer), std::string::npos);
    json.replace(json.find(buffer), buffer.size(), R"("uri": "huge.bin", "byteLength": )" + std::to_string(size));
    std::ofstream(dir.file("huge.gltf")) << json;
    std::ofstream(dir.file("huge.bin")).close();
    fs::resize_file(dir.file("huge.bin"), size);
    test::Measured bin = render("--model " + dir.file("huge.gltf") + " --out " + dir.file("b.png"));
    EXPECT_EQ(bin.status, 1) << bin.output;
    EXPECT_NE(bin.output.find("huge.bin is 1.5 GiB"), std::string::npos) << bin.output;
    EXPECT_NE(bin.output.find("exceeds its limit of 1.0 GiB"), std::string::npos) << bin.output;
    for (const auto* r : {&glb, &bin}) EXPECT_LT(r->peak_rss_mib(), 400 + facet::test::sanitizer_rss_slack_mib()) << "nothing of the 1.5 GiB was read";
    EXPECT_FALSE(fs::exists(dir.file("a.png")));
    EXPECT_FALSE(fs::exists(dir.file("b.png")));
}

// Texture sizes come from the PNG or JPEG header: absurd ones are refused before any
// decoder runs, and so is a set of textures over the budget.
TEST(LargeModel, TexturesOverTheLimitsAreRefusedFromTheirHeaders) {
    TempDir dir;
    auto error_of = [&](const std::string& image, const GltfLimits& limits = {}) {
        test::write_textured_quad(dir.file("quad.gltf"), "quad.bin", image);
        auto scene = load_gltf(dir.file("quad.gltf"), limits);
        return scene ? std::string("loaded") : scene.error().message;
    };
    test::write_png_header_only(dir.file("huge.png"), 40000, 40000);
    EXPECT_NE(error_of("huge.png").find("quad.gltf: image 'huge.png': 40000x40000 is larger than a texture may be "
                                        "(at most 32768 a side and 16384x16384 pixels); refused before decoding"),
              std::string::npos)
        << error_of("huge.png");
    test::write_png_header_only(dir.file("overflow.png"), 0xFFFFFFFFu, 0xFFFFFFFFu);
    EXPECT_NE(error_of("overflow.png").find("4294967295x4294967295 is larger than a texture may be"), std::string::npos)
        << error_of("overflow.png");
    test::write_png_header_only(dir.file("interlaced.png"), 12000, 12000, 1);
    EXPECT_NE(error_of("interlaced.png").find("12000x12000 interlaced PNG is decoded whole"), std::string::npos)
        << error_of("interlaced.png");

    test::write_png_rows(dir.file("small.png"), 64, 64, [](uint32_t, std::vector<uint8_t>& rgb) {
        std::fill(rgb.begin(), rgb.end(), 128);
    });
    GltfLimits limits;
    limits.max_texture_bytes = 16 << 10;
    EXPECT_NE(error_of("small.png", limits).find("its 1 textures need 21 KiB as RGBA8 with mips, more than the limit "
                                                 "of 16 KiB"),
              std::string::npos)
        << error_of("small.png", limits);
    limits.max_texture_size = 32;  // downsampled to 32 x 32, it fits
    EXPECT_EQ(error_of("small.png", limits), "loaded");
}

}  // namespace
}  // namespace facet
