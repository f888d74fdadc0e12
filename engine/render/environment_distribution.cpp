#include "render/environment_distribution.h"

#include <cmath>

#include <facet/core/shared_constants.h>
#include "io/equirect.h"

namespace facet {

EnvironmentDistribution build_environment_distribution(std::span<const float> rgba, uint32_t width,
                                                       uint32_t height) {
    EnvironmentDistribution d;
    d.width = width;
    d.height = height;
    const size_t W = width, H = height;
    std::vector<double> weight(W * H);
    double total = 0;
    for (size_t y = 0; y < H; ++y) {
        const double solid_angle = equirect_texel_solid_angle(uint32_t(y), width, height);
        for (size_t x = 0; x < W; ++x) {
            const float* t = &rgba[(y * W + x) * 4];
            const double luminance = facet::luminance(t[0], t[1], t[2]);
            weight[y * W + x] = std::max(luminance, 0.0) * solid_angle;
            total += weight[y * W + x];
        }
    }
    // A floor keeps black regions reachable by environment sampling (the BRDF strategy
    // covers them anyway; this only avoids zero densities).
    const double floor = total > 0 ? 1e-3 * total / double(W * H) : 1.0;
    total = 0;
    for (double& w : weight) total += (w += floor);
    d.values.assign(H + 2 * W * H, 0.0f);
    double rows = 0;
    for (size_t y = 0; y < H; ++y) {
        double row = 0;
        for (size_t x = 0; x < W; ++x) row += weight[y * W + x];
        double running = 0;
        for (size_t x = 0; x < W; ++x) {
            running += weight[y * W + x];
            d.values[H + y * W + x] = float(running / row);
            d.values[H + W * H + y * W + x] = float(weight[y * W + x] / total);
        }
        d.values[H + y * W + W - 1] = 1.0f;
        rows += row;
        d.values[y] = float(rows / total);
    }
    d.values[H - 1] = 1.0f;
    return d;
}

}  // namespace facet
