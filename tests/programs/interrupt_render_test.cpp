// facet-render stopped by SIGINT or SIGTERM during its bake, during a reference render
// and just before the commit: exit 130 or 143 with one message, the image, NAME.json and
// the views of an earlier run byte-identical, no temporary, a valid shader cache, and a
// rerun equal to an uninterrupted render. facet-viewer closes its window on SIGTERM and
// tears down cleanly. FACET_TEST_PAUSE_AT is the documented test hook (apps/interrupt.h).
#include <gtest/gtest.h>

#include <csignal>
#include <thread>

#include "support/output_files.h"
#include "support/process.h"
#include "support/spawn.h"
#include "support/xvfb.h"

namespace {

using namespace facet::test;

std::vector<std::string> render_args(const fs::path& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {FACET_RENDER_PATH, "--model", "builtin:sphere", "--env",  "builtin:sky",
                                     "--env-width",     "64",      "--ibl-size",     "16",     "--width",
                                     "64",              "--height", "64",            "--aov",  "normal,D",
                                     "--out",           out.string(), "--no-bake-cache"};  // every run bakes
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

std::string command_line(const std::vector<std::string>& args) {
    std::string line;
    for (const std::string& a : args) line += "'" + a + "' ";
    return line;
}

void expect_stopped_by(const Spawned::Ended& end, const std::string& output, int sig) {
    EXPECT_TRUE(end.exited) << output;
    EXPECT_EQ(end.status, 128 + sig) << output;
    const std::string message =
        std::string("facet-render: interrupted by ") + (sig == SIGINT ? "SIGINT" : "SIGTERM") + "; no output written";
    EXPECT_NE(output.find(message), std::string::npos) << output;
    EXPECT_EQ(output.find("facet-render: error"), std::string::npos) << output;
    EXPECT_EQ(output.find("alidation"), std::string::npos) << output;
}

// An earlier render in `dir` (a different exposure, so that any change would show).
std::map<std::string, std::string> earlier_render(const fs::path& dir) {
    Ran r = run_command(command_line(render_args(dir / "a.png", {"--exposure", "2"})));
    EXPECT_EQ(r.status, 0) << r.output;
    const auto files = snapshot(dir);
    EXPECT_EQ(files.size(), 4u);  // a.png, a.json, a.normal.exr, a.D.exr
    return files;
}

TEST(InterruptRender, SigintDuringTheBakeKeepsTheEarlierImageAndARerunMatches) {
    TempDir dir("interrupt_render_bake");
    fs::create_directories(dir / "out");
    fs::create_directories(dir / "reference");
    const auto before = earlier_render(dir / "out");
    const auto args = render_args(dir / "out" / "a.png", {"--shader-cache", (dir / "cache").string()});
    Spawned render(args);
    ASSERT_TRUE(render.wait_for("baking [1/")) << render.output();
    render.signal(SIGINT);
    const Spawned::Ended end = render.wait();
    expect_stopped_by(end, render.output(), SIGINT);
    EXPECT_TRUE(snapshot(dir / "out") == before) << "the earlier render changed";
    EXPECT_TRUE(shader_cache_is_valid(dir / "cache"));

    Ran rerun = run_command(command_line(args));
    ASSERT_EQ(rerun.status, 0) << rerun.output;
    Ran uninterrupted = run_command(command_line(render_args(dir / "reference" / "a.png")));
    ASSERT_EQ(uninterrupted.status, 0) << uninterrupted.output;
    expect_same_outputs(dir / "reference", dir / "out");
    EXPECT_TRUE(shader_cache_is_valid(dir / "cache"));
}

TEST(InterruptRender, SigtermDuringAReferenceRenderKeepsTheEarlierImage) {
    TempDir dir("interrupt_render_reference");
    const auto before = earlier_render(dir.path);
    // A noise target no run reaches: only the signal ends it.
    const auto args = render_args(dir / "a.png", {"--reference", "--reference-noise", "0.0001",
                                                  "--reference-samples", "1048576", "--shader-cache",
                                                  (dir / "cache").string()});
    fs::create_directories(dir / "cache");
    Spawned render(args);
    ASSERT_TRUE(render.wait_for("reference: ")) << render.output();
    const auto sent = std::chrono::steady_clock::now();
    render.signal(SIGTERM);
    const Spawned::Ended end = render.wait();
    const double stop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    expect_stopped_by(end, render.output(), SIGTERM);
    EXPECT_LT(stop_s, 5.0);
    std::printf("stopped %.3f s after SIGTERM\n", stop_s);
    EXPECT_TRUE(snapshot(dir.path) == before) << "the earlier render changed";
    EXPECT_TRUE(shader_cache_is_valid(dir / "cache"));
}

TEST(InterruptRender, SigintJustBeforeTheCommitRemovesEveryTemporary) {
    TempDir dir("interrupt_render_commit");
    const auto before = earlier_render(dir.path);
    Spawned render(render_args(dir / "a.png"), {"FACET_TEST_PAUSE_AT=commit"});
    ASSERT_TRUE(render.wait_for("paused at commit")) << render.output();
    const auto staged = temporaries_in(dir.path);
    EXPECT_EQ(staged.size(), 4u) << render.output();
    render.signal(SIGINT);
    const Spawned::Ended end = render.wait();
    expect_stopped_by(end, render.output(), SIGINT);
    EXPECT_TRUE(snapshot(dir.path) == before) << "the earlier render changed";
}

TEST(InterruptViewer, SigtermClosesTheWindowAndTearsDownCleanly) {
    static Xvfb xvfb;
    ASSERT_TRUE(xvfb.running()) << "Xvfb did not start";
    std::string display = xvfb.env();
    display.pop_back();  // "DISPLAY=:N "
    Spawned viewer({FACET_VIEWER_PATH, "--model", "builtin:sphere", "--env", "builtin:sky", "--env-width", "64",
                    "--ibl-size", "16", "--width", "64", "--height", "64", "--script", "frames 1000000"},
                   {display});
    ASSERT_TRUE(viewer.wait_for("script: frames")) << viewer.output();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a few frames
    viewer.signal(SIGTERM);
    const Spawned::Ended end = viewer.wait();
    EXPECT_TRUE(end.exited) << viewer.output();
    EXPECT_EQ(end.status, 128 + SIGTERM) << viewer.output();
    EXPECT_NE(viewer.output().find("facet-viewer: interrupted by SIGTERM; closing the window"), std::string::npos)
        << viewer.output();
    EXPECT_NE(viewer.output().find("facet-viewer: rendered "), std::string::npos) << viewer.output();
    EXPECT_EQ(viewer.output().find("alidation"), std::string::npos) << viewer.output();
}

}  // namespace
