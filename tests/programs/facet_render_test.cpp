// facet-render as a user runs it: help, bad arguments and bad files (one clear error,
// a non-zero exit, no output), the files it writes (PNG, linear EXR with the exposure
// applied, NAME.json, one EXR per view), and golden images of the built-in scenes and
// the shared models on lavapipe.
//
// Golden images live in tests/golden/. To update them after an intended change:
//   FACET_UPDATE_GOLDEN=1 ctest --test-dir build/release -R Golden
// then look at the new PNGs and commit them.
#include <gtest/gtest.h>

#include "support/process.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

namespace {

namespace fs = std::filesystem;

const std::string data = FACET_SHARED_DATA_DIR;

using facet::test::Ran;

Ran run(const std::string& args) { return facet::test::run_command(std::string(FACET_RENDER_PATH) + " " + args); }

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_render_test_" + std::to_string(::getpid()) + "_" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

void write_file(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

struct Pixels {
    int width = 0, height = 0, channels = 0;
    std::vector<float> values;
};

Pixels read_pixels(const std::string& path) {
    Pixels p;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return p;
    const OIIO::ImageSpec& spec = in->spec();
    p.width = spec.width;
    p.height = spec.height;
    p.channels = spec.nchannels;
    p.values.resize(size_t(p.width) * p.height * p.channels);
    in->read_image(0, 0, 0, p.channels, OIIO::TypeDesc::FLOAT, p.values.data());
    return p;
}

// Small, fast settings shared by the tests.
const std::string fast = " --width 96 --height 72 --env-width 128 --ibl-samples 256";

TEST(FacetRender, HelpAndVersion) {
    Ran help = run("--help");
    EXPECT_EQ(help.status, 0);
    for (const char* text : {"Usage: facet-render", "--model", "--env", "--camera", "--tonemap", "--preset", "--light",
                             "--aov", "--no-skybox", "gold", "diamond"})
        EXPECT_NE(help.output.find(text), std::string::npos) << text;
    Ran version = run("--version");
    EXPECT_EQ(version.status, 0);
    EXPECT_NE(version.output.find("facet-render 0."), std::string::npos);
}

TEST(FacetRender, BadArgumentsExitTwoWithAReason) {
    TempDir dir;
    const std::string out = " --out " + dir / "a.png";
    const std::pair<std::string, std::string> cases[] = {
        {"", "--out FILE.png|FILE.exr is required"},
        {" --out " + dir / "a.jpg", "must end in .png or .exr"},
        {out + " --preset unobtainium", "unknown preset 'unobtainium'"},
        {out + " --tonemap filmic", "unknown operator 'filmic'"},
        {out + " --aov normal,sparkle", "unknown view 'sparkle'"},
        {out + " --light 'laser dir=0,0,1'", "the type must be directional, point or spot"},
        {out + " --light 'point intensity=3'", "needs pos=X,Y,Z"},
        {out + " --light 'spot pos=0,0,0 dir=0,0,-1 inner=40 outer=30'", "inner < outer"},
        {out + " --camera orbit:1,2", "expected orbit:THETA,PHI,RADIUS"},
        {out + " --samples 3", "--samples must be 1, 2, 4 or 8"},
        {out + " --width 0", "--width: 0 is outside"},
        {out + " --target-error 0", "--target-error: 0 is outside (0, 1)"},
        {out + " --target-error 2", "--target-error: 2 is outside (0, 1)"},
        {out + " --target-error abc", "--target-error: 'abc' is not a finite number"},
        {out + " --brdf phong", "--brdf: expected gltf or thesis, got 'phong'"},
    };
    for (const auto& [args, message] : cases) {
        Ran r = run(args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
    }
    EXPECT_TRUE(fs::is_empty(dir.path));
}

// Bad files: one error naming the file and the problem, exit 1, nothing written.
TEST(FacetRender, BadFilesNameTheFileAndWriteNothing) {
    TempDir dir;
    const std::string triangle_json =
        R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":COUNT,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,"uri":"URI"}]})";
    auto gltf = [&](const std::string& name, const std::string& count, const std::string& uri) {
        std::string text = triangle_json;
        text.replace(text.find("COUNT"), 5, count);
        text.replace(text.find("URI"), 3, uri);
        write_file(dir / name, text);
        return dir / name;
    };
    write_file(dir / "tri.bin", std::string(36, '\0'));
    write_file(dir / "not_an_image.hdr", "this is not an image");
    const std::pair<std::string, std::string> cases[] = {
        {"--model " + dir / "missing.gltf", "missing.gltf"},
        {"--model " + gltf("nobuffer.gltf", "3", "absent.bin"), "nobuffer.gltf"},
        {"--model " + gltf("overrun.gltf", "30", "tri.bin"), "overrun.gltf"},
        {"--model " + dir / "tri.bin", "tri.bin"},
        {"--model builtin:teapot", "unknown built-in scene"},
        {"--model builtin:sphere --env " + dir / "not_an_image.hdr", "not_an_image.hdr"},
        {"--model builtin:sphere --env builtin:moon", "unknown built-in environment"},
        {"--model builtin:sphere --camera gltf", "has no camera"},
    };
    for (const auto& [args, name] : cases) {
        const std::string out = dir / "out.png";
        Ran r = run(args + fast + " --out " + out);
        EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("error: "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(name), std::string::npos) << args << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out)) << args;
        EXPECT_FALSE(fs::exists(dir / "out.json")) << args;
    }
    // The accessor error says what is wrong, not only where.
    Ran r = run("--model " + dir / "overrun.gltf" + fast + " --out " + dir / "out.png");
    EXPECT_NE(r.output.find("accessor"), std::string::npos) << r.output;
}

TEST(FacetRender, WritesPngExrJsonAndViews) {
    TempDir dir;
    const std::string args = "--model builtin:sphere --env builtin:sky --no-skybox" + fast;
    Ran png = run(args + " --out " + dir / "sphere.png --aov normal,position,D,F,G,diffuse,specular");
    ASSERT_EQ(png.status, 0) << png.output;
    EXPECT_EQ(png.output.find("Validation"), std::string::npos) << png.output;
    for (const char* view : {"normal", "position", "D", "F", "G", "diffuse", "specular"})
        EXPECT_TRUE(fs::exists(dir / (std::string("sphere.") + view + ".exr"))) << view;
    std::ifstream json_in(dir / "sphere.json");
    const std::string json((std::istreambuf_iterator<char>(json_in)), {});
    for (const char* key : {"\"camera\"", "\"position\"", "\"target\"", "\"up\"", "\"yfov_deg\"", "\"width\": 96",
                            "\"height\": 72", "\"content_hash\"", "\"exposure\"", "\"tonemap\": \"reinhard\"",
                            "\"gamma\": \"sRGB\"", "\"version\"", "\"builtin:sky\"", "sphere.normal.exr",
                            "\"brdf\": \"gltf\"", "\"requested\": \"auto\"", "\"method\": \"lights",
                            "\"reason\": \"1 light(s) extracted", "\"target_error\": 0.03", "\"predicted_error\": ",
                            "\"predicted_worst_group\": \"roughness [", "\"predicted_groups\": [", "\"unbent_groups\": [",
                            "\"two_lookup_groups\": ["})
        EXPECT_NE(json.find(key), std::string::npos) << key << "\n" << json;
    // The automatic choice keeps the predicted error within the target, and says it.
    const size_t at = json.find("\"predicted_error\": ");
    ASSERT_NE(at, std::string::npos);
    const double predicted = std::strtod(json.c_str() + at + 19, nullptr);
    EXPECT_GT(predicted, 0.0);
    EXPECT_LE(predicted, 0.03);
    EXPECT_NE(png.output.find("shading: lights"), std::string::npos) << png.output;
    EXPECT_NE(png.output.find("predicted error "), std::string::npos) << png.output;
    const Pixels ldr = read_pixels(dir / "sphere.png");
    EXPECT_EQ(ldr.width, 96);
    EXPECT_EQ(ldr.height, 72);

    // EXR: linear radiance times the exposure, nothing else.
    ASSERT_EQ(run(args + " --out " + dir / "e1.exr").status, 0);
    ASSERT_EQ(run(args + " --exposure 2 --tonemap aces --out " + dir / "e2.exr").status, 0);
    const Pixels e1 = read_pixels(dir / "e1.exr"), e2 = read_pixels(dir / "e2.exr");
    ASSERT_EQ(e1.values.size(), e2.values.size());
    ASSERT_FALSE(e1.values.empty());
    double brightest = 0;
    for (size_t i = 0; i < e1.values.size(); ++i) {
        if (i % 4 == 3) continue;
        EXPECT_NEAR(e2.values[i], 2 * e1.values[i], 1e-5 * std::max(1.0f, e1.values[i]));
        brightest = std::max(brightest, double(e1.values[i]));
    }
    EXPECT_GT(brightest, 1.0);  // HDR: the sun's highlight is not clamped
}

// The reference mode from the command line: it stops at the sample limit, says so when
// the noise target was not reached, and records both in NAME.json.
TEST(FacetRender, ReferenceModeReportsSamplesAndNoise) {
    TempDir dir;
    Ran r = run("--model builtin:sphere --env builtin:sky --reference --reference-samples 32 --reference-noise 0.0001" +
                fast + " --out " + dir / "ref.png");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("32 samples per pixel"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("warning: the reference stopped at 32"), std::string::npos) << r.output;
    std::ifstream in(dir / "ref.json");
    const std::string json((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(json.find("\"samples_per_pixel\": 32"), std::string::npos) << json;
    EXPECT_NE(json.find("\"converged\": false"), std::string::npos) << json;
    EXPECT_EQ(read_pixels(dir / "ref.png").width, 96);
}

// Light extraction from the command line: the built-in sky's sun becomes one disk light,
// recorded in NAME.json.
TEST(FacetRender, ExtractLightsFindsTheBuiltinSun) {
    TempDir dir;
    Ran r = run("--model builtin:sphere --env builtin:sky --extract-lights" + fast + " --out " + dir / "sun.png");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    // Said once whichever way the bake came: baked fresh, then from the bake cache. The
    // automatic shading's predicted error is kept beside the bake: the second run reads it
    // back, the same to the last digit.
    std::string predicted[2];
    for (int run_index = 0; run_index < 2; ++run_index) {
        Ran c = run("--model builtin:sphere --env builtin:sky --bake-cache " + dir / "cache" + fast +
                    " --out " + dir / "cached.png");
        ASSERT_EQ(c.status, 0) << c.output;
        EXPECT_NE(c.output.find(run_index == 0 ? "bake cache: stored" : "bake cache: using"), std::string::npos) << c.output;
        const size_t said = c.output.find("extracted 1 light(s)");
        EXPECT_NE(said, std::string::npos) << c.output;
        EXPECT_EQ(c.output.find("extracted 1 light(s)", said + 1), std::string::npos) << c.output;
        EXPECT_EQ(c.output.find("from the bake cache") != std::string::npos, run_index == 1) << c.output;
        std::ifstream cached_json(dir / "cached.json");
        const std::string text((std::istreambuf_iterator<char>(cached_json)), {});
        const size_t at = text.find("\"predicted_error\": ");
        ASSERT_NE(at, std::string::npos) << text;
        predicted[run_index] = text.substr(at, text.find(',', at) - at);
    }
    EXPECT_EQ(predicted[0], predicted[1]);
    std::ifstream in(dir / "sun.json");
    const std::string json((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(json.find("\"environment_lights\": ["), std::string::npos) << json;
    EXPECT_NE(json.find("\"angular_radius_deg\""), std::string::npos) << json;
}

double channel_difference(const Pixels& a, const Pixels& b, double* fraction_over_16) {
    double sum = 0;
    size_t over = 0;
    const size_t pixels = size_t(a.width) * a.height;
    for (size_t p = 0; p < pixels; ++p) {
        double worst = 0;
        for (int c = 0; c < 3; ++c) {
            const double d = std::abs(a.values[p * a.channels + c] - b.values[p * b.channels + c]) * 255.0;
            sum += d;
            worst = std::max(worst, d);
        }
        over += worst > 16.0;
    }
    *fraction_over_16 = double(over) / double(pixels);
    return sum / (3.0 * double(pixels));
}

// Golden images: mean channel difference under 1 level of 255 and under 0.5% of the
// pixels off by more than 16 levels (room for other CPUs' LLVM code generation).
void check_golden(const std::string& name, const std::string& args) {
    TempDir dir;
    const std::string out = dir / (name + ".png");
    Ran r = run(args + " --width 160 --height 120 --out " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;  // ctest sets FACET_VALIDATION=1
    const std::string golden = std::string(FACET_SOURCE_DIR) + "/tests/golden/" + name + ".png";
    if (std::getenv("FACET_UPDATE_GOLDEN")) {
        fs::copy_file(out, golden, fs::copy_options::overwrite_existing);
        std::printf("updated %s\n", golden.c_str());
        return;
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing (FACET_UPDATE_GOLDEN=1 writes it)";
    const Pixels want = read_pixels(golden), got = read_pixels(out);
    ASSERT_EQ(got.width, want.width);
    ASSERT_EQ(got.height, want.height);
    double over = 0;
    const double mean = channel_difference(got, want, &over);
    EXPECT_LT(mean, 1.0) << name;
    EXPECT_LT(over, 0.005) << name;
}

TEST(FacetRenderGolden, Spheres) { check_golden("spheres", "--model builtin:spheres --env builtin:sky --env-width 256"); }
TEST(FacetRenderGolden, SpheresGoldPreset) {
    check_golden("spheres_gold", "--model builtin:spheres --preset gold --env builtin:sky --env-width 256 --tonemap aces");
}
TEST(FacetRenderGolden, DamagedHelmet) {
    check_golden("damaged_helmet", "--model " + data + "/models/DamagedHelmet.glb --env " + data +
                                       "/env/studio_small_03_1k.hdr --light 'directional dir=-1,-1,-1 intensity=3'");
}
TEST(FacetRenderGolden, Suzanne) {
    check_golden("suzanne", "--model " + data + "/models/suzanne/02_suzanne.gltf --env builtin:sky --env-width 256 "
                                                "--camera orbit:30,15,3.5 --tonemap neutral");
}
TEST(FacetRenderGolden, Teapot) {
    check_golden("teapot", "--model " + data + "/models/teapot.gltf --env " + data +
                               "/env/royal_esplanade_1k.hdr --preset copper --no-skybox "
                               "--light 'point pos=2,3,2 intensity=40'");
}

}  // namespace
