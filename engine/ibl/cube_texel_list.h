#pragma once
// The texel list the convolutions (irradiance, specular) sum over: one entry per texel
// of a coarse level of the environment cube, built from its level-0 children
// (shaders/ibl/cube_texels.comp: radiance-weighted direction, cap spread, radiance x
// solid angle, solid angle). Shared helpers for passes that write cube levels.
#include <cstdint>
#include <vector>

#include <facet/core/result.h>
#include <facet/core/shared_constants.h>
#include <facet/graph/render_graph.h>
#include <facet/shader/compiler.h>

namespace facet {

class Context;
class PassContext;
class Pipeline;
class ProgramCache;

struct CubeTexelList {
    BufferHandle buffer;  // 2 x vec4 per entry
    uint32_t count = 0;   // 6 x face^2
    // An upper bound on any entry's cap radius (radians): the block's half-diagonal rho
    // widened to sqrt(2) rho plus a child's own (a cap's mean resultant length over a set
    // of radius rho is at least cos(rho) times its children's).
    double max_spread = pi;
};

// Lists the texels of `level` of `environment` (a cube with its mip chain).
Result<CubeTexelList> add_cube_texel_list_pass(RenderGraph& graph, ProgramCache& programs, ImageHandle environment,
                                               uint32_t level, const std::string& name);

// The same list from blocks of texels of an equirectangular image (RGBA32F), sized to
// about `target_entries` entries.
Result<CubeTexelList> add_equirect_texel_list_pass(RenderGraph& graph, ProgramCache& programs, ImageHandle equirect,
                                                   uint32_t target_entries, const std::string& name);

// `pipeline`'s workgroups over every face of an n x n level (z: the 6 faces).
void dispatch_cube(PassContext& pc, const Pipeline& pipeline, uint32_t n);
// Faces first .. first + count - 1 of it (gl_GlobalInvocationID.z the face; the shader's
// local size in z 1), for a shader whose invocations make `texels_per_invocation_x` texels
// side by side in x.
void dispatch_cube_faces(PassContext& pc, const Pipeline& pipeline, uint32_t n, uint32_t first, uint32_t count,
                         uint32_t texels_per_invocation_x = 1);
// Texels side by side per invocation for the shaders that loop over a buffer for each
// texel (specular_hybrid, specular_convolve, irradiance_convolve: their TEXELS): 8 on a
// CPU device (lavapipe reads a buffer lane by lane; each read then serves eight texels),
// 1 on a GPU, which keeps its parallelism.
uint32_t texels_per_invocation(const Context& context);
// Lanes of a subgroup that read a list together in those shaders (shaders/ibl/list_lanes.glsl):
// the subgroup size on a CPU device whose compute subgroups are one fixed size dividing the
// 8 x 8 workgroup and can broadcast, 1 elsewhere (each lane reads every entry itself).
uint32_t list_lanes(const Context& context);
// Those shaders' defines: `texels_define` (their TEXELS) = texels_per_invocation, and
// FACET_LIST_LANES = list_lanes.
std::vector<ShaderDefine> list_shader_defines(const Context& context, const char* texels_define);

constexpr VkImageViewType cube_array_view = VK_IMAGE_VIEW_TYPE_2D_ARRAY;

}  // namespace facet
