// facet-render with a saved bake (--ibl DIR) and with the bake cache (--bake-cache DIR):
// the same image as a fresh bake, a second run that bakes nothing, a damaged entry
// reported and rebuilt, two processes filling one entry, a missing bake named.
#include <gtest/gtest.h>

#include "support/output_files.h"
#include "support/process.h"
#include "support/spawn.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace {

namespace fs = std::filesystem;
using facet::test::Ran;
using facet::test::TempDir;

const std::string model = " --model builtin:sphere --width 64 --height 48";
const std::string scene = model + " --env builtin:sky --env-width 64 --ibl-size 16";

Ran render(const std::string& args) { return facet::test::run_command(std::string(FACET_RENDER_PATH) + scene + args); }
// With --ibl DIR the environment is the bake's: no --env or bake settings.
Ran render_with_bake(const std::string& args) {
    return facet::test::run_command(std::string(FACET_RENDER_PATH) + model + args);
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// The cache's one bake entry (the automatic method's predictions sit beside it in
// prediction-HASH directories; temporaries start with a dot). Empty if none or several.
fs::path only_entry(const fs::path& cache) {
    std::vector<fs::path> entries;
    for (const auto& e : fs::directory_iterator(cache)) {
        const std::string name = e.path().filename().string();
        if (e.is_directory() && name[0] != '.' && name.rfind("prediction-", 0) != 0 &&
            name.rfind("brdf-lut-", 0) != 0)
            entries.push_back(e.path());
    }
    return entries.size() == 1 ? entries[0] : fs::path();
}

std::vector<unsigned char> pixels(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<unsigned char> p(size_t(spec.width) * spec.height * spec.nchannels);
    in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, p.data());
    return p;
}

// Fraction of channel values that differ by more than `tolerance` (of 255).
double differing(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, int tolerance) {
    if (a.size() != b.size() || a.empty()) return 1.0;
    size_t off = 0;
    for (size_t i = 0; i < a.size(); ++i) off += std::abs(int(a[i]) - int(b[i])) > tolerance;
    return double(off) / double(a.size());
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

// A bake's LUT belongs to one BRDF model (bake.json's brdf_lut.brdf): rendering it with
// the other is an error naming both, and writes nothing; with the same model it renders.
TEST(RenderBakeCache, ABakeForTheOtherBrdfModelIsRefused) {
    TempDir dir("render_brdf");
    Ran bake = facet::test::run_command(std::string(FACET_BAKE_PATH) + " builtin:sky --width 64 --size 16 --brdf thesis --out " +
                                        (dir / "bake").string());
    ASSERT_EQ(bake.status, 0) << bake.output;
    EXPECT_NE(read_text(dir / "bake" / "bake.json").find("\"brdf\": \"thesis\""), std::string::npos);
    Ran wrong = render_with_bake(" --ibl " + (dir / "bake").string() + " --out " + (dir / "wrong.png").string());
    EXPECT_EQ(wrong.status, 1) << wrong.output;
    EXPECT_NE(wrong.output.find((dir / "bake").string() + ": its BRDF LUT is for the thesis BRDF model, the render asks "
                                                         "for gltf"),
              std::string::npos)
        << wrong.output;
    EXPECT_FALSE(fs::exists(dir / "wrong.png"));
    Ran right = render_with_bake(" --brdf thesis --ibl " + (dir / "bake").string() + " --out " + (dir / "right.png").string());
    EXPECT_EQ(right.status, 0) << right.output;
    EXPECT_NE(read_text(dir / "right.json").find("\"brdf\": \"thesis\""), std::string::npos);
    Ran bad = render_with_bake(" --brdf phong --ibl " + (dir / "bake").string() + " --out " + (dir / "bad.png").string());
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_NE(bad.output.find("--brdf: expected gltf or thesis, got 'phong'"), std::string::npos) << bad.output;
}

TEST(RenderBakeCache, ASavedBakeRendersTheSameImageWithoutBaking) {
    TempDir dir("render_ibl");
    // One method named for both: the automatic choice is predicted against the environment's
    // texels, which a saved bake does not carry (it falls back to the dominant method).
    Ran fresh = render(" --shading dominant --no-bake-cache --out " + (dir / "fresh.png").string());
    ASSERT_EQ(fresh.status, 0) << fresh.output;
    EXPECT_GT(count(fresh.output, "baking ["), 0u) << fresh.output;
    Ran bake = facet::test::run_command(std::string(FACET_BAKE_PATH) + " builtin:sky --width 64 --size 16 --out " +
                                        (dir / "bake").string());
    ASSERT_EQ(bake.status, 0) << bake.output;
    Ran loaded = render_with_bake(" --shading dominant --ibl " + (dir / "bake").string() + " --out " +
                                  (dir / "loaded.png").string());
    ASSERT_EQ(loaded.status, 0) << loaded.output;
    EXPECT_EQ(count(loaded.output, "baking ["), 0u) << loaded.output;
    EXPECT_LE(differing(pixels(dir / "fresh.png"), pixels(dir / "loaded.png"), 1), 0.001);

    // A bake that is not there: one error naming the file, nothing written.
    Ran missing = render_with_bake(" --ibl " + (dir / "nowhere").string() + " --out " + (dir / "missing.png").string());
    EXPECT_EQ(missing.status, 1) << missing.output;
    EXPECT_NE(missing.output.find((dir / "nowhere").string()), std::string::npos) << missing.output;
    EXPECT_FALSE(fs::exists(dir / "missing.png"));
}

TEST(RenderBakeCache, TheSecondRunBakesNothingAndADamagedEntryIsRebuilt) {
    TempDir dir("render_cache");
    const std::string cache = " --bake-cache " + (dir / "cache").string();
    Ran first = render(cache + " --out " + (dir / "first.png").string());
    ASSERT_EQ(first.status, 0) << first.output;
    EXPECT_NE(first.output.find("bake cache: stored"), std::string::npos) << first.output;
    EXPECT_GT(count(first.output, "baking ["), 0u);
    Ran second = render(cache + " --out " + (dir / "second.png").string());
    ASSERT_EQ(second.status, 0) << second.output;
    EXPECT_NE(second.output.find("bake cache: using"), std::string::npos) << second.output;
    EXPECT_EQ(count(second.output, "baking ["), 0u) << second.output;
    EXPECT_EQ(pixels(dir / "first.png"), pixels(dir / "second.png"));

    // The entry holds what a load reads, no previews.
    fs::path entry = only_entry(dir / "cache");
    ASSERT_FALSE(entry.empty());
    EXPECT_TRUE(fs::exists(entry / "specular.ktx2"));
    EXPECT_TRUE(fs::exists(entry / "bake.json"));
    for (const char* preview : {"environment.png", "environment.hdr", "brdf_lut.png"})
        EXPECT_FALSE(fs::exists(entry / preview)) << preview;

    // Damage the entry's specular cube: detected, reported, baked again, never used.
    fs::resize_file(entry / "specular.ktx2", fs::file_size(entry / "specular.ktx2") / 2);
    Ran third = render(cache + " --out " + (dir / "third.png").string());
    ASSERT_EQ(third.status, 0) << third.output;
    EXPECT_NE(third.output.find("was damaged (specular.ktx2:"), std::string::npos) << third.output;
    EXPECT_GT(count(third.output, "baking ["), 0u);
    EXPECT_EQ(pixels(dir / "first.png"), pixels(dir / "third.png"));
}

// The cache checks sizes, the load each file's hash as it reads it: one flipped byte in the
// middle of the specular cube (same size) is found, reported and baked again.
TEST(RenderBakeCache, AFlippedByteInACachedSpecularCubeIsFoundAndRebuilt) {
    TempDir dir("render_cache_flip");
    const std::string cache = " --bake-cache " + (dir / "cache").string();
    Ran first = render(cache + " --out " + (dir / "first.png").string());
    ASSERT_EQ(first.status, 0) << first.output;
    const fs::path entry = only_entry(dir / "cache");
    ASSERT_FALSE(entry.empty());
    const fs::path specular = entry / "specular.ktx2";
    const auto size = fs::file_size(specular);
    {
        std::fstream f(specular, std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(std::streamoff(size / 2));
        const char byte = char(f.get() ^ 0x10);
        f.seekp(std::streamoff(size / 2));
        f.put(byte);
    }
    ASSERT_EQ(fs::file_size(specular), size);
    Ran second = render(cache + " --out " + (dir / "second.png").string());
    ASSERT_EQ(second.status, 0) << second.output;
    EXPECT_NE(second.output.find("was damaged (specular.ktx2: contents differ"), std::string::npos) << second.output;
    EXPECT_GT(count(second.output, "baking ["), 0u) << second.output;
    EXPECT_NE(second.output.find("bake cache: stored"), std::string::npos) << second.output;
    EXPECT_EQ(pixels(dir / "first.png"), pixels(dir / "second.png"));
    // The rebuilt entry is whole: the next run uses it.
    Ran third = render(cache + " --out " + (dir / "third.png").string());
    ASSERT_EQ(third.status, 0) << third.output;
    EXPECT_EQ(count(third.output, "baking ["), 0u) << third.output;
    EXPECT_EQ(count(third.output, "damaged"), 0u) << third.output;
}

// With --ibl DIR the environment is the bake's: NAME.json names the bake and its input,
// the skybox is the bake's cube (the image equals a fresh render of that environment),
// and --env beside --ibl is an error naming both.
TEST(RenderBakeCache, WithASavedBakeTheEnvironmentIsTheBakes) {
    TempDir dir("render_ibl_env");
    Ran bake = facet::test::run_command(std::string(FACET_BAKE_PATH) + " builtin:white --width 64 --size 16 --out " +
                                        (dir / "bake").string());
    ASSERT_EQ(bake.status, 0) << bake.output;
    Ran fresh = facet::test::run_command(std::string(FACET_RENDER_PATH) + model +
                                         " --shading dominant --env builtin:white --env-width 64 --ibl-size 16 "
                                         "--no-bake-cache --out " + (dir / "fresh.png").string());
    ASSERT_EQ(fresh.status, 0) << fresh.output;
    Ran loaded = render_with_bake(" --shading dominant --ibl " + (dir / "bake").string() + " --out " +
                                  (dir / "loaded.png").string());
    ASSERT_EQ(loaded.status, 0) << loaded.output;
    EXPECT_LE(differing(pixels(dir / "fresh.png"), pixels(dir / "loaded.png"), 1), 0.001);
    // Not the default environment's image (builtin:sky differs from builtin:white).
    Ran sky = render(" --no-bake-cache --out " + (dir / "sky.png").string());
    ASSERT_EQ(sky.status, 0) << sky.output;
    EXPECT_GT(differing(pixels(dir / "sky.png"), pixels(dir / "loaded.png"), 1), 0.1);
    const std::string json = read_text(dir / "loaded.json");
    EXPECT_NE(json.find("\"bake\": \"" + (dir / "bake").string() + "\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"source\": \"builtin:white\""), std::string::npos) << json;
    EXPECT_EQ(json.find("builtin:sky"), std::string::npos) << json;
    EXPECT_NE(json.find("\"skybox\": true"), std::string::npos) << json;

    Ran both = render_with_bake(" --env builtin:sky --ibl " + (dir / "bake").string() + " --out " +
                                (dir / "both.png").string());
    EXPECT_NE(both.status, 0) << both.output;
    EXPECT_NE(both.output.find("--env and --ibl"), std::string::npos) << both.output;
    EXPECT_FALSE(fs::exists(dir / "both.png"));
}

TEST(RenderBakeCache, TwoProcessesFillingOneEntryBothFinishWithTheSameImage) {
    TempDir dir("render_cache_race");
    const std::string cache = (dir / "cache").string();
    auto args = [&](const char* name) {
        return std::vector<std::string>{FACET_RENDER_PATH, "--model", "builtin:sphere", "--env", "builtin:sky",
                                        "--env-width", "64", "--ibl-size", "16", "--width", "64", "--height", "48",
                                        "--bake-cache", cache, "--out", (dir / name).string()};
    };
    facet::test::Spawned a(args("a.png")), b(args("b.png"));
    const auto end_a = a.wait(), end_b = b.wait();
    ASSERT_EQ(end_a.status, 0) << a.output();
    ASSERT_EQ(end_b.status, 0) << b.output();
    // One baked and stored the entry; the other waited for it and used it.
    EXPECT_EQ(count(a.output() + b.output(), "bake cache: stored"), 1u) << a.output() << b.output();
    EXPECT_EQ(count(a.output() + b.output(), "bake cache: using"), 1u);
    EXPECT_EQ(pixels(dir / "a.png"), pixels(dir / "b.png"));
}
