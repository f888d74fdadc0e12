#pragma once
// The split-sum BRDF LUT of one BRDF model as two compute passes: the scale and bias
// (A, B) of specular = prefiltered * (F0 * A + B) and the diffuse lobe's mean Fresnel
// weight (fourth channel), then the average albedo per roughness for multiscatter
// compensation in the third channel. Layout fixed in design.md.
#include <cstdint>

#include <facet/core/brdf_model.h>
#include <facet/core/result.h>
#include <facet/graph/render_graph.h>

namespace facet {

class ProgramCache;

struct BrdfLutSettings {
    uint32_t size = 128;            // width = height
    uint32_t sample_count = 2048;   // Hammersley samples per texel (max abs error < 1e-3)
    BrdfModel brdf = BrdfModel::gltf;  // the model whose specular lobe the LUT integrates
};

// Writes the LUT into `lut` (RGBA32F, settings.size square); returns its final version.
Result<ImageHandle> add_brdf_lut_passes(RenderGraph& graph, ProgramCache& programs, const BrdfLutSettings& settings,
                                        ImageHandle lut);

}  // namespace facet
