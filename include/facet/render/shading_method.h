#pragma once
// How the forward pass lights surfaces with the environment (issue 13's methods):
// - split_sum: the prefiltered cube along R times the LUT (Karis 2013);
// - dominant: the same with three lookups fitted to the true lobe, which leans towards n and
//   stretches at n.v < 1 (render/specular_lobes.h);
// - lights: bright regions (suns, lamps, softboxes, a low sun's glow) taken out of the
//   map before the bake and shaded as disk lights with the full BRDF, the rest by the
//   split sum (ibl/light_extraction.h);
// - lights_dominant: both;
// - automatic: chosen per environment, BRDF model and scene (RenderSession,
//   render/render_job.h): each method the bake serves is tried on a small probe against
//   the exact integral, and the cheapest whose worst group of issue 13's measure is
//   within the target error wins (the most accurate when none is).
// Cost order (the forward pass's work): split_sum < dominant < lights < lights_dominant.
#include <array>
#include <optional>
#include <vector>
#include <string>
#include <string_view>

namespace facet {

enum class ShadingMethod { automatic, split_sum, dominant, lights, lights_dominant };

// "auto", "split-sum", "dominant", "lights", "lights+dominant".
const char* shading_method_name(ShadingMethod method);
std::optional<ShadingMethod> parse_shading_method(std::string_view name);
// "auto, split-sum, dominant, lights, lights+dominant"
const char* shading_method_names();

}  // namespace facet

namespace facet {

// What a session shades with, and why (written into facet-render's NAME.json, shown by
// the viewer).
// One group of issue 13's measure (a roughness band x metal or dielectric) and the mean
// relative error of luminance predicted for it.
struct GroupErrorPrediction {
    std::string group;  // "roughness [0.2,0.4) metal"
    double error = 0;   // a fraction (0.03 = 3%)
};

struct ShadingChoice {
    ShadingMethod requested = ShadingMethod::automatic;
    ShadingMethod method = ShadingMethod::split_sum;  // never automatic
    std::string reason;
    double target_error = 0.03;  // what the automatic choice keeps every group within (a fraction)
    // The method's predicted error in the worst group the scene's materials reach (a
    // fraction), that group, and every such group's: measured on a probe under this
    // environment (render/error_prediction.h). Absent without an environment's texels
    // (no environment, a saved bake) or when no probe pixel has light to measure.
    std::optional<double> predicted_error;
    std::string predicted_worst_group;
    std::vector<GroupErrorPrediction> predicted_groups;
    // lights_dominant or dominant chosen automatically: the groups whose materials read
    // along R instead (the cheaper method predicted within the target there); the
    // predicted errors above are then per group those of the lookup each group uses.
    std::vector<std::string> unbent_groups;
    // Of the bending groups below roughness 0.6, those reading two fitted lookups instead of
    // three (render/shading_choice.h, choose_group_bends); their predicted errors above are
    // the two lookups'.
    std::vector<std::string> two_lookup_groups;
};

// The lower edges of issue 13's roughness bands ([0.2,0.4) [0.4,0.6) [0.6,0.8) [0.8,1]; the
// measure's own definition: reference/final_image_accuracy.h, measure_group); group g is band
// g / 2, metal where g is odd.
inline constexpr std::array<float, 4> kShadingGroupBandLow = {0.2f, 0.4f, 0.6f, 0.8f};

struct Material;
// The groups of issue 13's measure (index 2 x roughness band + metal) a material's pixels
// can fall in: its roughness factor's band, or every band up to it where a
// metallic-roughness texture scales it; metal where metallic >= 0.5, dielectric where it is
// below or a texture can scale it below. Roughness under 0.2 counts as the first band.
std::array<bool, 8> material_shading_groups(const Material& material);

}  // namespace facet
