#pragma once
// Importance sampling of an equirectangular environment: texels are picked in proportion
// to luminance x solid angle (a marginal CDF over rows, a conditional CDF per row), then a
// direction uniformly within the texel's solid angle. Laid out for
// shaders/render/reference.comp: marginal[H], conditional[H * W], texel probability[H * W].
#include <cstdint>
#include <span>
#include <vector>

namespace facet {

struct EnvironmentDistribution {
    uint32_t width = 0, height = 0;
    std::vector<float> values;  // marginal, conditional, probability (see above)
};

// `rgba`: width x height texels, row 0 = the top row (+Y). Every texel keeps a small
// probability (1e-3 of the mean weight), so that no direction with light is unreachable.
EnvironmentDistribution build_environment_distribution(std::span<const float> rgba, uint32_t width,
                                                       uint32_t height);

}  // namespace facet
