#pragma once
// Diffuse irradiance, stored as E(n) / pi in a small cube (design.md), by one of the
// methods the thesis and its references discuss, each a compute pass of the graph.
#include <cstdint>
#include <optional>
#include <string>

#include <facet/core/result.h>
#include <facet/graph/render_graph.h>

namespace facet {

class ProgramCache;
class Sampler;

enum class IrradianceMethod {
    convolve,  // exact cosine convolution over every texel of a small level (default)
    riemann,   // the thesis' Riemann sum over (phi, theta) with a step
    sh9,       // 9 spherical-harmonic coefficients per channel (optionally windowed)
    blur,      // spherical Gaussian blur of a small level (cheap alternative)
    lowmip,    // trilinear sample of a low level (cheapest alternative)
};

const char* irradiance_method_name(IrradianceMethod method);
std::optional<IrradianceMethod> parse_irradiance_method(const std::string& name);

struct IrradianceSettings {
    IrradianceMethod method = IrradianceMethod::convolve;
    uint32_t size = 32;          // output face size
    uint32_t source_size = 16;   // convolve/blur: largest source face size used
    float riemann_step = 0.025f; // riemann: step in radians (the thesis' value)
    float blur_sigma = 0.5f;     // blur: Gaussian width in radians
    uint32_t lowmip_size = 2;    // lowmip: face size of the level sampled
    bool sh9_windowing = true;   // sh9: the weakest window that keeps irradiance >= 0
};

// Reads `environment` (a cube with its full mip chain, sampled with `cube_sampler`:
// linear, mipmapped) and writes `irradiance` (RGBA32F cube, settings.size, 1 level).
// When `equirect` (the input image, RGBA32F) is given, convolve, blur and sh9 list its
// texels directly instead of the cube's, so no resampling stands between input and result.
// For sh9, `sh9_coefficients` (if given) receives the buffer of 10 vec4: L_i for
// i = 0..8 (RGB, before the cosine kernel) and the window parameter h in [9].x (0: none).
Result<ImageHandle> add_irradiance_passes(RenderGraph& graph, ProgramCache& programs, const Sampler& cube_sampler,
                                          ImageHandle environment, ImageHandle irradiance,
                                          const IrradianceSettings& settings,
                                          BufferHandle* sh9_coefficients = nullptr, ImageHandle equirect = {});

// The level of a cube of face `size` whose faces are at most `max_face` texels wide.
uint32_t level_at_most(uint32_t size, uint32_t mip_levels, uint32_t max_face);

}  // namespace facet
