// Very large environments (README, "Large inputs"): a 16384 x 8192 file generated here,
// run-length encoded so it takes a few megabytes, is downsampled while it is read by
// load_environment and by facet-bake, keeping the solid-angle mean and the position of
// a feature, in bounded memory; sizes beyond the hard limits are refused from the
// header, before anything is allocated.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "io/box_downsample.h"
#include <facet/io/environment_image.h>
#include "support/sanitizers.h"
#include "support/measured_process.h"
#include "support/rle_hdr.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_large_env_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

// The generated environment: radiance 0.5 everywhere but a 64 x 64 patch of (64, 32, 16)
// at x 12288, y 2048; every value is exact in RGBE.
constexpr uint32_t kWidth = 16384, kHeight = 8192;
constexpr uint32_t kPatchX = 12288, kPatchY = 2048, kPatch = 64;
constexpr float kSky = 0.5f;
constexpr float kPatchRgb[3] = {64.0f, 32.0f, 16.0f};

void write_large_environment(const std::string& path) {
    ASSERT_TRUE(test::write_rle_hdr(path, kWidth, kHeight, [](uint32_t y, std::vector<float>& rgb) {
        std::fill(rgb.begin(), rgb.end(), kSky);
        if (y >= kPatchY && y < kPatchY + kPatch)
            for (uint32_t x = kPatchX; x < kPatchX + kPatch; ++x)
                for (int c = 0; c < 3; ++c) rgb[x * 3 + c] = kPatchRgb[c];
    }));
}

// Fraction of the sphere between rows a and b of an equirect `height` rows tall.
double band(double a, double b, double height) {
    return (std::cos(std::numbers::pi * a / height) - std::cos(std::numbers::pi * b / height)) / 2.0;
}

// The mean radiance over the sphere (each texel by its exact solid angle) of channel c.
double sphere_mean(const std::vector<float>& rgba, uint32_t w, uint32_t h, int c) {
    double sum = 0;
    for (uint32_t y = 0; y < h; ++y) {
        double row = 0;
        for (uint32_t x = 0; x < w; ++x) row += rgba[(size_t(y) * w + x) * 4 + c];
        sum += band(y, y + 1, h) * row / w;
    }
    return sum;
}

double expected_mean(int c) {
    return kSky + (kPatchRgb[c] - kSky) * double(kPatch) / kWidth * band(kPatchY, kPatchY + kPatch, kHeight);
}

// The patch, `factor` times smaller, is where it was and keeps its radiance; the sky
// around it is untouched.
void expect_patch(const std::vector<float>& rgba, uint32_t w, uint32_t factor) {
    const uint32_t x0 = kPatchX / factor, y0 = kPatchY / factor, n = kPatch / factor;
    auto at = [&](uint32_t x, uint32_t y, int c) { return rgba[(size_t(y) * w + x) * 4 + c]; };
    for (uint32_t y = y0; y < y0 + n; ++y)
        for (uint32_t x = x0; x < x0 + n; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(at(x, y, c), kPatchRgb[c], 1e-4f) << x << ", " << y;
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(at(x0 - 1, y0, c), kSky, 1e-6f);
        EXPECT_NEAR(at(x0 + n, y0, c), kSky, 1e-6f);
        EXPECT_NEAR(at(x0, y0 - 1, c), kSky, 1e-6f);
        EXPECT_NEAR(at(x0, y0 + n, c), kSky, 1e-6f);
    }
}

void write_float_environment(const std::string& path, uint32_t w, uint32_t h) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(int(w), int(h), 3, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, std::vector<float>(size_t(w) * h * 3, kSky).data()));
    out->close();
}

long own_peak_rss_kb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
}

TEST(LargeEnvironment, A16kFileIsDownsampledWhileReadKeepingItsMeanAndFeatures) {
    TempDir dir;
    const std::string path = dir.file("large.hdr");
    write_large_environment(path);
    EXPECT_LT(fs::file_size(path), 16u << 20) << "run-length encoded, mostly constant";

    auto env = load_environment(path);  // default: at most 4096 x 2048
    ASSERT_TRUE(env) << env.error().message;
    EXPECT_EQ(env->source_width, kWidth);
    EXPECT_EQ(env->source_height, kHeight);
    EXPECT_EQ(env->width, 4096u);
    EXPECT_EQ(env->height, 2048u);
    EXPECT_TRUE(env->downsampled());
    EXPECT_EQ(env->rgba.size(), size_t(4096) * 2048 * 4);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(sphere_mean(env->rgba, env->width, env->height, c) / expected_mean(c), 1.0, 1e-6) << "channel " << c;
    expect_patch(env->rgba, env->width, 4);
    // Reading it whole as RGBA32F would take 2 GiB; the output is 128 MiB.
    std::printf("load_environment of a 16384x8192 file kept at 4096x2048: this test peaked at %.0f MiB\n",
                own_peak_rss_kb() / 1024.0);
    EXPECT_LT(own_peak_rss_kb(), (512 + facet::test::sanitizer_rss_slack_mib()) * 1024) << "the test process peaked above 512 MiB";
}

// The same file through facet-bake with small settings: the environment it records is
// the downsampled one, with the file's size in bake.json, and the program's peak memory
// stays far below what reading the file whole would take (2 GiB as RGBA32F).
TEST(LargeEnvironment, FacetBakeDownsamplesA16kFileWithinItsMemoryBudget) {
    TempDir dir;
    const std::string path = dir.file("large.hdr");
    write_large_environment(path);
    const std::string small = " --size 16 --levels 2 --irradiance-size 8 --lut-size 8 --lut-samples 16 --samples 16";
    test::Measured bake = test::run_measured(std::string(FACET_BAKE_PATH) + " " + path + " --max-env-width 1024" +
                                             small + " --out " + dir.file("out"));
    ASSERT_EQ(bake.status, 0) << bake.output;
    EXPECT_NE(bake.output.find("16384x8192 downsampled to 1024x512 while reading (--max-env-width 1024)"),
              std::string::npos)
        << bake.output;
    std::ifstream json_file(dir.file("out/bake.json"));
    std::stringstream json;
    json << json_file.rdbuf();
    for (const char* field : {R"("width": 1024)", R"("height": 512)", R"("source_width": 16384)",
                              R"("source_height": 8192)", R"("max_env_width": 1024)"})
        EXPECT_NE(json.str().find(field), std::string::npos) << field << " in " << json.str();

    auto baked = load_environment(dir.file("out/environment.exr"));
    ASSERT_TRUE(baked) << baked.error().message;
    ASSERT_EQ(baked->width, 1024u);
    ASSERT_EQ(baked->height, 512u);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(sphere_mean(baked->rgba, 1024, 512, c) / expected_mean(c), 1.0, 1e-6) << "channel " << c;
    expect_patch(baked->rgba, 1024, 16);

    // The same bake of a small file: the difference is what the large one costs.
    write_float_environment(dir.file("small.exr"), 1024, 512);
    test::Measured reference = test::run_measured(std::string(FACET_BAKE_PATH) + " " + dir.file("small.exr") + small +
                                                  " --out " + dir.file("reference"));
    ASSERT_EQ(reference.status, 0) << reference.output;
    std::printf("facet-bake peak RSS: %.0f MiB for the 16384x8192 file kept at 1024x512, %.0f MiB for a 1024x512 file\n",
                bake.peak_rss_mib(), reference.peak_rss_mib());
    EXPECT_LT(bake.peak_rss_mib() - reference.peak_rss_mib(), 64);
}

// Declared sizes beyond the hard limits, or ones that overflow: one clear error, exit
// 1, no output, and nothing large allocated.
TEST(LargeEnvironment, SizesBeyondTheHardLimitsAreRefusedFromTheHeader) {
    TempDir dir;
    ASSERT_TRUE(test::write_hdr_header_only(dir.file("huge.hdr"), "-Y 100000 +X 200000"));
    auto huge = load_environment(dir.file("huge.hdr"));
    ASSERT_FALSE(huge);
    EXPECT_EQ(huge.error().message, dir.file("huge.hdr") +
                                        ": 200000x100000 is larger than an environment may be (at most 65536 texels a "
                                        "side and 65536x32768 texels in all); refused before reading it");
    ASSERT_TRUE(test::write_hdr_header_only(dir.file("many.hdr"), "-Y 60000 +X 60000"));
    auto many = load_environment(dir.file("many.hdr"));
    ASSERT_FALSE(many);
    EXPECT_NE(many.error().message.find("60000x60000 is larger than an environment may be"), std::string::npos);
    ASSERT_TRUE(test::write_hdr_header_only(dir.file("overflow.hdr"), "-Y 4294967296 +X 4294967296"));
    auto overflow = load_environment(dir.file("overflow.hdr"));
    ASSERT_FALSE(overflow);
    EXPECT_NE(overflow.error().message.find(dir.file("overflow.hdr") + ": "), std::string::npos);

    for (const char* name : {"huge.hdr", "many.hdr", "overflow.hdr"}) {
        const std::string out = dir.file(std::string("out_") + name);
        test::Measured bake =
            test::run_measured(std::string(FACET_BAKE_PATH) + " " + dir.file(name) + " --out " + out);
        EXPECT_EQ(bake.status, 1) << bake.output;
        EXPECT_NE(bake.output.find("facet-bake: error: " + dir.file(name) + ": "), std::string::npos) << bake.output;
        EXPECT_FALSE(fs::exists(out)) << "nothing written";
        EXPECT_LT(bake.peak_rss_mib(), 256 + facet::test::sanitizer_rss_slack_mib()) << name << ": nothing of its size was allocated";
        test::Measured render = test::run_measured(std::string(FACET_RENDER_PATH) + " --env " + dir.file(name) +
                                                   " --out " + out + ".png");
        EXPECT_EQ(render.status, 1) << render.output;
        EXPECT_NE(render.output.find("facet-render: error: " + dir.file(name) + ": "), std::string::npos)
            << render.output;
        EXPECT_FALSE(fs::exists(out + ".png"));
        EXPECT_LT(render.peak_rss_mib(), 256 + facet::test::sanitizer_rss_slack_mib()) << name;
    }
}

// Tiled files are read a row of tiles at a time; the result is the scanline file's.
TEST(LargeEnvironment, TiledAndScanlineFilesDownsampleAlike) {
    TempDir dir;
    const uint32_t w = 96, h = 48;
    std::vector<float> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = float((i * 7919) % 1000) / 100.0f;
    for (bool tiled : {false, true}) {
        auto out = OIIO::ImageOutput::create("exr");
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(int(w), int(h), 3, OIIO::TypeDesc::FLOAT);
        if (tiled) spec.tile_width = spec.tile_height = 16;
        spec.attribute("compression", "zip");
        const std::string path = dir.file(tiled ? "tiled.exr" : "lines.exr");
        ASSERT_TRUE(out->open(path, spec));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
        out->close();
    }
    auto lines = load_environment(dir.file("lines.exr"), {false, 20});
    auto tiled = load_environment(dir.file("tiled.exr"), {false, 20});
    ASSERT_TRUE(lines) << lines.error().message;
    ASSERT_TRUE(tiled) << tiled.error().message;
    EXPECT_EQ(lines->width, 20u);
    EXPECT_EQ(lines->height, 10u);
    EXPECT_EQ(lines->rgba, tiled->rgba);
    EXPECT_EQ(lines->content_hash, tiled->content_hash);
    // 96 / 20 is no integer: the box takes fractional texels at its edges, and the
    // solid-angle mean still holds.
    std::vector<float> source(size_t(w) * h * 4, 1.0f);
    for (size_t i = 0; i < size_t(w) * h; ++i)
        for (int c = 0; c < 3; ++c) source[i * 4 + c] = rgb[i * 3 + c];
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(sphere_mean(lines->rgba, 20, 10, c), sphere_mean(source, w, h, c), 1e-5);
}

}  // namespace
}  // namespace facet
