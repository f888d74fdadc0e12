#include "render/shading_choice.h"

#include <algorithm>
#include <cmath>

namespace facet {

ResolvedShading resolve_shading(const RenderJob& requested) {
    ResolvedShading r{requested, {}};
    ShadingMethod method = requested.shading;
    r.choice.requested = method;
    if (requested.extract_lights || requested.frame.dominant_direction) {
        // The older switches add their part to the method (to the plain split sum when
        // automatic).
        const bool lights = requested.extract_lights || method == ShadingMethod::lights ||
                            method == ShadingMethod::lights_dominant;
        const bool dominant = requested.frame.dominant_direction || method == ShadingMethod::dominant ||
                              method == ShadingMethod::lights_dominant;
        method = lights ? (dominant ? ShadingMethod::lights_dominant : ShadingMethod::lights)
                        : ShadingMethod::dominant;
        r.choice.requested = method;
    }
    if (method == ShadingMethod::automatic) {
        // Extract whatever is bright, wide regions included; finish_shading_choice decides
        // with what was found.
        r.job.extract_lights = requested.env != "none";
        r.job.frame.dominant_direction = true;
        r.choice.method = r.job.extract_lights ? ShadingMethod::lights_dominant : ShadingMethod::dominant;
        r.choice.reason = "no environment";
        return r;
    }
    r.job.extract_lights = method == ShadingMethod::lights || method == ShadingMethod::lights_dominant;
    r.job.frame.dominant_direction = method == ShadingMethod::dominant || method == ShadingMethod::lights_dominant;
    r.choice.method = method;
    r.choice.reason = "requested";
    return r;
}

void finish_shading_choice(ResolvedShading& r, size_t lights, double power_fraction) {
    if (r.choice.requested != ShadingMethod::automatic || !r.job.extract_lights) return;
    if (lights == 0) {
        // Nothing compact or bright enough to take out: the split sum with the lookup bent
        // towards n (it halves the rough lobes' error under skies and studios).
        r.choice.method = ShadingMethod::dominant;
        r.choice.reason = "no bright region to extract";
        return;
    }
    r.choice.method = ShadingMethod::lights_dominant;
    r.choice.reason = std::to_string(lights) + " light(s) extracted, " +
                      std::to_string(int(std::lround(100 * power_fraction))) + "% of the power";
}

}  // namespace facet
