#pragma once
// The table of the split sum's fitted lookups: for each BRDF model, roughness and n.v, three
// lookups of the prefiltered cube whose kernels, summed, follow the true specular lobe
// D V (n.l) (fitted by least squares: scripts/fit_specular_lobes.py). The forward pass binds it
// for the dominant and automatic shading methods; a host engine whose own shaders call
// facet_environment_light with fitted lookups (shaders/facet/shading.glsl) uploads these
// texels as a VK_FORMAT_R32G32B32A32_UINT image and binds it as a usampler2D (the shader
// reads it with texelFetch: any sampler).
#include <cstdint>
#include <vector>

#include <facet/core/shared_constants.h>

namespace facet {

// Entries per axis: n.v 0.1 .. 0.9 and roughness 0.2 .. 1 in 64 steps each (a constant shared with
// the shaders), fine enough that
// the shader reads the nearest entry, one unfiltered fetch per pixel (two bilinear fetches of
// the fit's 9 x 9 entries cost a third of the plain split sum's frame on lavapipe).
inline constexpr uint32_t kSpecularLobeTableSteps = uint32_t(specular_lobe_table_steps);
inline constexpr uint32_t kSpecularLobeTableWidth = kSpecularLobeTableSteps + 1;         // n.v columns
inline constexpr uint32_t kSpecularLobeTableHeight = 2 * (kSpecularLobeTableSteps + 1);  // 2 BRDF models x roughness rows

// RGBA32UI texels, row 0 first: texel (column, model * (steps + 1) + row) holds the fit's lookups,
// interpolated linearly between its 9 x 9 entries, as eight halves packed two to a channel
// (GLSL packHalf2x16: the first in the low 16 bits): (t0, t1), (t2, w0), (r0, r1), (r2, w1).
// Lookup k reads along normalize(mix(n, R, t_k)) at roughness r_k with weight w_k,
// w2 = 1 - w0 - w1 (the fit's weights sum to 1). t_k is the fit's fraction s_k of the angle
// theta = acos(n.v) from n to R turned into the linear weight that reaches the same direction
// at the entry's n.v, sin(s theta) / (sin(s theta) + sin((1 - s) theta)), so that the shader
// needs no trigonometry.
std::vector<uint32_t> specular_lobe_table_texels();

// The eight numbers of one texel, unpacked: t0, t1, t2, w0, r0, r1, r2, w1.
struct SpecularLobeEntry {
    float t[3];
    float r[3];
    float w[3];  // w[2] = 1 - w[0] - w[1]
};
SpecularLobeEntry specular_lobe_table_entry(const std::vector<uint32_t>& texels, uint32_t model, uint32_t column,
                                            uint32_t row);

// The smallest roughness that the fitted lookups of any surface at `roughness` or rougher
// read (their kernels are narrower than the surface's lobe): the bake keeps the specular
// levels from there on (ibl/bake_rules.h, ibl_settings_for_scene).
float lowest_lookup_roughness(float roughness);

}  // namespace facet
