// The programs' start-up (README "Start-up and caches"): the shader cache is on by
// default, in $XDG_CACHE_HOME/facet/shaders, so a second start compiles nothing
// (FACET_LOG=debug prints one line per glslang compile); --no-shader-cache writes nothing;
// --shader-cache with --no-shader-cache is refused by every program; a damaged entry is
// compiled again and replaced, an unwritable directory is a warning, and processes that
// share one cache at once leave it whole. And OpenImageIO is loaded only by a process that
// reads or writes an image (the engine's image module, io/image_module.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include <facet/io/image_io.h>
#include "support/output_files.h"
#include "support/process.h"

namespace {

using namespace facet::test;

// The user's environment as the tests see it, less what would choose the cache for them.
const std::string clean_env = "env -u FACET_SHADER_CACHE -u FACET_SHADER_DIR FACET_LOG=debug ";

// A small render: a few seconds on lavapipe, every pass of the bake and the frame.
std::string render(const fs::path& xdg, const fs::path& out, const std::string& flags = "",
                   const std::string& env = "builtin:sky") {
    return clean_env + "XDG_CACHE_HOME=" + xdg.string() + " " + FACET_RENDER_PATH + " --model builtin:sphere --env " +
           env + " --no-bake-cache --width 32 --height 24 --env-width 64"
           " --ibl-samples 64 --out " + out.string() + " " + flags;
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

const std::string compiled = "shader compiled by glslang";
const std::string from_cache = "shader read from the shader cache";

TEST(ShaderCache, OnByDefaultSoASecondStartCompilesNothing) {
    TempDir dir("shader_cache_default");
    const fs::path cache = dir / "xdg" / "facet" / "shaders";
    Ran first = run_command(render(dir / "xdg", dir / "a.png"));
    ASSERT_EQ(first.status, 0) << first.output;
    EXPECT_GT(count(first.output, compiled), 3u) << first.output;
    EXPECT_EQ(count(first.output, from_cache), 0u) << first.output;
    size_t entries = 0;
    ASSERT_TRUE(shader_cache_is_valid(cache, &entries));
    EXPECT_EQ(entries, count(first.output, compiled));
    const auto before = snapshot(cache);

    Ran second = run_command(render(dir / "xdg", dir / "b.png"));
    ASSERT_EQ(second.status, 0) << second.output;
    EXPECT_EQ(count(second.output, compiled), 0u) << second.output;
    EXPECT_EQ(count(second.output, from_cache), entries) << second.output;
    EXPECT_EQ(snapshot(cache), before);
    EXPECT_EQ(file_bytes(dir / "a.png"), file_bytes(dir / "b.png"));

    // facet-bake shares the cache: what the render compiled, it reads.
    const std::string bake = clean_env + "XDG_CACHE_HOME=" + (dir / "xdg").string() + " " + FACET_BAKE_PATH +
                             " builtin:sky --width 64 --size 16 --irradiance-size 8 --samples 64 --lut-size 16"
                             " --lut-samples 64 --out ";
    Ran baked = run_command(bake + (dir / "bake1").string());
    ASSERT_EQ(baked.status, 0) << baked.output;
    EXPECT_GT(count(baked.output, from_cache), 0u) << baked.output;
    Ran again = run_command(bake + (dir / "bake2").string());
    ASSERT_EQ(again.status, 0) << again.output;
    EXPECT_EQ(count(again.output, compiled), 0u) << again.output;
}

TEST(ShaderCache, NoShaderCacheWritesNothing) {
    TempDir dir("shader_cache_off");
    Ran r = run_command(render(dir / "xdg", dir / "a.png", "--no-shader-cache"));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_GT(count(r.output, compiled), 3u) << r.output;
    EXPECT_FALSE(fs::exists(dir / "xdg" / "facet" / "shaders"));
    // FACET_SHADER_CACHE is only a default: the flag wins.
    Ran env = run_command("FACET_SHADER_CACHE=" + (dir / "env").string() + " " + FACET_RENDER_PATH +
                          " --model builtin:sphere --env none --width 8 --height 8 --no-shader-cache --out " +
                          (dir / "b.png").string());
    ASSERT_EQ(env.status, 0) << env.output;
    EXPECT_FALSE(fs::exists(dir / "env"));
}

TEST(ShaderCache, EveryProgramOffersItAndRefusesBothFlags) {
    TempDir dir("shader_cache_flags");
    // Each with what it needs besides, so that the flags are what is refused.
    const std::vector<std::string> programs = {std::string(FACET_BAKE_PATH) + " builtin:sky --out " + (dir / "bake").string(),
                                               std::string(FACET_RENDER_PATH) + " --out " + (dir / "a.png").string(),
                                               FACET_VIEWER_PATH,
                                               std::string(FACET_BENCH_PATH) + " render",
                                               std::string(FACET_BENCH_PATH) + " sweep",
                                               std::string(FACET_BENCH_PATH) + " accuracy"};
    for (const std::string& program : programs) {
        Ran help = run_command(program + " --help");
        EXPECT_EQ(help.status, 0) << program << help.output;
        EXPECT_NE(help.output.find("--shader-cache DIR"), std::string::npos) << program << help.output;
        EXPECT_NE(help.output.find("--no-shader-cache"), std::string::npos) << program << help.output;
        Ran both = run_command(program + " --shader-cache " + (dir / "cache").string() + " --no-shader-cache");
        EXPECT_EQ(both.status, 2) << program << both.output;
        EXPECT_NE(both.output.find("error: --shader-cache and --no-shader-cache exclude each other"),
                  std::string::npos)
            << program << both.output;
    }
    EXPECT_TRUE(snapshot(dir.path).empty());
}

// One entry cut short, one with a changed byte: each a warning, compiled again and
// replaced; the image is the same.
TEST(ShaderCache, DamagedEntriesAreCompiledAgainAndReplaced) {
    TempDir dir("shader_cache_damaged");
    const fs::path cache = dir / "xdg" / "facet" / "shaders";
    Ran first = run_command(render(dir / "xdg", dir / "a.png"));
    ASSERT_EQ(first.status, 0) << first.output;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(cache)) files.push_back(e.path());
    ASSERT_GE(files.size(), 2u);
    std::sort(files.begin(), files.end());
    const auto whole = snapshot(cache);
    fs::resize_file(files[0], fs::file_size(files[0]) / 2);
    {
        std::fstream f(files[1], std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(100);
        const char byte = char(f.get());
        f.seekp(100);
        f.put(char(byte ^ 0x21));
    }
    ASSERT_FALSE(shader_cache_is_valid(cache));

    Ran second = run_command(render(dir / "xdg", dir / "b.png"));
    ASSERT_EQ(second.status, 0) << second.output;
    for (int i = 0; i < 2; ++i)
        EXPECT_NE(second.output.find(files[size_t(i)].filename().string() + ": shader cache entry is damaged"),
                  std::string::npos)
            << second.output;
    EXPECT_EQ(count(second.output, compiled), 2u) << second.output;
    EXPECT_EQ(snapshot(cache), whole);
    EXPECT_EQ(file_bytes(dir / "a.png"), file_bytes(dir / "b.png"));
}

TEST(ShaderCache, UnwritableDirectoryIsAWarning) {
    TempDir dir("shader_cache_unwritable");
    std::ofstream(dir / "file") << "a file, not a directory";
    const fs::path cache = dir / "file" / "cache";  // can never be created, even by root
    Ran r = run_command(render(dir / "xdg", dir / "a.png", "--shader-cache " + cache.string()));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(count(r.output, "cannot write to the shader cache"), 1u) << r.output;
    EXPECT_GT(count(r.output, compiled), 3u) << r.output;
    EXPECT_TRUE(fs::exists(dir / "a.png"));
}

// Two programs filling one empty cache at once (as ctest -j2 does): both succeed, every
// entry is whole, no temporary is left, and a third start compiles nothing.
TEST(ShaderCache, ProcessesSharingOneCacheAtOnce) {
    TempDir dir("shader_cache_shared");
    const fs::path cache = dir / "xdg" / "facet" / "shaders";
    Ran both = run_command("(" + render(dir / "xdg", dir / "a.png") + " > " + (dir / "a.log").string() + " 2>&1; echo $? > " +
                           (dir / "a.status").string() + ") & (" + render(dir / "xdg", dir / "b.png") + " > " +
                           (dir / "b.log").string() + " 2>&1; echo $? > " + (dir / "b.status").string() + "); wait");
    for (const char* name : {"a", "b"})
        EXPECT_EQ(file_bytes(dir / (std::string(name) + ".status")), "0\n") << file_bytes(dir / (std::string(name) + ".log"));
    EXPECT_EQ(file_bytes(dir / "a.png"), file_bytes(dir / "b.png"));
    size_t entries = 0;
    EXPECT_TRUE(shader_cache_is_valid(cache, &entries));  // also: nothing but entries
    EXPECT_GT(entries, 3u);
    Ran third = run_command(render(dir / "xdg", dir / "c.png"));
    ASSERT_EQ(third.status, 0) << third.output;
    EXPECT_EQ(count(third.output, compiled), 0u) << third.output;
}

// The dynamic linker's own record (LD_DEBUG=files names every library it loads): a start
// that writes no image loads no OpenImageIO, and neither does writing a PNG (Facet's own
// encoder); reading an image other than a Radiance .hdr (an .exr environment) loads the
// module, and it.
TEST(ImageModule, OpenImageIOIsLoadedOnlyForImages) {
    TempDir dir("image_module_loading");
    Ran help = run_command("LD_DEBUG=files " + std::string(FACET_RENDER_PATH) + " --help");
    ASSERT_EQ(help.status, 0) << help.output;
    EXPECT_NE(help.output.find("file=libvulkan.so"), std::string::npos) << help.output;
    EXPECT_EQ(help.output.find("libOpenImageIO"), std::string::npos) << help.output;
    EXPECT_EQ(help.output.find("libfacet_image_io"), std::string::npos) << help.output;

    auto tail = [](const std::string& text) { return text.substr(text.size() - std::min<size_t>(text.size(), 4000)); };
    Ran wrote = run_command("LD_DEBUG=files " + render(dir / "xdg", dir / "a.png"));
    ASSERT_EQ(wrote.status, 0) << tail(wrote.output);
    EXPECT_TRUE(fs::exists(dir / "a.png"));
    EXPECT_EQ(wrote.output.find("libfacet_image_io"), std::string::npos);
    EXPECT_EQ(wrote.output.find("libOpenImageIO"), std::string::npos);

    const std::vector<float> sky(64 * 32 * 4, 0.5f);
    ASSERT_TRUE(facet::write_hdr_image((dir / "sky.exr").string(), 64, 32, sky));
    Ran read = run_command("LD_DEBUG=files " + render(dir / "xdg", dir / "b.png", "", (dir / "sky.exr").string()));
    ASSERT_EQ(read.status, 0) << tail(read.output);
    EXPECT_NE(read.output.find("file=libfacet_image_io.so"), std::string::npos);
    EXPECT_NE(read.output.find("file=libOpenImageIO.so"), std::string::npos);
}

}  // namespace
