#pragma once
// How the forward pass lights surfaces with the environment (issue 13's methods):
// - split_sum: the prefiltered cube along R times the LUT (Karis 2013);
// - dominant: the same with the lookup bent towards n for rough lobes;
// - lights: bright regions (suns, lamps, softboxes, a low sun's glow) taken out of the
//   map before the bake and shaded as disk lights with the full BRDF, the rest by the
//   split sum (ibl/light_extraction.h);
// - lights_dominant: both;
// - automatic: chosen per environment (RenderSession, render/render_job.h): the lights
//   (wide regions split into several) with the dominant direction where the environment
//   has bright regions, the dominant direction alone where it has none.
#include <optional>
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
struct ShadingChoice {
    ShadingMethod requested = ShadingMethod::automatic;
    ShadingMethod method = ShadingMethod::split_sum;  // never automatic
    std::string reason;
};

}  // namespace facet
