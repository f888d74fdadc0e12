#pragma once
// Prefiltered specular cube for the split sum (GGX, alpha = roughness^2): one roughness
// per mip level, level 0 = roughness 0 = the environment itself. Each level is made by
// a method chosen per level (design.md; bake.json records the roughness of each level).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/graph/render_graph.h>

namespace facet {

class ProgramCache;
class Sampler;

enum class SpecularMethod {
    automatic,   // per level: filtered importance sampling for smooth levels, convolve for rough ones
    importance,  // the thesis: GGX importance sampling with N Hammersley samples from level 0
    filtered,    // filtered importance sampling (Krivanek and Colbert 2008)
    convolve,    // deterministic sum over a small source level that resolves the lobe
    mips,        // the thesis' cheap alternative: the environment's own mip chain
    hybrid,      // filtered importance sampling of the environment clamped at a threshold, plus the
                 // excess above it summed exactly (a sun: one entry, not a thousand samples)
};

const char* specular_method_name(SpecularMethod method);
std::optional<SpecularMethod> parse_specular_method(const std::string& name);

struct SpecularSettings {
    SpecularMethod method = SpecularMethod::automatic;
    uint32_t levels = 6;               // roughness of level m = m / (levels - 1)
    uint32_t sample_count = 1024;      // importance / filtered
    float automatic_convolve_from = 0.5f;  // automatic: convolve at and above this roughness, hybrid below
    // hybrid: filtered samples of the residual. 128: at 96 the levels were within 0.21% of
    // 128's (all under 1.4% at 1024 x 512), but the thesis model's final image under
    // royal_esplanade at 1280 x 720 (issue 13's measure: facet-bench accuracy --brdf thesis
    // --pixels 4000) was 3.01% off in its worst group against a 3% target; 2.97% at 128.
    uint32_t hybrid_sample_count = 128;
    float excess_factor = 16.0f;           // hybrid: the threshold T, x the environment's mean luminance
    // hybrid: the residual's sampled part made at half the level's face size and read
    // bilinearly (seamless) by the level's texels, where the lobe spans enough texels of the
    // half size (hybrid_residual_at_half_size); the excess stays exact at the level's size.
    // A quarter of the samples: a 1024x512 bake's levels 1 and 2 89 -> 37 ms and 21 -> 12 ms
    // on lavapipe, and their error against the brute-force truth 0.04-1.40% before, 0.03-1.36%
    // after (venice_sunset_1k 0.53 -> 0.62% at level 1, the others equal or better). One
    // pipeline does both parts and the whole (a push constant chooses).
    bool hybrid_half_size_residual = true;
    // Model no more than the scene needs: levels that no lookup with roughness >= this
    // reaches (trilinear reads floor(roughness x (levels - 1)) and the level above) are
    // not computed; their texels stay undefined.
    float min_roughness = 0.0f;
    // Only levels [first_level, end_level) are computed (end 0: to the last), so that two
    // calls can fill one cube from two sources (light extraction: smooth levels from the
    // whole environment, rough ones from the map without its lights).
    uint32_t first_level = 0;
    uint32_t end_level = 0;
};

// Roughness of every level (level 0 = 0, last = 1).
std::vector<float> specular_level_roughness(uint32_t levels);
// The method a level actually uses.
SpecularMethod specular_level_method(const SpecularSettings& settings, float roughness);
// Whether a hybrid level of `roughness` and face size `face` makes its residual's part at
// half size (SpecularSettings::hybrid_half_size_residual): where the lobe's half width at
// half maximum in l (about 1.28 alpha radians) spans at least 1.25 texels of the half-size
// face at its centre (4 / face radians), i.e. alpha x face >= 3.9, and the half size is
// at least 8. The default bake's level 1 (roughness 0.2, faces of 128: 5.1) and level 2
// (0.4, 64: 10.2) do; a sharper level 1 (more levels, or a smaller cube) does not.
bool hybrid_residual_at_half_size(const SpecularSettings& settings, float roughness, uint32_t face);
// The first level computed: the later of first_level and the first one a lookup with
// roughness >= min_roughness can read.
uint32_t first_needed_specular_level(const SpecularSettings& settings);
// W = integral of D(h) (n.l) over the hemisphere of l, n = v (GGX, alpha = roughness^2): the
// hybrid method's normalisation of its excess entries.
double specular_lobe_weight(float roughness);
// Face size of the source level the convolve method reads for a roughness: texels of
// about a quarter of the GGX lobe's width, between 8 and 64 (the texel list keeps each
// block's radiance-weighted direction, so a sun stays where it is).
uint32_t convolve_source_size(float roughness);

// `environment`: the environment cube with its full mip chain (sampled through
// `cube_sampler`: linear, mipmapped). `specular`: an RGBA32F cube of the same face size
// with settings.levels levels. Returns the specular cube's final version.
// With `equirect` (the input, RGBA32F, at least 16 rows), convolve levels list its texels
// directly instead of a cube level's (no resampling between input and result), and with
// `equirect_sampler` too (linear, repeat in u), hybrid levels split the input itself.
// `level0_written`: `specular` is a version whose level 0 already holds the environment's
// level 0 (add_environment_cube_passes' mirror), so no copy pass is added for it.
Result<ImageHandle> add_specular_passes(RenderGraph& graph, ProgramCache& programs, const Sampler& cube_sampler,
                                        ImageHandle environment, ImageHandle specular, const SpecularSettings& settings,
                                        ImageHandle equirect = {}, const Sampler* equirect_sampler = nullptr,
                                        bool level0_written = false);

}  // namespace facet
