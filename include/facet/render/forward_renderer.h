#pragma once
// The forward PBR frame as render-graph passes: the forward pass (opaque and masked
// primitives, then blended ones sorted back to front, into an MSAA HDR target resolved
// at the end), the skybox composited under it (when on and an environment is given),
// the display transform, and
// one single-sample pass per requested view (AOV). Only what the frame needs is added:
// no skybox when it is off, no IBL inputs without an environment.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/gpu/resources.h>
#include <facet/graph/render_graph.h>
#include <facet/render/camera.h>
#include <facet/render/tonemap.h>
#include <facet/render/views.h>
#include <facet/ibl/light_extraction.h>
#include <facet/scene/scene.h>

namespace facet {

class Context;
class GpuScene;
class Pipeline;
class ProgramCache;

// Image-based lighting baked earlier in the same graph (ibl/ibl_bake.h).
struct IblInputs {
    ImageHandle cube;        // environment cube (skybox)
    ImageHandle irradiance;  // E/pi cube; invalid: no diffuse IBL (a scene of pure metals)
    ImageHandle specular;    // prefiltered cube, roughness level / (levels - 1)
    ImageHandle lut;         // split-sum A, B
    uint32_t specular_levels = 1;
    VkSampler cube_sampler = VK_NULL_HANDLE;  // linear, mipmapped, clamped
    float intensity = 1.0f;
};

struct FrameSettings {
    uint32_t width = 1280, height = 720;
    uint32_t samples = 4;  // MSAA of the final colour (views are single-sample)
    CameraView camera;
    DisplaySettings display;
    bool skybox = true;
    bool height_correlated = false;  // glTF's Smith visibility for punctual lights
    bool multiscatter = false;       // energy compensation (needs IBL: LUT and irradiance)
    bool dominant_direction = false; // specular lookup bent towards n for rough lobes
    std::vector<Light> lights;       // every punctual light of the frame
    // Bright regions taken out of the environment before the bake (light extraction),
    // shaded as disk lights with the full BRDF; the skybox shows them again.
    std::vector<DiskLight> environment_lights;
    // First specular level baked without the extracted lights (the smooth ones below it
    // hold them): the disks' specular fades in across the level below it.
    uint32_t environment_light_level = 0;
    std::vector<View> views;         // extra images, each RGBA32F, one sample per pixel
};

struct FrameImages {
    ImageHandle hdr;  // RGBA32F linear radiance, before exposure
    ImageHandle ldr;  // RGBA8, tone-mapped and encoded
    std::vector<std::pair<View, ImageHandle>> views;
};

class ForwardRenderer {
public:
    ForwardRenderer(Context& context, ProgramCache& programs);
    ~ForwardRenderer();

    // The host-visible frame data written here is read when the graph runs, so one
    // frame at a time per renderer.
    Result<FrameImages> add_passes(RenderGraph& graph, const GpuScene& scene, const FrameSettings& settings,
                                   const std::optional<IblInputs>& ibl);

    // Composites the environment under `hdr` (RGBA32F, alpha = coverage) as seen by the
    // frame's camera; returns the new version of `hdr`.
    Result<ImageHandle> add_skybox_pass(RenderGraph& graph, ImageHandle hdr, const FrameSettings& settings,
                                        const IblInputs& ibl);

    // Pipeline variants created so far (each a distinct feature set).
    size_t pipeline_variants() const { return variants_.size(); }

private:
    struct DrawList {
        std::vector<uint32_t> opaque;  // instance indices
        std::vector<uint32_t> blend;   // back to front
    };
    Result<const Pipeline*> material_pipeline(const GpuScene& scene, uint32_t material, View view,
                                              VkSampleCountFlagBits samples, bool ibl, const FrameSettings& settings);
    DrawList draw_list(const GpuScene& scene, const CameraView& camera) const;

    Context& context_;
    ProgramCache& programs_;
    Buffer frame_, lights_, sky_disks_;
    Sampler nearest_, lut_sampler_;
    std::set<std::string> variants_;
};

}  // namespace facet
