#pragma once
// The environment as a cube map with a full mip chain, built by compute passes:
// equirect -> level 0, then each level from the one above by solid-angle weighting.
#include <cstdint>
#include <string>

#include <facet/core/result.h>
#include <facet/graph/render_graph.h>

namespace facet {

class ProgramCache;
class Sampler;
struct ProceduralSky;

// Face size for an equirect of the given height: about height / 2 (design choice: a cube
// face texel then spans about the angle of an equirect texel), at least 1.
uint32_t cube_size_for(uint32_t equirect_height);
uint32_t full_mip_count(uint32_t size);

// The cube image description: RGBA32F, 6 layers, cube-compatible, `mips` levels.
ImageDesc environment_cube_desc(uint32_t size, uint32_t mips);

// Fills every level of `cube` from `equirect` (sampled with `equirect_sampler`: linear,
// repeat in u; taps x taps bilinear samples per texel); returns the cube's final version.
// Passes named `name` and `name` mip M (default "equirect to cube", "cube mip M").
// With `mirror` (a valid cube of the same face size and format) level 0 is written there
// too, and *mirror becomes its written version: specular level 0 without a copy pass.
Result<ImageHandle> add_environment_cube_passes(RenderGraph& graph, ProgramCache& programs,
                                                const Sampler& equirect_sampler, ImageHandle equirect,
                                                ImageHandle cube, uint32_t taps = 4, const std::string& name = "",
                                                ImageHandle* mirror = nullptr);

// Whether `mirror` (if given and valid) can take `cube`'s level 0: a cube of the same face
// size and format. The error names `pass`.
Status check_cube_mirror(const RenderGraph& graph, ImageHandle cube, const ImageHandle* mirror, const std::string& pass);

// Level 0 of `cube` straight from builtin:sky's model, taps 4 x 4 a texel as above
// (shaders/ibl/procedural_sky_cube.comp; pass "procedural sky to cube"), `mirror` as above;
// returns the version with level 0 written (add_cube_mip_passes makes the rest).
Result<ImageHandle> add_procedural_sky_cube_pass(RenderGraph& graph, ProgramCache& programs, const ProceduralSky& sky,
                                                 ImageHandle cube, ImageHandle* mirror = nullptr);

// Levels 1 .. of `cube` (a version whose level 0 is written), each from the one above
// (shaders/ibl/cube_downsample.comp); passes named `name` + level. Returns the final version.
Result<ImageHandle> add_cube_mip_passes(RenderGraph& graph, ProgramCache& programs, ImageHandle cube,
                                        const std::string& name);

}  // namespace facet
