#include <facet/render/specular_lobes.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <facet/io/ktx2.h>

#include "render/specular_lobes_table.h"

namespace facet {

namespace {

// The fit's eight numbers at entry (model, row, column) of its 9 x 9 grid.
std::array<double, 8> fitted_entry(int model, int row, int column) {
    std::array<double, 8> out{};
    const double theta = std::acos(0.1 * (column + 1));
    const int entry = ((model * kSpecularLobeRows + row) * kSpecularLobeColumns + column) * 3;
    for (int lookup = 0; lookup < 3; ++lookup) {
        const float* e = kSpecularLobeEntries[entry + lookup];
        const double a = std::sin(double(e[0]) * theta), b = std::sin((1.0 - double(e[0])) * theta);
        out[size_t(lookup)] = a / (a + b);
        out[size_t(4 + lookup)] = e[1];
    }
    out[3] = kSpecularLobeEntries[entry][2];      // the first lookup's weight
    out[7] = kSpecularLobeEntries[entry + 1][2];  // the second's
    return out;
}

}  // namespace

std::vector<uint32_t> specular_lobe_table_texels() {
    static_assert(kSpecularLobeRows == kSpecularLobeColumns && kSpecularLobeTableSteps % (kSpecularLobeRows - 1) == 0);
    constexpr uint32_t n = kSpecularLobeTableSteps + 1;
    std::vector<uint32_t> texels(size_t(kSpecularLobeTableWidth) * kSpecularLobeTableHeight * 4, 0u);
    for (int model = 0; model < kSpecularLobeModels; ++model)
        for (uint32_t row = 0; row < n; ++row)
            for (uint32_t column = 0; column < n; ++column) {
                // The fit's grid coordinates, interpolated linearly as a sampler would.
                const double x = double(column) * (kSpecularLobeColumns - 1) / kSpecularLobeTableSteps;
                const double y = double(row) * (kSpecularLobeRows - 1) / kSpecularLobeTableSteps;
                const int x0 = std::min(int(x), kSpecularLobeColumns - 2), y0 = std::min(int(y), kSpecularLobeRows - 2);
                const double fx = x - x0, fy = y - y0;
                const std::array<double, 8> a = fitted_entry(model, y0, x0), b = fitted_entry(model, y0, x0 + 1),
                                            c = fitted_entry(model, y0 + 1, x0), d = fitted_entry(model, y0 + 1, x0 + 1);
                uint16_t halves[8];
                for (size_t i = 0; i < 8; ++i)
                    halves[i] = float_to_half(float((1 - fy) * ((1 - fx) * a[i] + fx * b[i]) + fy * ((1 - fx) * c[i] + fx * d[i])));
                uint32_t* texel = &texels[((size_t(model) * n + row) * kSpecularLobeTableWidth + column) * 4];
                for (size_t i = 0; i < 4; ++i) texel[i] = uint32_t(halves[2 * i]) | uint32_t(halves[2 * i + 1]) << 16;
            }
    return texels;
}

SpecularLobeEntry specular_lobe_table_entry(const std::vector<uint32_t>& texels, uint32_t model, uint32_t column,
                                            uint32_t row) {
    const uint32_t* texel = &texels[((size_t(model) * (kSpecularLobeTableSteps + 1) + row) * kSpecularLobeTableWidth + column) * 4];
    auto half = [&](size_t i) { return half_to_float(uint16_t(texel[i / 2] >> (16 * (i % 2)))); };
    SpecularLobeEntry e{};
    e.t[0] = half(0);
    e.t[1] = half(1);
    e.t[2] = half(2);
    e.w[0] = half(3);
    e.r[0] = half(4);
    e.r[1] = half(5);
    e.r[2] = half(6);
    e.w[1] = half(7);
    e.w[2] = 1.0f - e.w[0] - e.w[1];
    return e;
}

float lowest_lookup_roughness(float roughness) {
    // Rows from the one at or below `roughness` up; below 0.2 the shader scales the first
    // row's lookups by roughness / 0.2; no lookup reads below 0.35 x the surface's roughness.
    const int first_row = roughness < 0.2f ? 0 : std::min(int((roughness - 0.2f) * 10.0f + 1e-4f), kSpecularLobeRows - 1);
    const float scale = roughness < 0.2f ? std::max(roughness, 0.0f) / 0.2f : 1.0f;
    float lowest = roughness;
    for (int model = 0; model < kSpecularLobeModels; ++model)
        for (int row = first_row; row < kSpecularLobeRows; ++row)
            for (int i = 0; i < kSpecularLobeColumns * 3; ++i)
                lowest = std::min(lowest, std::max(scale * kSpecularLobeEntries[(model * kSpecularLobeRows + row) * kSpecularLobeColumns * 3 + i][1],
                                                   0.35f * roughness));
    return lowest;
}

}  // namespace facet
