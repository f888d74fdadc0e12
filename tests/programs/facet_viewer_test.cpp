// facet-viewer under Xvfb on lavapipe (a private server per test process), scripted: its
// screenshot matches facet-render's image for the same settings, sessions that switch
// everything are validation-clean (ctest sets FACET_VALIDATION=1) and exit cleanly; bad
// arguments are clear errors.
#include <gtest/gtest.h>

#include "support/process.h"
#include "support/xvfb.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include <OpenImageIO/imageio.h>

namespace {

namespace fs = std::filesystem;

using facet::test::Ran;

Ran run(const std::string& command_line) { return facet::test::run_command(command_line); }

std::vector<float> pixels(const std::string& path, int* w, int* h) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    *w = in->spec().width;
    *h = in->spec().height;
    std::vector<float> v(size_t(*w) * *h * in->spec().nchannels);
    in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, v.data());
    return v;
}

// "rendered N frames" at the viewer's exit; -1 without it.
int frames_rendered(const std::string& log) {
    const size_t at = log.find("rendered ");
    return at == std::string::npos ? -1 : std::atoi(log.c_str() + at + 9);
}

size_t count(const std::string& text, const std::string& part) {
    size_t n = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

// Mean absolute difference of two images in 8-bit levels; a large value when either is
// missing or their sizes differ.
double mean_difference(const std::string& a_path, const std::string& b_path) {
    int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
    const auto a = pixels(a_path, &w1, &h1);
    const auto b = pixels(b_path, &w2, &h2);
    if (a.empty() || a.size() != b.size()) return 1e9;
    double diff = 0;
    for (size_t i = 0; i < a.size(); ++i) diff += std::abs(a[i] - b[i]);
    return diff / double(a.size()) * 255.0;
}

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_viewer_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
};

// How far the viewer's screenshot `shot` is from facet-render's image of the same settings
// (mean difference in 8-bit steps; 1e9 when facet-render failed or the sizes differ).
double difference_from_render(const TempDir& dir, const std::string& settings, const std::string& shot) {
    const std::string rendered = (dir.path / "render.png").string();
    Ran r = run(std::string(FACET_RENDER_PATH) + " " + settings + " --out " + rendered);
    EXPECT_EQ(r.status, 0) << r.output;
    return r.status == 0 ? mean_difference(shot, rendered) : 1e9;
}

// Each test process gets its own X server (Xvfb, as on CI machines without a display).
facet::test::Xvfb& xvfb() {
    static facet::test::Xvfb server;
    return server;
}

std::string viewer_command() {
    EXPECT_TRUE(xvfb().running()) << "Xvfb did not start";
    return xvfb().env() + FACET_VIEWER_PATH;
}

TEST(FacetViewer, ScreenshotMatchesFacetRender) {
    TempDir dir;
    for (const std::string scene : {"--model builtin:spheres --env builtin:sky --env-width 256",
                                    "--model builtin:sphere --preset gold --env builtin:sky --env-width 256 "
                                    "--tonemap aces --light 'point pos=2,2,3 intensity=30'"}) {
        const std::string settings = scene + " --width 160 --height 120";
        Ran shown = run(viewer_command() + " " + settings + " --frames 3 --screenshot " + (dir.path / "viewer.png").string());
        ASSERT_EQ(shown.status, 0) << shown.output;
        EXPECT_EQ(shown.output.find("Validation"), std::string::npos) << shown.output;
        EXPECT_NE(shown.output.find("rendered 3 frames"), std::string::npos) << shown.output;
        // Steady frames reuse the graph's images (GraphExecutor) and the frame's buffers.
        EXPECT_NE(shown.output.find("(after the first: 0 device allocations, 0 images created)"), std::string::npos)
            << shown.output;
        Ran rendered = run(std::string(FACET_RENDER_PATH) + " " + settings + " --out " +
                           (dir.path / "render.png").string());
        ASSERT_EQ(rendered.status, 0) << rendered.output;
        int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
        const auto a = pixels((dir.path / "viewer.png").string(), &w1, &h1);
        const auto b = pixels((dir.path / "render.png").string(), &w2, &h2);
        ASSERT_EQ(w1, 160);
        ASSERT_EQ(h1, 120);
        ASSERT_EQ(a.size(), b.size());
        double diff = 0;
        for (size_t i = 0; i < a.size(); ++i) diff += std::abs(a[i] - b[i]);
        EXPECT_LT(diff / double(a.size()) * 255.0, 0.5) << "mean difference in 8-bit levels: " << scene;
    }
}

// A scripted session that switches model, environment, component view, material and
// window size: validation-clean throughout, a clean exit (the validation layer reports any
// Vulkan object left at teardown), and a screenshot of the new size.
TEST(FacetViewer, ScriptedSessionSwitchesEverything) {
    TempDir dir;
    const std::string shot = (dir.path / "switched.png").string();
    // Loads run in the background while frames go on: "wait" holds the script until each is in use.
    Ran r = run(viewer_command() + " --model builtin:spheres --env builtin:sky --env-width 128 --width 160 --height 120 "
                         "--script 'frames 1; model builtin:sphere; wait; frames 1; env builtin:white; wait; frames 1; "
                         "view D; frames 1; view specular; size 200x150; frames 2; screenshot " + shot +
                "; preset gold; view final; env builtin:sky; wait; frames 1; skybox off; tonemap aces; frames 1'");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    EXPECT_GE(frames_rendered(r.output), 8) << r.output;
    EXPECT_EQ(count(r.output, "swapped in "), 3) << r.output;
    int w = 0, h = 0;
    const auto p = pixels(shot, &w, &h);
    EXPECT_EQ(w, 200);
    EXPECT_EQ(h, 150);
    Ran bad = run(std::string(FACET_VIEWER_PATH) + " --script 'view sparkle'");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.output.find("unknown view"), std::string::npos) << bad.output;
}

// Issue 15, a viewer that never freezes: another environment loads and bakes on a worker
// thread while the window keeps drawing the old one (frames counted while the load ran,
// and the steady frames still allocate nothing); the new one is swapped in between frames
// and matches facet-render. No bake cache, so that the load really bakes.
TEST(FacetViewer, EnvironmentSwitchBakesWhileFramesGoOn) {
    TempDir dir;
    const std::string common = "--model builtin:spheres --env-width 512 --width 160 --height 120";
    const std::string shot = (dir.path / "switched.png").string();
    Ran shown = run(viewer_command() + " " + common + " --env none --no-bake-cache --script 'frames 2; env builtin:sky; "
                    "wait; frames 2; screenshot " + shot + "'");
    ASSERT_EQ(shown.status, 0) << shown.output;
    EXPECT_EQ(shown.output.find("Validation"), std::string::npos) << shown.output;
    const size_t swapped = shown.output.find("swapped in builtin:spheres under builtin:sky after ");
    ASSERT_NE(swapped, std::string::npos) << shown.output;
    const size_t meanwhile = shown.output.find("ms: ", swapped);
    ASSERT_NE(meanwhile, std::string::npos) << shown.output;
    EXPECT_GT(std::atoi(shown.output.c_str() + meanwhile + 4), 0) << "frames drawn while the load ran\n" << shown.output;
    // The render thread allocated nothing in its steady frames while the worker baked.
    EXPECT_NE(shown.output.find("(after the first: 0 device allocations, 0 images created)"), std::string::npos)
        << shown.output;
    EXPECT_LT(difference_from_render(dir, common + " --env builtin:sky", shot), 0.5);
}

// Choosing another environment while one bakes ("wait bake": its bake has run a pass)
// stops the stale bake at its next safe point (or drops its result when it ended first,
// as on a fast GPU); the second one is what is shown.
TEST(FacetViewer, SecondSwitchCancelsTheFirst) {
    TempDir dir;
    const std::string common = "--model builtin:spheres --env-width 256 --width 160 --height 120";
    const std::string shot = (dir.path / "second.png").string();
    Ran shown = run(viewer_command() + " " + common + " --env none --no-bake-cache --script 'frames 1; env builtin:sky; "
                    "wait bake; env builtin:white; wait; frames 1; screenshot " + shot + "'");
    ASSERT_EQ(shown.status, 0) << shown.output;
    EXPECT_EQ(shown.output.find("Validation"), std::string::npos) << shown.output;
    EXPECT_NE(shown.output.find("cancelling the load of builtin:spheres under builtin:sky: superseded by "
                                "builtin:spheres under builtin:white"),
              std::string::npos)
        << shown.output;
    // Where it stopped depends on the machine's speed: mid-bake here, at once on a fast GPU.
    EXPECT_TRUE(shown.output.find("stopped the load of builtin:spheres under builtin:sky at its safe point") !=
                    std::string::npos ||
                shown.output.find("the superseded load of builtin:spheres under builtin:sky ended") != std::string::npos ||
                shown.output.find("the load of builtin:spheres under builtin:sky was superseded before it started") !=
                    std::string::npos)
        << shown.output;
    EXPECT_EQ(shown.output.find("swapped in builtin:spheres under builtin:sky"), std::string::npos) << shown.output;
    EXPECT_EQ(count(shown.output, "swapped in builtin:spheres under builtin:white"), 1u) << shown.output;
    EXPECT_LT(difference_from_render(dir, common + " --env builtin:white", shot), 0.5);
}

// A bad environment file mid-session: the error is shown, the old environment stays (the
// frames after it are the frames before), and a script that asked for it exits with 1.
TEST(FacetViewer, BadEnvironmentMidSessionKeepsTheOldOne) {
    TempDir dir;
    const std::string bad = (dir.path / "bad.hdr").string();
    std::ofstream(bad) << "this is no image";
    auto shot = [&](const char* name) { return (dir.path / name).string(); };
    Ran shown = run(viewer_command() + " --model builtin:sphere --env builtin:sky --env-width 128 --width 120 "
                    "--height 90 --script 'frames 1; screenshot " + shot("before.png") + "; env " + bad +
                    "; wait; frames 2; screenshot " + shot("after.png") + "'");
    EXPECT_EQ(shown.status, 1) << shown.output;
    EXPECT_EQ(shown.output.find("Validation"), std::string::npos) << shown.output;
    EXPECT_NE(shown.output.find("bad.hdr"), std::string::npos) << shown.output;
    EXPECT_NE(shown.output.find("(the previous scene stays)"), std::string::npos) << shown.output;
    EXPECT_EQ(shown.output.find("swapped in"), std::string::npos) << shown.output;
    EXPECT_LT(mean_difference(shot("before.png"), shot("after.png")), 0.01);
}

// The material sliders, scripted: gold's factors on the white sphere give facet-render's
// gold preset exactly (no bake between).
TEST(FacetViewer, MaterialFactorsMatchThePreset) {
    TempDir dir;
    const std::string common = "--model builtin:sphere --env builtin:sky --env-width 128 --width 120 --height 90";
    Ran shown = run(viewer_command() + " " + common + " --script 'frames 1; material 1,0.71,0.29,1,0.5; frames 1; screenshot " +
                    (dir.path / "slider.png").string() + "'");
    ASSERT_EQ(shown.status, 0) << shown.output;
    EXPECT_EQ(shown.output.find("Validation"), std::string::npos) << shown.output;
    Ran rendered = run(std::string(FACET_RENDER_PATH) + " " + common + " --preset gold --out " +
                       (dir.path / "gold.png").string());
    ASSERT_EQ(rendered.status, 0) << rendered.output;
    int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
    const auto a = pixels((dir.path / "slider.png").string(), &w1, &h1);
    const auto b = pixels((dir.path / "gold.png").string(), &w2, &h2);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    double diff = 0;
    for (size_t i = 0; i < a.size(); ++i) diff += std::abs(a[i] - b[i]);
    EXPECT_LT(diff / double(a.size()) * 255.0, 0.5);
}

// Shader hot reload: the viewer runs from a copy of shaders/; breaking a shader shows the
// compile error with file:line and keeps the last good pipelines running; fixing it
// rebuilds them.
TEST(FacetViewer, ShaderHotReloadShowsErrorsAndKeepsRunning) {
    TempDir dir;
    const fs::path shaders = dir.path / "shaders";
    fs::copy(FACET_SOURCE_DIR "/shaders", shaders, fs::copy_options::recursive);
    const fs::path log = dir.path / "viewer.log", pid_file = dir.path / "viewer.pid";
    const std::string command = viewer_command() + " --model builtin:sphere --env none --width 64 --height 48 " +
                                "--shader-dir " + shaders.string() + " --frames 100000 > " + log.string() +
                                " 2>&1 & echo $! > " + pid_file.string();
    ASSERT_EQ(std::system(command.c_str()), 0);
    auto log_text = [&] {
        std::ifstream in(log);
        return std::string((std::istreambuf_iterator<char>(in)), {});
    };
    auto wait_for = [&](const std::string& text) {
        for (int i = 0; i < 2400; ++i) {  // up to 60 s: a loaded machine starts slowly
            if (log_text().find(text) != std::string::npos) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(25));
        }
        return false;
    };
    // The shader is broken only once the first frame has built its pipelines (a busy
    // machine can take seconds to get there); the reload must keep the good ones.
    EXPECT_TRUE(wait_for("first frame shown")) << log_text();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const fs::path tonemap = shaders / "render" / "tonemap.comp";
    std::ifstream original_in(tonemap);
    const std::string original((std::istreambuf_iterator<char>(original_in)), {});
    std::ofstream(tonemap) << original << "\nthis is not glsl;\n";
    EXPECT_TRUE(wait_for("shader error")) << log_text();
    EXPECT_NE(log_text().find("tonemap.comp:"), std::string::npos) << log_text();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    int pid = 0;
    std::ifstream(pid_file) >> pid;
    EXPECT_EQ(::kill(pid, 0), 0) << "the viewer must keep running after a shader error";
    std::ofstream(tonemap) << original;
    EXPECT_TRUE(wait_for("shaders reloaded")) << log_text();
    if (pid > 0) ::kill(pid, SIGTERM);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_EQ(log_text().find("Validation"), std::string::npos) << log_text();
}

// Factors or textures, and the AO factor: on the textured box, switching its texture off
// changes the image, and an AO of 0 removes the image-based light.
TEST(FacetViewer, TexturesAndAmbientOcclusionFactor) {
    TempDir dir;
    auto shot = [&](const char* name) { return (dir.path / name).string(); };
    Ran r = run(viewer_command() + " --model " FACET_SHARED_DATA_DIR "/models/box_textured/BoxTextured.gltf "
                "--env builtin:white --env-width 64 --no-skybox --width 96 --height 72 --script '"
                "material 1,1,1,0,0.5,1,on; frames 1; screenshot " + shot("on.png") +
                "; material 1,1,1,0,0.5,1,off; frames 1; screenshot " + shot("off.png") +
                "; material 1,1,1,0,0.5,0,off; frames 1; screenshot " + shot("dark.png") + "'");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    int w = 0, h = 0;
    const auto on = pixels(shot("on.png"), &w, &h), off = pixels(shot("off.png"), &w, &h),
               dark = pixels(shot("dark.png"), &w, &h);
    ASSERT_EQ(on.size(), off.size());
    ASSERT_EQ(on.size(), dark.size());
    double changed = 0, lit = 0, unlit = 0;
    for (size_t i = 0; i < on.size(); ++i) {
        if (i % 4 == 3) continue;  // colour only (RGBA)
        changed += std::abs(on[i] - off[i]);
        lit += off[i];
        unlit += dark[i];
    }
    EXPECT_GT(changed / double(on.size()), 0.01) << "the texture must show";
    EXPECT_LT(unlit, 0.2 * lit) << "AO 0 takes the environment's light away";
}

TEST(FacetViewer, HelpAndBadArguments) {
    Ran help = run(std::string(FACET_VIEWER_PATH) + " --help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.output.find("Usage: facet-viewer"), std::string::npos) << help.output;
    EXPECT_NE(help.output.find("--screenshot"), std::string::npos);
    Ran bad = run(std::string(FACET_VIEWER_PATH) + " --frames zero");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.output.find("--frames"), std::string::npos) << bad.output;
    Ran model = run(viewer_command() + " --model builtin:nothing --frames 1");
    EXPECT_EQ(model.status, 1) << model.output;
    EXPECT_NE(model.output.find("builtin:nothing"), std::string::npos) << model.output;
}

}  // namespace
