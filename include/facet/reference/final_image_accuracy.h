#pragma once
// The final image against its truth, as issue 13 measures it: pixels with n.v > 0.3 and
// roughness >= 0.2, grouped by roughness band ([0.2,0.4) [0.4,0.6) [0.6,0.8) [0.8,1]) x
// metal (metalness >= 0.5) or dielectric; per group the mean and max of
// |lum(render) - lum(truth)| / lum(truth) and the mean signed error. The truth is
// environment_truth (final_image_truth.h) of the material the views report.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <facet/core/brdf_model.h>
#include <facet/reference/final_image_truth.h>

namespace facet::test {

// A rendered frame: every image RGBA float, width x height, row-major. `hdr` is the
// final colour before exposure (alpha = coverage); the others are the forward pass's
// views (render/views.h): world normal and position (alpha 1 where covered),
// base colour, metalness and roughness (in r); optionally the clear coat's (weight and
// roughness in r, g) and its normal (empty: no clear coat).
struct FinalImageViews {
    uint32_t width = 0, height = 0;
    std::span<const float> hdr, normal, position, basecolor, metallic, roughness;
    std::span<const float> clearcoat, clearcoat_normal;
    std::span<const float> iridescence;  // View::iridescence: weight, film ior, thickness (empty: no film)
    std::span<const float> anisotropy;   // View::anisotropy: direction, strength (empty: none)
    std::span<const float> sheen;        // View::sheen: colour, roughness (empty: none)
    std::span<const float> transmission; // View::transmission: weight (r) (empty: none)
};

struct AccuracySettings {
    double intensity = 1;       // the renderer's IBL intensity (scales the truth)
    uint32_t max_pixels = 4000; // pixel budget, spread evenly over the eligible pixels
    double min_n_v = 0.3;       // pixels with n.v <= this are left out
    double min_roughness = 0.2; // and those below this roughness
    double dielectric_f0 = 0.04, specular_weight = 1;
    Vec3 specular_color{1, 1, 1};
    unsigned threads = 0;       // 0: std::thread::hardware_concurrency()
};

struct GroupError {
    double roughness_min = 0, roughness_max = 0;
    bool metal = false;
    size_t pixels = 0;
    double mean_rel = 0, max_rel = 0, mean_signed = 0;  // fractions (0.03 = 3%)
};

struct FinalImageAccuracy {
    // Band-major: groups[2 * band + metal], band 0 = [0.2, 0.4).
    std::array<GroupError, 8> groups;
    int worst = -1;              // index of the group with the largest mean_rel; -1 if all empty
    double worst_mean_rel = 0;
    size_t pixels = 0;           // pixels measured (all groups)
    double truth_seconds = 0;    // wall time of the truth sums
};

// The measurement in two steps, for several renders of one frame (the same views, other
// shading methods): the eligible pixels and their truth once, then each render's errors.
struct FinalImageTruth {
    uint32_t width = 0, height = 0;
    std::vector<size_t> index;      // the pixels measured: y * width + x
    std::vector<int> group;         // each one's group (band-major, as FinalImageAccuracy::groups)
    std::vector<double> luminance;  // each one's truth, luminance x intensity
    double seconds = 0;             // wall time of the truth sums
};
// Throws std::invalid_argument when an image's size is not width x height x 4.
FinalImageTruth final_image_truth(const FinalImageViews& views, const Vec3& eye, const TexelLights& env, BrdfModel model,
                                  const AccuracySettings& settings = {});
// `hdr`: a render of the frame `truth` was taken from (width x height RGBA, before
// exposure); throws std::invalid_argument when its size differs.
FinalImageAccuracy final_image_accuracy(const FinalImageTruth& truth, std::span<const float> hdr);

// Throws std::invalid_argument when an image's size is not width x height x 4.
FinalImageAccuracy final_image_accuracy(const FinalImageViews& views, const Vec3& eye, const TexelLights& env,
                                        BrdfModel model, const AccuracySettings& settings = {});
FinalImageAccuracy final_image_accuracy(const FinalImageViews& views, const Vec3& eye, const Equirect& env,
                                        BrdfModel model, const AccuracySettings& settings = {});

// Group g of the measure (band-major: 2 * band + metal), its band's edges and metalness set,
// nothing measured yet.
GroupError measure_group(int g);
// "roughness [0.2,0.4) dielectric", ...
std::string group_name(const GroupError& g);
// One header line, then one line per group (name, pixels, mean %, max %, signed mean %),
// then the worst group.
std::string format_accuracy_table(const FinalImageAccuracy& a);

}  // namespace facet::test
