// facet-bake stopped by SIGINT or SIGTERM at several points (shader compilation, the
// accuracy budget's brute-force sums, between graph passes, just before the commit):
// exit 130 or 143 with one message, no output file and no temporary, an earlier bake
// byte-identical, every shader cache entry valid, and a rerun that matches an
// uninterrupted bake. Also: a second signal kills at once, and damaged cache entries are
// recompiled and rewritten. Points that timing alone cannot hit use the documented test
// hook FACET_TEST_PAUSE_AT (apps/interrupt.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>

#include "support/output_files.h"
#include "support/process.h"
#include "support/spawn.h"

namespace {

using namespace facet::test;

// Small enough for a few seconds on lavapipe; every pass and output file still there.
// `extra`: flags, or options that replace these values.
std::vector<std::string> bake_args(const fs::path& out, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = {FACET_BAKE_PATH, "builtin:sky",  "--width",     "64", "--size",
                                     "16",            "--irradiance-size", "8",     "--samples", "64",
                                     "--lut-size",    "16",           "--lut-samples", "64", "--out", out.string(),
                                     // Every bake computes its LUT, so that bake.json's passes compare.
                                     "--no-lut-cache"};
    for (size_t i = 0; i < extra.size(); ++i) {
        const bool has_value = i + 1 < extra.size() && extra[i + 1].rfind("--", 0) != 0;
        auto known = std::find(args.begin(), args.end(), extra[i]);
        if (has_value && known != args.end()) {
            *(known + 1) = extra[++i];
            continue;
        }
        args.push_back(extra[i]);
        if (has_value) args.push_back(extra[++i]);
    }
    return args;
}

std::string command_line(const std::vector<std::string>& args) {
    std::string line;
    for (const std::string& a : args) line += "'" + a + "' ";
    return line;
}

// An uninterrupted bake of the same settings (no cache), to compare reruns with.
const fs::path& reference_bake() {
    static TempDir dir("interrupt_bake_reference");
    static const bool made = [] {
        Ran r = run_command(command_line(bake_args(dir / "out")));
        EXPECT_EQ(r.status, 0) << r.output;
        return true;
    }();
    (void)made;
    static const fs::path out = dir / "out";
    return out;
}

struct Stopped {
    Spawned::Ended end;
    std::string output;
};

// Starts the bake, waits for `cue` in its output, sends `sig`, waits for the end.
Stopped interrupt_at(const std::vector<std::string>& args, const std::string& cue, int sig,
                     const std::vector<std::string>& env = {}) {
    Spawned bake(args, env);
    EXPECT_TRUE(bake.started());
    EXPECT_TRUE(bake.wait_for(cue)) << "never printed '" << cue << "':\n" << bake.output();
    bake.signal(sig);
    Stopped s{bake.wait(), ""};
    s.output = bake.output();
    return s;
}

void expect_stopped_by(const Stopped& s, int sig) {
    EXPECT_TRUE(s.end.exited) << s.output;
    EXPECT_EQ(s.end.status, 128 + sig) << s.output;
    const std::string message =
        std::string("facet-bake: interrupted by ") + (sig == SIGINT ? "SIGINT" : "SIGTERM") + "; no output written";
    EXPECT_NE(s.output.find(message), std::string::npos) << s.output;
    EXPECT_EQ(s.output.find("facet-bake: error"), std::string::npos) << s.output;
    EXPECT_EQ(s.output.find("alidation"), std::string::npos) << s.output;  // teardown was clean
}

TEST(InterruptBake, SigintDuringShaderCompilationWritesNothingAndKeepsTheCacheValid) {
    const fs::path& reference = reference_bake();
    TempDir dir("interrupt_bake_shaders");
    const auto args = bake_args(dir / "out", {"--shader-cache", (dir / "cache").string()});
    // Paused between the first shaders (the BRDF LUT's, for its cache key) and the bake's:
    // the cache starts empty, so the rest are compiled only by the rerun.
    const Stopped s = interrupt_at(args, "paused at shaders", SIGINT, {"FACET_TEST_PAUSE_AT=shaders"});
    expect_stopped_by(s, SIGINT);
    EXPECT_EQ(s.output.find("running"), std::string::npos) << "not stopped before the passes:\n" << s.output;
    EXPECT_TRUE(snapshot(dir / "out").empty()) << names(snapshot(dir / "out")).size() << " files left";
    size_t compiled_before_the_signal = 0;
    EXPECT_TRUE(shader_cache_is_valid(dir / "cache", &compiled_before_the_signal));

    Ran rerun = run_command(command_line(args));
    ASSERT_EQ(rerun.status, 0) << rerun.output;
    expect_same_outputs(reference, dir / "out");
    size_t entries = 0;
    EXPECT_TRUE(shader_cache_is_valid(dir / "cache", &entries));
    EXPECT_LT(compiled_before_the_signal, entries);
    EXPECT_GE(entries, 8u);
}

TEST(InterruptBake, SigtermBetweenPassesKeepsTheEarlierBakeByteIdentical) {
    TempDir dir("interrupt_bake_passes");
    Ran first = run_command(command_line(bake_args(dir / "out")));
    ASSERT_EQ(first.status, 0) << first.output;
    const auto before = snapshot(dir / "out");
    // --force: the same settings would otherwise be skipped as up to date.
    const Stopped s = interrupt_at(bake_args(dir / "out", {"--force"}), "paused at bake", SIGTERM,
                                   {"FACET_TEST_PAUSE_AT=bake"});
    expect_stopped_by(s, SIGTERM);
    EXPECT_EQ(s.output.find("[2/"), std::string::npos) << "ran on after the signal:\n" << s.output;
    EXPECT_TRUE(snapshot(dir / "out") == before) << "the earlier bake changed";
}

TEST(InterruptBake, SigintInTheBudgetsBruteForceSumsStopsPromptly) {
    TempDir dir("interrupt_bake_budget");
    Ran first = run_command(command_line(bake_args(dir / "out")));
    ASSERT_EQ(first.status, 0) << first.output;
    const auto before = snapshot(dir / "out");
    // Nothing meets 1e-9: every candidate is measured against sums over 512x256 texels
    // (seconds of CPU work on any device); the signal comes after the first.
    const auto args = bake_args(dir / "out", {"--width", "512", "--target-error", "1e-9"});
    Spawned bake(args);
    ASSERT_TRUE(bake.wait_for("budget: irradiance")) << bake.output();
    const auto sent = std::chrono::steady_clock::now();
    bake.signal(SIGINT);
    const Stopped s{bake.wait(), bake.output()};
    const double stop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    expect_stopped_by(s, SIGINT);
    EXPECT_EQ(s.output.find("budget: specular"), std::string::npos) << s.output;
    EXPECT_LT(stop_s, 5.0);
    std::printf("stopped %.3f s after SIGINT\n", stop_s);
    EXPECT_TRUE(snapshot(dir / "out") == before) << "the earlier bake changed";
}

TEST(InterruptBake, SigintJustBeforeTheCommitRemovesEveryTemporary) {
    const fs::path& reference = reference_bake();
    TempDir dir("interrupt_bake_commit");
    Ran first = run_command(command_line(bake_args(dir / "out", {"--lut-size", "8"})));
    ASSERT_EQ(first.status, 0) << first.output;
    const auto before = snapshot(dir / "out");
    const auto args = bake_args(dir / "out", {"--graph-dot", (dir / "graph.dot").string()});
    Spawned bake(args, {"FACET_TEST_PAUSE_AT=commit"});
    ASSERT_TRUE(bake.wait_for("paused at commit")) << bake.output();
    // Every new file is written, under a hidden temporary name; the old ones are intact.
    const auto staged = temporaries_in(dir / "out");
    EXPECT_EQ(staged.size(), before.size()) << bake.output();
    for (const std::string& name : staged) EXPECT_NE(name.find(".partial-"), std::string::npos) << name;
    EXPECT_EQ(temporaries_in(dir.path).size(), 1u);  // graph.dot's
    EXPECT_TRUE(snapshot(dir / "out").size() == 2 * before.size());
    bake.signal(SIGINT);
    const Stopped s{bake.wait(), bake.output()};
    expect_stopped_by(s, SIGINT);
    EXPECT_TRUE(snapshot(dir / "out") == before) << "the earlier bake changed";
    EXPECT_FALSE(fs::exists(dir / "graph.dot"));
    EXPECT_TRUE(temporaries_in(dir.path).empty());

    Ran rerun = run_command(command_line(bake_args(dir / "out")));
    ASSERT_EQ(rerun.status, 0) << rerun.output;
    expect_same_outputs(reference, dir / "out");
}

TEST(InterruptBake, ASecondSignalWhileStoppingKillsAtOnce) {
    TempDir dir("interrupt_bake_twice");
    Spawned bake(bake_args(dir / "out"), {"FACET_TEST_PAUSE_AT=bake,stopping"});
    ASSERT_TRUE(bake.wait_for("paused at bake")) << bake.output();
    bake.signal(SIGINT);
    ASSERT_TRUE(bake.wait_for("paused at stopping")) << bake.output();
    bake.signal(SIGINT);
    const Spawned::Ended end = bake.wait(10);
    EXPECT_FALSE(end.exited) << bake.output();
    EXPECT_EQ(end.signal, SIGINT) << bake.output();
    EXPECT_TRUE(snapshot(dir / "out").empty());
}

// A cache entry cut short (a writer killed outright, a full disk), one with a changed
// byte, one empty and one that is not an entry at all: each is a warning, compiled again
// and rewritten; the outputs are those of an uninterrupted bake.
TEST(InterruptBake, DamagedShaderCacheEntriesAreRecompiledAndRewritten) {
    const fs::path& reference = reference_bake();
    TempDir dir("interrupt_bake_cache");
    const fs::path cache = dir / "cache";
    Ran first = run_command("FACET_SHADER_CACHE=" + cache.string() + " " + command_line(bake_args(dir / "a")));
    ASSERT_EQ(first.status, 0) << first.output;
    size_t entries = 0;
    ASSERT_TRUE(shader_cache_is_valid(cache, &entries));
    ASSERT_GE(entries, 4u);
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(cache)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    fs::resize_file(files[0], fs::file_size(files[0]) - 5);
    {
        std::fstream f(files[1], std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(40);
        const char byte = char(f.get());
        f.seekp(40);
        f.put(char(byte ^ 0x5a));
    }
    fs::resize_file(files[2], 0);
    std::ofstream(files[3], std::ios::binary | std::ios::trunc) << "not a shader cache entry at all";
    EXPECT_FALSE(shader_cache_is_valid(cache));

    Ran second = run_command("FACET_SHADER_CACHE=" + cache.string() + " " + command_line(bake_args(dir / "b")));
    ASSERT_EQ(second.status, 0) << second.output;
    for (int i = 0; i < 4; ++i)
        EXPECT_NE(second.output.find(files[size_t(i)].filename().string() + ": shader cache entry is damaged"),
                  std::string::npos)
            << second.output;
    EXPECT_EQ(second.output.find("facet-bake: error"), std::string::npos) << second.output;
    expect_same_outputs(reference, dir / "b");
    size_t after = 0;
    EXPECT_TRUE(shader_cache_is_valid(cache, &after));
    EXPECT_EQ(after, entries);
    // Whole again: a third bake reads every entry without a warning.
    Ran third = run_command(command_line(bake_args(dir / "c", {"--shader-cache", cache.string()})));
    ASSERT_EQ(third.status, 0) << third.output;
    EXPECT_EQ(third.output.find("damaged"), std::string::npos) << third.output;
}

}  // namespace
