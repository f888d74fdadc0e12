#pragma once
// Predicts issue 13's per-group error of shading methods under a session's environment,
// BRDF model and bake, before the frame is drawn: a small probe (builtin:spheres, every
// group of the measure) is rendered with each method and compared, at a few hundred
// pixels, with the double-precision truth of the frame's BRDF model (facet::reference,
// final_image_accuracy.h) over a box-filtered copy of the environment. The truth is C++
// written from the equations, independent of the shaders the probe runs.
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <facet/core/result.h>
#include <facet/render/shading_method.h>
#include "render/render_session_state.h"

namespace facet {

struct PredictionSettings {
    uint32_t width = 320, height = 180;  // the probe's image
    uint32_t truth_env_width = 256;      // the truth's environment is box-filtered down to about this width
    uint32_t pixels = 480;               // probe pixels compared with the truth (all groups together)
    // Stop after the first method whose worst group is within this (the methods given
    // cheapest first, the rest are then not predicted); negative: predict every one.
    double stop_within = -1;
    // A method that bends the lookup is also rendered with two fitted lookups in every group
    // (FrameSettings::two_lookup_groups all set): MethodPrediction::two_lookup_error.
    bool two_lookups = false;
};

// The probe: builtin:spheres (7 x 7, the measure's scene) with the scene's
// materials: its distinct (roughness, metalness) pairs of roughness 0.2 and up, in turn,
// where no texture scales them and there are 49 or fewer; else roughness (columns) and
// metalness (rows) spread over what the materials span (factors, down to 0 where a
// texture scales them; roughness from the smallest any texel has, scene/scene_needs.h,
// what the bake serves; metalness 1 alone where nothing is diffuse: the bake then has no
// irradiance). A scene smoother than 0.2 everywhere gets the measure's whole range.
Scene probe_scene(const Scene& scene);
// The groups (band-major as test::FinalImageAccuracy::groups: 2 * band + metal) that a
// scene's materials fall in (material_shading_groups of each; a roughness factor below 0.2
// in none).
std::array<bool, 8> material_groups(const Scene& scene);

struct MethodPrediction {
    ShadingMethod method = ShadingMethod::split_sum;
    std::array<double, 8> group_error{};  // mean relative error of luminance; NaN: no pixel measured
    double worst = 0;                     // over the groups asked for; NaN when none was measured
    int worst_group = -1;
    // With PredictionSettings::two_lookups and a bending method: each group's error with two
    // fitted lookups instead of three (the bands from kTwoLookupsRoughness read two in both).
    // NaN where not predicted.
    std::array<double, 8> two_lookup_error{nan_errors()};

    static constexpr std::array<double, 8> nan_errors() {
        std::array<double, 8> a{};
        for (double& e : a) e = std::numeric_limits<double>::quiet_NaN();
        return a;
    }
};

struct ShadingPrediction {
    std::vector<MethodPrediction> methods;  // in the order asked for (up to the stop, PredictionSettings)
    std::array<bool, 8> groups{};           // the probe's (material_groups of probe_scene)
    double seconds = 0;                     // wall time: probe renders and truth sums
    double truth_seconds = 0;
};

// `s` after its bake (s.env holding the environment's texels, s.baked the images):
// each of `methods` must be one the bake serves (render/shading_choice.h,
// shading_candidates). Device failures are returned as the Error.
Result<ShadingPrediction> predict_shading_errors(RenderSession::State& s, std::span<const ShadingMethod> methods,
                                                 const PredictionSettings& settings = {});

}  // namespace facet
