#include <facet/render/specular_lobes.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "render/specular_lobes_table.h"

namespace facet {

static_assert(kSpecularLobeTableWidth == 3 * kSpecularLobeColumns);
static_assert(kSpecularLobeTableHeight == kSpecularLobeModels * kSpecularLobeRows);

namespace {
// The linear weight between n and R that reaches the fit's fraction s of the angle theta.
float axis_weight(float s, double theta) {
    const double a = std::sin(double(s) * theta), b = std::sin((1.0 - double(s)) * theta);
    return float(a / (a + b));
}
}  // namespace

std::vector<float> specular_lobe_table_texels() {
    std::vector<float> texels(std::size_t(kSpecularLobeTableWidth) * kSpecularLobeTableHeight * 4, 0.0f);
    for (int model = 0; model < kSpecularLobeModels; ++model)
        for (int row = 0; row < kSpecularLobeRows; ++row)
            for (int column = 0; column < kSpecularLobeColumns; ++column) {
                const double theta = std::acos(0.1 * (column + 1));
                const std::size_t y = std::size_t(model * kSpecularLobeRows + row);
                float* directions = &texels[(y * kSpecularLobeTableWidth + std::size_t(column)) * 4];
                float* widths = &texels[(y * kSpecularLobeTableWidth + std::size_t(kSpecularLobeColumns + column)) * 4];
                float* two = &texels[(y * kSpecularLobeTableWidth + std::size_t(2 * kSpecularLobeColumns + column)) * 4];
                for (int lookup = 0; lookup < 2; ++lookup) {
                    const float* e =
                        kSpecularLobeTwoEntries[((model * kSpecularLobeRows + row) * kSpecularLobeColumns + column) * 2 + lookup];
                    two[lookup] = axis_weight(e[0], theta);
                    two[2 + lookup] = e[1];
                }
                for (int lookup = 0; lookup < 3; ++lookup) {
                    const float* e =
                        kSpecularLobeEntries[((model * kSpecularLobeRows + row) * kSpecularLobeColumns + column) * 3 + lookup];
                    directions[lookup] = axis_weight(e[0], theta);
                    widths[lookup] = e[1];
                }
                directions[3] = kSpecularLobeEntries[((model * kSpecularLobeRows + row) * kSpecularLobeColumns + column) * 3][2];
                widths[3] = kSpecularLobeEntries[((model * kSpecularLobeRows + row) * kSpecularLobeColumns + column) * 3 + 1][2];
            }
    return texels;
}

float lowest_lookup_roughness(float roughness) {
    // Rows from the one at or below `roughness` up; below 0.2 the shader scales the first
    // row's lookups by roughness / 0.2; no lookup reads below 0.35 x the surface's roughness.
    const int first_row = roughness < 0.2f ? 0 : std::min(int((roughness - 0.2f) * 10.0f + 1e-4f), kSpecularLobeRows - 1);
    const float scale = roughness < 0.2f ? std::max(roughness, 0.0f) / 0.2f : 1.0f;
    float lowest = roughness;
    auto read = [&](float width) { lowest = std::min(lowest, std::max(scale * width, 0.35f * roughness)); };
    for (int model = 0; model < kSpecularLobeModels; ++model)
        for (int row = first_row; row < kSpecularLobeRows; ++row) {
            const int entry = (model * kSpecularLobeRows + row) * kSpecularLobeColumns;
            for (int i = 0; i < kSpecularLobeColumns * 3; ++i) read(kSpecularLobeEntries[entry * 3 + i][1]);
            // Any row's two lookups (FrameSettings::two_lookup_groups may allow them anywhere).
            for (int i = 0; i < kSpecularLobeColumns * 2; ++i) read(kSpecularLobeTwoEntries[entry * 2 + i][1]);
        }
    return lowest;
}

}  // namespace facet
