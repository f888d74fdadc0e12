// facet-bench runs and reports (its figures are measurements, never checked here).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

std::pair<int, std::string> run(const std::string& args) {
    const std::string command = std::string(FACET_BENCH_PATH) + " " + args + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    std::string out;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
    const int raw = pclose(pipe);
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}

TEST(FacetBench, ReportsMediansOfPassesAndWholeBake) {
    const std::string csv = (std::filesystem::temp_directory_path() / "facet_bench_test.csv").string();
    auto [status, out] = run("bake builtin:white --runs 2 --csv " + csv +
                             " --bake-args '--width 32 --lut-size 8 --lut-samples 16'");
    ASSERT_EQ(status, 0) << out;
    EXPECT_NE(out.find("builtin:white: 2 runs, medians"), std::string::npos) << out;
    EXPECT_NE(out.find("irradiance convolve"), std::string::npos) << out;
    EXPECT_NE(out.find("ms wall"), std::string::npos) << out;
    std::ifstream in(csv);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(text.find("\"builtin:white\",\"whole bake (GPU)\""), std::string::npos) << text;
    std::filesystem::remove(csv);
}

TEST(FacetBench, RenderReportsMedianFrameAndPasses) {
    auto [status, out] = run("render --model builtin:sphere --env builtin:white --width 64 --height 48 --frames 3 "
                             "--light 'directional dir=0,-1,-1'");
    ASSERT_EQ(status, 0) << out;
    for (const char* text : {"3 frames", "forward", "skybox", "tonemap", "ms GPU", "ms wall", "IBL bake", "1 light(s)"})
        EXPECT_NE(out.find(text), std::string::npos) << text << "\n" << out;
    EXPECT_EQ(out.find("Validation"), std::string::npos) << out;
    auto [bad, bad_out] = run("render --model builtin:nothing");
    EXPECT_EQ(bad, 1);
    EXPECT_NE(bad_out.find("builtin:nothing"), std::string::npos) << bad_out;
}

TEST(FacetBench, BadUseIsAClearError) {
    auto [status, out] = run("frobnicate");
    EXPECT_EQ(status, 2);
    EXPECT_NE(out.find("bake"), std::string::npos) << out;
    auto [bad_status, bad_out] = run("bake builtin:nothing --runs 1");
    EXPECT_EQ(bad_status, 1);
    EXPECT_NE(bad_out.find("builtin:nothing"), std::string::npos) << bad_out;
}

}  // namespace
