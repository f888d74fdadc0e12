// The automatic shading choice's prediction (render/error_prediction.h: a 320 x 180 probe,
// the truth over a box-filtered copy of the environment) against what facet-bench
// accuracy measures on the frame itself: builtin:spheres at 640 x 360 under builtin:sky
// (512 x 256 texels), every group of issue 13's measure compared with the
// double-precision truth over every texel (facet::reference). Tolerance per group:
// within 1.5 points or 25% of the measured error, whichever is larger.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <facet/reference/final_image_accuracy.h>
#include <facet/render/render_job.h>
#include "support/gpu_test.h"

namespace facet {
namespace {

const std::vector<float>& view_of(const RenderedImages& frame, View view) {
    static const std::vector<float> none;
    for (const auto& [v, pixels] : frame.views)
        if (v == view) return pixels;
    return none;
}

double tolerance(double measured) { return std::max(0.015, 0.25 * measured); }

// Renders the frame with `shading`, measures it as facet-bench accuracy does and compares
// every group with the session's prediction; returns the session's choice.
ShadingChoice predicted_against_measured(ShadingMethod shading, BrdfModel model, double target_error = 0.03,
                                         std::array<bool, 8>* two_lookup_groups = nullptr) {
    RenderJob job;
    job.programs = &test::gpu_programs();  // the suite's pipelines, each built once
    job.target_error = target_error;
    job.model = "builtin:spheres";
    job.env = "builtin:sky";
    job.env_width = 512;
    job.frame.width = 640;
    job.frame.height = 360;
    job.frame.skybox = false;
    job.frame.brdf = model;
    job.frame.views = {View::normal, View::position, View::basecolor, View::metallic, View::roughness};
    job.shading = shading;
    job.predict_named_method = true;
    auto session = RenderSession::create(test::gpu(), job);
    if (!session) {
        ADD_FAILURE() << session.error().message;
        return {};
    }
    const ShadingChoice choice = (*session)->shading();
    if (two_lookup_groups) *two_lookup_groups = (*session)->frame().two_lookup_groups;
    auto frame = (*session)->render_frame();
    if (!frame) {
        ADD_FAILURE() << frame.error().message;
        return choice;
    }
    const EnvironmentSource* env = (*session)->environment();
    EXPECT_NE(env, nullptr);
    if (!env) return choice;
    const test::Equirect texels{env->width, env->height, env->image.rgba};
    const test::FinalImageViews views{frame->width, frame->height, frame->hdr, view_of(*frame, View::normal),
                                      view_of(*frame, View::position), view_of(*frame, View::basecolor),
                                      view_of(*frame, View::metallic), view_of(*frame, View::roughness)};
    const glm::vec3 eye = (*session)->camera().position;
    test::AccuracySettings settings;
    settings.max_pixels = 1000;
    const test::FinalImageAccuracy measured =
        test::final_image_accuracy(views, {eye.x, eye.y, eye.z}, texels, model, settings);

    std::printf("%s BRDF, %s: predicted (probe) / measured (frame), mean relative error per group\n",
                brdf_model_name(model), shading_method_name(choice.method));
    EXPECT_TRUE(choice.predicted_error.has_value()) << choice.reason;
    EXPECT_EQ(choice.predicted_groups.size(), 8u);  // builtin:spheres reaches every group
    for (const GroupErrorPrediction& p : choice.predicted_groups) {
        const auto g = std::find_if(measured.groups.begin(), measured.groups.end(),
                                    [&](const test::GroupError& e) { return test::group_name(e) == p.group; });
        if (g == measured.groups.end() || g->pixels < 20) {
            ADD_FAILURE() << p.group << ": not measured on the frame";
            continue;
        }
        std::printf("  %-32s %6.2f%% / %6.2f%%\n", p.group.c_str(), 100 * p.error, 100 * g->mean_rel);
        EXPECT_NEAR(p.error, g->mean_rel, tolerance(g->mean_rel)) << p.group;
    }
    if (choice.predicted_error) {
        std::printf("  worst: predicted %.2f%% (%s), measured %.2f%% (%s)\n", 100 * *choice.predicted_error,
                    choice.predicted_worst_group.c_str(), 100 * measured.worst_mean_rel,
                    test::group_name(measured.groups[size_t(measured.worst)]).c_str());
        EXPECT_NEAR(*choice.predicted_error, measured.worst_mean_rel, tolerance(measured.worst_mean_rel));
    }
    return choice;
}

TEST(ShadingPrediction, AutomaticChoiceOnTheBuiltinSkyIsWithinTheTargetAsPredicted) {
    const ShadingChoice c = predicted_against_measured(ShadingMethod::automatic, BrdfModel::gltf);
    EXPECT_EQ(c.requested, ShadingMethod::automatic);
    ASSERT_TRUE(c.predicted_error.has_value());
    EXPECT_LE(*c.predicted_error, c.target_error) << c.reason;  // the sun is extracted: within 3%
    EXPECT_NE(c.reason.find("<= target 3.0%"), std::string::npos) << c.reason;
}

TEST(ShadingPrediction, ThePlainSplitSumsLargeErrorIsPredicted) {
    // The split sum is far off under a sun (issue 13: 20% and more on rough metals): the
    // prediction must see it, not only small errors.
    const ShadingChoice c = predicted_against_measured(ShadingMethod::split_sum, BrdfModel::thesis);
    EXPECT_EQ(c.method, ShadingMethod::split_sum);
    EXPECT_EQ(c.reason, "requested");
    ASSERT_TRUE(c.predicted_error.has_value());
    EXPECT_GT(*c.predicted_error, 0.05);
}

// A target no method reaches (0.5% under the sun sky): lights+dominant, the most accurate,
// and every bending group whose two lookups are predicted within 15% of the worst group's
// error with three reads two (render/shading_choice.h). The session's frame carries them,
// the choice lists them, and the frame measures as predicted with them.
TEST(ShadingPrediction, OutOfReachTheChoiceTakesTwoLookupsAndTheFrameFollows) {
    std::array<bool, 8> two{};
    const ShadingChoice c = predicted_against_measured(ShadingMethod::automatic, BrdfModel::gltf, 0.005, &two);
    EXPECT_EQ(c.method, ShadingMethod::lights_dominant) << c.reason;
    ASSERT_TRUE(c.predicted_error.has_value());
    EXPECT_GT(*c.predicted_error, c.target_error);
    for (const std::string& g : c.two_lookup_groups) std::printf("  two lookups: %s\n", g.c_str());
    EXPECT_FALSE(c.two_lookup_groups.empty()) << c.reason;
    EXPECT_NE(c.reason.find("two fitted lookups instead of three: "), std::string::npos) << c.reason;
    const char* labels[8] = {"roughness [0.2,0.4) dielectric", "roughness [0.2,0.4) metal",
                             "roughness [0.4,0.6) dielectric", "roughness [0.4,0.6) metal",
                             "roughness [0.6,0.8) dielectric", "roughness [0.6,0.8) metal",
                             "roughness [0.8,1.0] dielectric", "roughness [0.8,1.0] metal"};
    for (size_t g = 0; g < 4; ++g) {  // the bands below 0.6, where two are not the default
        const bool listed =
            std::find(c.two_lookup_groups.begin(), c.two_lookup_groups.end(), labels[g]) != c.two_lookup_groups.end();
        EXPECT_EQ(two[g], listed) << labels[g];
    }
    for (size_t g = 4; g < 8; ++g) EXPECT_TRUE(two[g]) << labels[g] << ": the default";
}

TEST(ShadingPrediction, NoEnvironmentNoPrediction) {
    RenderJob job;
    job.model = "builtin:sphere";
    job.env = "none";
    job.frame.width = job.frame.height = 32;
    auto session = RenderSession::create(test::gpu(), job);
    ASSERT_TRUE(session) << session.error().message;
    EXPECT_FALSE((*session)->shading().predicted_error.has_value());
}

TEST(ShadingPrediction, TargetOutsideZeroToOneIsAnError) {
    for (double bad : {0.0, 1.0, -0.1, 2.0, std::nan("")}) {
        RenderJob job;
        job.env = "none";
        job.target_error = bad;
        auto session = RenderSession::create(test::gpu(), job);
        ASSERT_FALSE(session) << bad;
        EXPECT_NE(session.error().message.find("target error"), std::string::npos) << session.error().message;
    }
}

}  // namespace
}  // namespace facet
