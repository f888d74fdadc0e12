// The final image's targets (issue "accurate by default"), held by the default shading for
// each BRDF model under every shared environment: builtin:spheres from the default camera,
// each group of pixels (roughness band x dielectric/metal, n.v > 0.3) against the
// double-precision sum of the same model over every environment texel (facet-bench
// accuracy). Targets: every group within 3% under builtin:sky, venice_sunset and
// royal_esplanade, within 5% under studio_small_03 and empty_warehouse_01, and never worse
// than the plain split sum. The frame is the 1280x720 (at 640x360 a group at 3.01%
// there read 2.94%), from the same 512-wide environments as the benchmark's (docs/accuracy.md
// has its figures at 4000 pixels); the table is printed.
#include <gtest/gtest.h>

#include "io/json_reader.h"
#include "support/process.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Environment {
    std::string path;
    double target;
};

const std::vector<Environment>& environments() {
    static const std::string d = FACET_SHARED_DATA_DIR "/env/";
    static const std::vector<Environment> e = {{"builtin:sky", 0.03},
                                               {d + "venice_sunset_1k.hdr", 0.03},
                                               {d + "royal_esplanade_1k.hdr", 0.03},
                                               {d + "studio_small_03_1k.hdr", 0.05},
                                               {d + "empty_warehouse_01_1k.hdr", 0.05}};
    return e;
}

// Environment -> group -> mean relative error of the default shading and of the split sum
// (facet-bench accuracy --compare: the same truth), and environment -> method auto chose.
struct Measured {
    std::map<std::string, std::map<std::string, double>> error, split;
    std::map<std::string, std::string> method;
};

Measured measure(const std::string& brdf) {
    Measured m;
    const fs::path json = fs::temp_directory_path() / ("facet_targets_" + brdf + "_" + std::to_string(::getpid()) + ".json");
    std::string envs;
    for (const Environment& e : environments()) envs += (envs.empty() ? "" : ",") + e.path;
    const facet::test::Ran r = facet::test::run_command(std::string(FACET_BENCH_PATH) + " accuracy --brdf " + brdf +
                                                        " --compare split-sum --env " + envs +
                                                        " --size 1280x720 --env-width 512 --pixels 1500 --runs 1 "
                                                        "--no-bake-cache --json " + json.string());
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    std::ifstream in(json);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    fs::remove(json);
    auto doc = facet::parse_json(text);
    EXPECT_TRUE(doc) << text;
    if (!doc || !doc->find("environments")) return m;
    for (const facet::JsonValue& env : doc->find("environments")->items()) {
        const std::string name = env.find("environment")->string();
        m.method[name] = env.find("shading")->string();
        for (const facet::JsonValue& g : env.find("groups")->items())
            m.error[name][g.find("group")->string()] = g.find("mean_rel")->number();
        const facet::JsonValue* compared = env.find("compared");
        EXPECT_TRUE(compared) << name;
        if (!compared) continue;
        for (const facet::JsonValue& g : compared->find("groups")->items())
            m.split[name][g.find("group")->string()] = g.find("mean_rel")->number();
    }
    return m;
}

void check_targets(const std::string& brdf) {
    const Measured automatic = measure(brdf);
    std::printf("%s model, mean error per group (%%): auto (its method) / split sum, target\n", brdf.c_str());
    for (const Environment& e : environments()) {
        const std::string name = fs::path(e.path).filename().string();
        const std::string key = e.path.rfind("builtin:", 0) == 0 ? e.path : name;  // as facet-bench names it
        const auto found = automatic.error.find(key);
        ASSERT_NE(found, automatic.error.end()) << key;
        const auto& groups = found->second;
        ASSERT_EQ(groups.size(), 8u) << e.path << ": every group has pixels";
        std::printf("  %s (%s, target %.0f%%)\n", name.c_str(), automatic.method.at(key).c_str(), 100 * e.target);
        for (const auto& [group, error] : groups) {
            const double plain = automatic.split.at(key).at(group);
            std::printf("    %-32s %6.2f / %6.2f\n", group.c_str(), 100 * error, 100 * plain);
            EXPECT_LE(error, e.target) << brdf << ", " << name << ", " << group;
            // Never worse than the split sum: where both are near the noise of 1500 pixels
            // (a group's mean of a few hundred), a quarter of a point apart is the same.
            EXPECT_LE(error, plain + 0.0025) << brdf << ", " << name << ", " << group;
        }
    }
}

// --compare names a shading method; anything else is a usage error naming it (exit 2).
TEST(AccuracyTargets, CompareTakesAShadingMethod) {
    for (const char* bad : {"--compare frobnicate", "--compare split-sum --reference"}) {
        const facet::test::Ran r = facet::test::run_command(std::string(FACET_BENCH_PATH) + " accuracy " + bad);
        EXPECT_EQ(r.status, 2) << bad << "\n" << r.output;
        EXPECT_NE(r.output.find("--compare"), std::string::npos) << r.output;
    }
}

TEST(AccuracyTargets, GltfModelEveryGroupWithinItsTarget) { check_targets("gltf"); }

TEST(AccuracyTargets, ThesisModelEveryGroupWithinItsTarget) { check_targets("thesis"); }

}  // namespace
