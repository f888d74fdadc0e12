#pragma once
// What a RenderSession holds (facet/render/render_job.h), shared by the files that implement it:
// render_job.cpp (loading, baking, forward frames) and render_reference.cpp.
#include <memory>
#include <optional>
#include <vector>

#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_executor.h>
#include <facet/graph/graph_run.h>
#include <facet/render/render_job.h>
#include <facet/ibl/baked_environment.h>
#include <facet/shader/program_cache.h>
#include "render/shading_choice.h"

namespace facet {

class GpuScene;

struct RenderSession::State {
    Context* context = nullptr;
    RenderJob job;
    Scene scene;
    std::optional<EnvironmentSource> env;
    std::unique_ptr<ShaderCompiler> compiler;    // the session's own (none with a shared cache)
    std::unique_ptr<ProgramCache> own_programs;  // likewise
    ProgramCache* programs = nullptr;            // own_programs, or RenderJob::programs (the caller's)
    std::optional<BakedEnvironment> baked;  // the image-based lighting (nothing without an environment)
    IblSettings ibl_settings;               // as baked
    std::vector<PassTiming> bake_timings;
    std::unique_ptr<GpuScene> gpu_scene;
    std::unique_ptr<ForwardRenderer> renderer;
    std::unique_ptr<GraphExecutor> executor;  // frames of render_frame(), one at a time
    std::unique_ptr<ReferenceRenderer> reference;
    std::unique_ptr<Sampler> nearest;
    std::vector<float> original_texels;  // the environment before light extraction
    std::vector<Material> materials;      // the scene's own, before any override
    std::vector<std::string> warnings;    // IBL methods used outside their domain
    int textures_on = 7;                  // bits: albedo, metallic-roughness, occlusion textures used
    FrameSettings frame;
    ResolvedShading shading;
};

inline const ResourceState readable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                             VK_ACCESS_2_TRANSFER_READ_BIT};
inline const ResourceState sampled_by_fragments{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

// The baked images as imported resources of a frame's graph (nothing without IBL).
std::optional<IblInputs> import_ibl(RenderSession::State& s, RenderGraph& graph);
// One RGBA32F image, mip 0 / layer 0, in `layout`.
std::vector<float> read_floats(Context& context, const Image& image, VkImageLayout layout);

}  // namespace facet
