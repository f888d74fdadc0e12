#pragma once
// The table of the split sum's fitted lookups: for each BRDF model, roughness and n.v, three
// lookups of the prefiltered cube whose kernels, summed, follow the true specular lobe
// D V (n.l) (fitted by least squares: scripts/fit_specular_lobes.py). The forward pass binds it
// for the dominant and automatic shading methods; a host engine whose own shaders call
// facet_environment_light with fitted lookups (shaders/facet/shading.glsl) uploads these
// texels as a VK_FORMAT_R32G32B32A32_SFLOAT image and samples it linearly, clamped to edge.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <facet/render/shading_method.h>

namespace facet {

inline constexpr uint32_t kSpecularLobeTableWidth = 27;   // 3 texels x 9 n.v columns (0.1 .. 0.9)
inline constexpr uint32_t kSpecularLobeTableHeight = 18;  // 2 BRDF models x 9 roughness rows (0.2 .. 1)

// Two lookups of equal weight instead of three (fitted alike: scripts/fit_specular_lobes.py
// --two) cost one table read and one cube read fewer. From this roughness up they keep every
// group within its targets, so the bands from it read two by default
// (FrameSettings::two_lookup_groups); below it they can leave the image outside them
// (docs/accuracy.md: venice_sunset's [0.4,0.6) metal 4.0%), so there the automatic choice
// takes them only where predicted within the target's margin, or where the target is out
// of reach and they are about as good (render/shading_choice.h, kTwoLookupsTolerance).
inline constexpr float kTwoLookupsRoughness = 0.6f;

// Those bands as groups of issue 13's measure (kShadingGroupBandLow, render/shading_method.h):
// FrameSettings::two_lookup_groups' default.
constexpr std::array<bool, 8> default_two_lookup_groups() {
    std::array<bool, 8> groups{};
    for (std::size_t g = 0; g < groups.size(); ++g) groups[g] = kShadingGroupBandLow[g / 2] >= kTwoLookupsRoughness - 1e-4f;
    return groups;
}
inline constexpr std::array<bool, 8> kDefaultTwoLookupGroups = default_two_lookup_groups();

// RGBA texels, row 0 first, three per entry so that the shader reads them with two fetches
// (three lookups) or one (two): texel (column, model * 9 + row) holds (t0, t1, t2, w0), texel
// (9 + column, model * 9 + row) (r0, r1, r2, w1) and texel (18 + column, model * 9 + row) the
// two lookups' (t0, t1, r0, r1); lookup k reads along normalize(mix(n, R, t_k)) at roughness
// r_k with weight w_k, w2 = 1 - w0 - w1 (the fit's weights sum to 1; the two lookups weigh
// one half each). t_k is the fit's fraction s_k of the angle theta = acos(n.v) from n to R
// turned into the linear weight that reaches the same direction at the column's n.v,
// sin(s theta) / (sin(s theta) + sin((1 - s) theta)), so that the shader needs no trigonometry.
std::vector<float> specular_lobe_table_texels();

// The smallest roughness that the fitted lookups of any surface at `roughness` or rougher
// read (their kernels are narrower than the surface's lobe): the bake keeps the specular
// levels from there on (ibl/bake_rules.h, ibl_settings_for_scene).
float lowest_lookup_roughness(float roughness);

}  // namespace facet
