// facet-bake as a user runs it: help, bad arguments, bad outputs, and a real bake.
#include <gtest/gtest.h>

#include "support/process.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include <facet/io/environment_image.h>
#include <facet/io/ktx2.h>
#include <facet/reference/ibl_reference.h>

namespace {

namespace fs = std::filesystem;

using facet::test::Ran;

Ran run(const std::string& args) { return facet::test::run_command(std::string(FACET_BAKE_PATH) + " " + args); }

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_bake_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
};

std::string file_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

TEST(FacetBake, HelpAndVersion) {
    Ran help = run("--help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.output.find("Usage: facet-bake"), std::string::npos) << help.output;
    EXPECT_NE(help.output.find("--out DIR"), std::string::npos);
    Ran version = run("--version");
    EXPECT_EQ(version.status, 0);
    EXPECT_NE(version.output.find("facet-bake 0."), std::string::npos) << version.output;
}

TEST(FacetBake, BadArgumentsExitTwoWithAReason) {
    Ran none = run("");
    EXPECT_EQ(none.status, 2);
    EXPECT_NE(none.output.find("expected exactly one environment"), std::string::npos) << none.output;
    Ran no_out = run("builtin:sky");
    EXPECT_EQ(no_out.status, 2);
    EXPECT_NE(no_out.output.find("--out"), std::string::npos) << no_out.output;
    Ran unknown = run("builtin:sky --out x --frobnicate");
    EXPECT_EQ(unknown.status, 2);
    EXPECT_NE(unknown.output.find("--frobnicate"), std::string::npos) << unknown.output;
    Ran bad_width = run("builtin:sky --out x --width 12abc");
    EXPECT_EQ(bad_width.status, 2);
    EXPECT_NE(bad_width.output.find("--width"), std::string::npos) << bad_width.output;
    Ran bad_method = run("builtin:sky --out x --specular sorcery");
    EXPECT_EQ(bad_method.status, 2);
    EXPECT_NE(bad_method.output.find("sorcery"), std::string::npos) << bad_method.output;
}

TEST(FacetBake, BadInputsNameTheProblemAndWriteNothing) {
    TempDir dir;
    const std::string out = (dir.path / "out").string();
    Ran unknown = run("builtin:nothing --out " + out);
    EXPECT_EQ(unknown.status, 1);
    EXPECT_NE(unknown.output.find("builtin:nothing"), std::string::npos) << unknown.output;
    std::ofstream(dir.path / "garbage.hdr") << "not an image";
    Ran garbage = run((dir.path / "garbage.hdr").string() + " --out " + out);
    EXPECT_EQ(garbage.status, 1);
    EXPECT_NE(garbage.output.find("garbage.hdr: cannot read the image"), std::string::npos) << garbage.output;
    Ran missing = run((dir.path / "missing.hdr").string() + " --out " + out);
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.output.find("missing.hdr: no such file"), std::string::npos) << missing.output;
    EXPECT_FALSE(fs::exists(out));

    std::ofstream(dir.path / "a_file") << "x";
    Ran file_as_dir = run("builtin:sky --width 64 --out " + (dir.path / "a_file").string());
    EXPECT_EQ(file_as_dir.status, 1);
    EXPECT_NE(file_as_dir.output.find("not a directory"), std::string::npos) << file_as_dir.output;
}

TEST(FacetBake, BakesTheBuiltInSky) {
    TempDir dir;
    const std::string out = (dir.path / "sky").string();
    Ran bake = run("builtin:sky --width 128 --validation --out " + out);
    ASSERT_EQ(bake.status, 0) << bake.output;
    EXPECT_EQ(bake.output.find("validation:"), std::string::npos) << bake.output;
    for (const char* name : {"specular.ktx2", "irradiance.ktx2", "brdf_lut.ktx2", "brdf_lut.png", "environment.ktx2",
                             "environment.exr", "environment.hdr", "environment.png", "bake.json"})
        EXPECT_TRUE(fs::exists(fs::path(out) / name)) << name;
    std::ifstream json(fs::path(out) / "bake.json");
    std::string text((std::istreambuf_iterator<char>(json)), {});
    EXPECT_NE(text.find("\"procedural sky\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"gpu_time_ms\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"content_hash\""), std::string::npos) << text;
    size_t files = 0;
    for (auto& e : fs::directory_iterator(out)) files += e.is_regular_file();
    EXPECT_EQ(files, 9u) << "no temporary files left behind";
    EXPECT_NE(text.find("\"roughness\": 1"), std::string::npos) << text;
    EXPECT_NE(text.find("\"bake_key\""), std::string::npos) << text;

    Ran again = run("builtin:sky --width 128 --out " + out);
    ASSERT_EQ(again.status, 0) << again.output;
    EXPECT_NE(again.output.find("up to date"), std::string::npos) << again.output;
    EXPECT_EQ(again.output.find("running"), std::string::npos) << "an identical bake is skipped";

    Ran other = run("builtin:sky --width 128 --irradiance riemann --out " + out);
    ASSERT_EQ(other.status, 0) << other.output;
    EXPECT_NE(other.output.find("replacing"), std::string::npos) << "replacing is said, not silent";
    Ran forced = run("builtin:sky --width 128 --irradiance riemann --force --out " + out);
    ASSERT_EQ(forced.status, 0) << forced.output;
    EXPECT_NE(forced.output.find("running"), std::string::npos) << forced.output;
}

TEST(FacetBake, BadTexelsFailOrAreSanitised) {
    TempDir dir;
    std::vector<float> texels(32 * 16 * 3, 0.5f);
    texels[(3 * 32 + 5) * 3 + 1] = -2.0f;
    const std::string path = (dir.path / "negative.exr").string();
    {
        auto out = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(32, 16, 3, OIIO::TypeDesc::FLOAT);
        ASSERT_TRUE(out->open(path, spec));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels.data()));
        out->close();
    }
    const std::string out_dir = (dir.path / "out").string();
    Ran bad = run(path + " --lut-size 8 --out " + out_dir);
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("negative.exr: texel (5, 3) channel G is negative"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(fs::path(out_dir) / "bake.json")) << "no output for a failed bake";
    Ran sanitised = run(path + " --sanitize --lut-size 8 --out " + out_dir);
    ASSERT_EQ(sanitised.status, 0) << sanitised.output;
    EXPECT_NE(sanitised.output.find("replaced 1 NaN, Inf or negative texels"), std::string::npos) << sanitised.output;
    EXPECT_NE(file_bytes(fs::path(out_dir) / "bake.json").find("\"sanitized_texels\": 1"), std::string::npos);
}

TEST(FacetBake, BakesAnEnvironmentFile) {
    TempDir dir;
    const std::string out = (dir.path / "studio").string();
    const std::string env = std::string(FACET_SHARED_DATA_DIR) + "/env/studio_small_03_1k.hdr";
    Ran bake = run(env + " --size 32 --lut-size 32 --lut-samples 256 --validation --out " + out);
    ASSERT_EQ(bake.status, 0) << bake.output;
    EXPECT_NE(bake.output.find("1024x512"), std::string::npos) << bake.output;
    EXPECT_EQ(bake.output.find("validation:"), std::string::npos) << bake.output;
    std::ifstream json(fs::path(out) / "bake.json");
    std::string text((std::istreambuf_iterator<char>(json)), {});
    EXPECT_NE(text.find("\"upload environment\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"samples\": 256"), std::string::npos) << text;
    EXPECT_NE(text.find("\"size\": 32"), std::string::npos) << text;
}

// Results identical from run to run: no random seeds, no order-dependent sums.
// Also across the two ways a bake ends: with validation the device is torn down (and the
// layer checks it); without, the process ends after the commit without tearing it down.
// Both give every file, byte for byte, and every line.
TEST(FacetBake, BakesAreDeterministic) {
    TempDir dir;
    const std::string args = "builtin:sky --width 128 --lut-size 16 --force --out ";
    auto with_validation = [&](const char* on, const char* sub) {
        return facet::test::run_command(std::string("FACET_VALIDATION=") + on + " " + FACET_BAKE_PATH + " " + args +
                                        (dir.path / sub).string());
    };
    Ran first = with_validation("1", "a");
    Ran second = with_validation("0", "b");
    ASSERT_EQ(first.status, 0) << first.output;
    ASSERT_EQ(second.status, 0) << second.output;
    for (const Ran* r : {&first, &second}) EXPECT_NE(r->output.find("GPU, "), std::string::npos) << r->output;
    for (const char* name : {"specular.ktx2", "irradiance.ktx2", "brdf_lut.ktx2", "environment.ktx2", "environment.exr",
                             "environment.hdr", "environment.png", "brdf_lut.png"}) {
        const std::string a = file_bytes(dir.path / "a" / name), b = file_bytes(dir.path / "b" / name);
        EXPECT_FALSE(a.empty()) << name;
        EXPECT_TRUE(a == b) << name << " differs between two identical bakes";
    }
    for (const char* sub : {"a", "b"}) {
        size_t files = 0;
        for (auto& e : fs::directory_iterator(dir.path / sub)) files += e.is_regular_file();
        EXPECT_EQ(files, 9u) << sub << ": no temporary files left behind";
    }
}

TEST(FacetBake, Sh9WritesItsCoefficients) {
    TempDir dir;
    const std::string out = (dir.path / "sh").string();
    Ran bake = run("builtin:sky --width 64 --lut-size 8 --irradiance sh9 --out " + out);
    ASSERT_EQ(bake.status, 0) << bake.output;
    const std::string json = file_bytes(fs::path(out) / "sh9.json");
    EXPECT_NE(json.find("\"coefficients\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"window_h\""), std::string::npos) << json;
    Ran other = run("builtin:sky --width 64 --lut-size 8 --out " + out);
    ASSERT_EQ(other.status, 0) << other.output;
    EXPECT_FALSE(fs::exists(fs::path(out) / "sh9.json")) << "a stale sh9.json is removed, and said";
    EXPECT_NE(other.output.find("removing"), std::string::npos) << other.output;
}

// The white furnace through the whole program: every specular level and the irradiance,
// as written in the KTX2 files, are 1 (RGBA16F keeps 1 exactly; bound 1e-3).
TEST(FacetBake, WhiteFurnaceThroughTheFiles) {
    TempDir dir;
    const std::string out = (dir.path / "white").string();
    Ran bake = run("builtin:white --width 128 --levels 5 --lut-size 16 --out " + out);
    ASSERT_EQ(bake.status, 0) << bake.output;
    auto specular = facet::read_ktx2((fs::path(out) / "specular.ktx2").string());
    ASSERT_TRUE(specular) << specular.error().message;
    EXPECT_EQ(specular->faces, 6u);
    EXPECT_EQ(specular->levels, 5u);
    EXPECT_EQ(specular->width, 32u);
    EXPECT_EQ(specular->format, VK_FORMAT_R16G16B16A16_SFLOAT);
    auto irradiance = facet::read_ktx2((fs::path(out) / "irradiance.ktx2").string());
    ASSERT_TRUE(irradiance) << irradiance.error().message;
    EXPECT_EQ(irradiance->faces, 6u);
    for (const facet::Ktx2Image* image : {&specular.value(), &irradiance.value()})
        for (uint32_t l = 0; l < image->levels; ++l) {
            const auto& data = image->level_data[l];
            for (size_t i = 0; i + 1 < data.size(); i += 2) {
                if ((i / 2) % 4 == 3) continue;  // alpha
                uint16_t h;
                std::memcpy(&h, data.data() + i, 2);
                ASSERT_NEAR(facet::half_to_float(h), 1.0f, 1e-3f) << "level " << l;
            }
        }
    auto lut = facet::read_ktx2((fs::path(out) / "brdf_lut.ktx2").string());
    ASSERT_TRUE(lut) << lut.error().message;
    EXPECT_EQ(lut->faces, 1u);
    EXPECT_EQ(lut->width, 16u);
}

// Methods used outside their domain say so, in bake.json and on stderr.
TEST(FacetBake, WarnsWhenAMethodLeavesItsDomain) {
    TempDir dir;
    Ran sh9 = run("builtin:sky --width 128 --irradiance sh9 --lut-size 8 --lut-samples 16 --out " +
                  (dir.path / "sh9").string());
    ASSERT_EQ(sh9.status, 0) << sh9.output;
    EXPECT_NE(sh9.output.find("warning: irradiance sh9: compact lights hold"), std::string::npos) << sh9.output;
    const std::string json = file_bytes(dir.path / "sh9" / "bake.json");
    EXPECT_NE(json.find("\"warnings\": [\n    \"irradiance sh9"), std::string::npos) << json;
    Ran defaults = run("builtin:sky --width 128 --lut-size 8 --lut-samples 16 --out " + (dir.path / "ok").string());
    ASSERT_EQ(defaults.status, 0) << defaults.output;
    EXPECT_EQ(defaults.output.find("warning"), std::string::npos) << defaults.output;
    EXPECT_NE(file_bytes(dir.path / "ok" / "bake.json").find("\"warnings\": []"), std::string::npos);
}

void check_irradiance_against_truth(const fs::path& bake, const fs::path& whole);

// The accuracy budget: a loose target picks cheaper methods than a tight one; every
// choice records its predicted error, which the bake then meets: the irradiance written
// to irradiance.ktx2, compared here with the brute-force integral over environment.exr.
TEST(FacetBake, AccuracyBudgetPicksTheCheapestMethodThatMeetsIt) {
    TempDir dir;
    const std::string common = "builtin:sky --width 128 --roughness 0.3,1 --out ";
    Ran loose = run(common + (dir.path / "loose").string() + " --target-error 0.5");
    ASSERT_EQ(loose.status, 0) << loose.output;
    Ran tight = run(common + (dir.path / "tight").string() + " --target-error 0.02");
    ASSERT_EQ(tight.status, 0) << tight.output;
    const std::string loose_json = file_bytes(dir.path / "loose" / "bake.json");
    const std::string tight_json = file_bytes(dir.path / "tight" / "bake.json");
    for (const std::string* json : {&loose_json, &tight_json}) {
        EXPECT_NE(json->find("\"budget\": {"), std::string::npos) << *json;
        EXPECT_NE(json->find("\"roughness_range\""), std::string::npos);
        EXPECT_EQ(json->find("\"met\": false"), std::string::npos) << *json;
    }
    // Under the sun, sh9 (7%) is enough for 50% but not for 2%.
    EXPECT_NE(loose_json.find("\"method\": \"sh9\""), std::string::npos) << loose_json;
    EXPECT_NE(tight_json.find("\"method\": \"convolve\""), std::string::npos) << tight_json;

    // With the sun extracted the irradiance is still baked from the whole environment, so its
    // method is judged there (judged on the map without the sun, sh9 would pass).
    Ran lights = run(common + (dir.path / "lights").string() + " --target-error 0.02 --extract-lights");
    ASSERT_EQ(lights.status, 0) << lights.output;
    const std::string lights_json = file_bytes(dir.path / "lights" / "bake.json");
    EXPECT_NE(lights_json.find("\"method\": \"convolve\""), std::string::npos) << lights_json;
    EXPECT_EQ(lights_json.find("\"split_level\": 0"), std::string::npos) << "the sun is extracted: " << lights_json;

    // The tight bakes' irradiance meets its prediction over 96 texels it was not measured on,
    // against the whole environment (the lights bake's environment.exr is the map without the
    // sun; the tight bake's is the whole).
    for (const char* bake : {"tight", "lights"})
        check_irradiance_against_truth(dir.path / bake, dir.path / "tight" / "environment.exr");
}

void check_irradiance_against_truth(const fs::path& bake, const fs::path& whole) {
    SCOPED_TRACE(bake.string());
    auto env = facet::load_environment(whole.string());
    ASSERT_TRUE(env) << env.error().message;
    const facet::test::Equirect e{env->width, env->height, env->rgba};
    auto ktx = facet::read_ktx2((bake / "irradiance.ktx2").string());
    ASSERT_TRUE(ktx) << ktx.error().message;
    const uint32_t n = ktx->width;
    double err2 = 0, ref2 = 0;
    for (uint32_t face = 0; face < 6; ++face)
        for (uint32_t k = 0; k < 16; ++k) {
            const uint32_t x = (k * 7 + 3) % n, y = (k * 11 + 5) % n;
            const facet::test::Vec3 want =
                facet::test::irradiance_over_pi(e, facet::test::cube_texel_direction(face, x, y, n));
            // RGBA16F, face after face.
            const auto* halves = reinterpret_cast<const uint16_t*>(ktx->level_data[0].data());
            const size_t texel = (size_t(face) * n + y) * n + x;
            for (int c = 0; c < 3; ++c) {
                const double d = facet::half_to_float(halves[texel * 4 + size_t(c)]) - want[size_t(c)];
                err2 += d * d;
                ref2 += want[size_t(c)] * want[size_t(c)];
            }
        }
    EXPECT_LT(std::sqrt(err2 / ref2), 0.02) << "irradiance against the truth";
}

}  // namespace

namespace {

// A clear-sky-like sun beyond RGBA16F's range (2e5 > 65504), written as an EXR.
std::string write_bright_sun(const fs::path& dir, uint32_t width = 128, double diameter_deg = 5.0) {
    const facet::test::Equirect sky = facet::test::sun_sky(width, width / 2, 2e5, diameter_deg, 30.0, 10.0);
    const std::string path = (dir / "bright_sun.exr").string();
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out);
    OIIO::ImageSpec spec(int(sky.w), int(sky.h), 4, OIIO::TypeDesc::FLOAT);
    EXPECT_TRUE(out->open(path, spec));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, sky.rgba.data()));
    out->close();
    return path;
}

}  // namespace

// No texel becomes Inf because it exceeds half float: the outputs that need it are kept
// in RGBA32F, said on stderr and in bake.json.
TEST(FacetBake, ASunBeyondHalfFloatIsKeptInFloat32AndSaid) {
    TempDir dir;
    const std::string env = write_bright_sun(dir.path), out = (dir.path / "sun").string();
    Ran bake = run(env + " --lut-size 8 --lut-samples 16 --irradiance-size 8 --samples 64 --out " + out);
    ASSERT_EQ(bake.status, 0) << bake.output;
    EXPECT_NE(bake.output.find("specular kept in R32G32B32A32_SFLOAT"), std::string::npos) << bake.output;
    const std::string json = file_bytes(fs::path(out) / "bake.json");
    EXPECT_NE(json.find("\"format_notes\": [\n    \"environment cube kept in R32G32B32A32_SFLOAT"), std::string::npos)
        << json;
    for (const char* name : {"specular.ktx2", "environment.ktx2", "irradiance.ktx2"}) {
        auto k = facet::read_ktx2((fs::path(out) / name).string());
        ASSERT_TRUE(k) << k.error().message;
        const bool half = k->format == VK_FORMAT_R16G16B16A16_SFLOAT;
        size_t bad = 0;
        for (const auto& level : k->level_data)
            for (size_t i = 0; i < level.size() / (half ? 2 : 4); ++i) {
                float v;
                if (half) {
                    uint16_t h;
                    std::memcpy(&h, level.data() + i * 2, 2);
                    v = facet::half_to_float(h);
                } else {
                    std::memcpy(&v, level.data() + i * 4, 4);
                }
                bad += !std::isfinite(v);
            }
        EXPECT_EQ(bad, 0u) << name;
        if (std::string(name) != "irradiance.ktx2") EXPECT_EQ(k->format, VK_FORMAT_R32G32B32A32_SFLOAT) << name;
    }
    // --float32: every output RGBA32F, nothing to say.
    Ran f32 = run("builtin:white --width 32 --lut-size 8 --lut-samples 16 --float32 --out " + (dir.path / "f32").string());
    ASSERT_EQ(f32.status, 0) << f32.output;
    EXPECT_EQ(f32.output.find("kept in"), std::string::npos) << f32.output;
    auto lut = facet::read_ktx2((dir.path / "f32" / "brdf_lut.ktx2").string());
    ASSERT_TRUE(lut) << lut.error().message;
    EXPECT_EQ(lut->format, VK_FORMAT_R32G32B32A32_SFLOAT);
}

TEST(FacetBake, ExtractedLightsAreRecordedWithTheirSplitLevel) {
    TempDir dir;
    const std::string env = write_bright_sun(dir.path, 256, 3.0), out = (dir.path / "lights").string();
    Ran bake = run(env + " --extract-lights --lut-size 8 --lut-samples 16 --irradiance-size 8 --samples 64 --out " + out);
    ASSERT_EQ(bake.status, 0) << bake.output;
    EXPECT_NE(bake.output.find("extracted 1 light(s)"), std::string::npos) << bake.output;
    const std::string json = file_bytes(fs::path(out) / "bake.json");
    EXPECT_NE(json.find("\"angular_radius\""), std::string::npos) << json;
    EXPECT_EQ(json.find("\"split_level\": 0"), std::string::npos) << json;
}
