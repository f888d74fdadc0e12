#pragma once
// The forward PBR frame as render-graph passes a host adds or leaves out: the forward
// pass (opaque and masked primitives, then blended ones sorted back to front) into the
// caller's colour and depth targets with the caller's matrices, the skybox composited
// under it, the display transform (render/tonemap.h) and one single-sample pass per
// component view (AOV). add_passes() composes them into the programs' frame. An engine
// can stop at linear HDR: add_forward_pass() alone.
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <facet/core/brdf_model.h>
#include <facet/core/result.h>
#include <facet/gpu/resources.h>
#include <facet/render/specular_lobes.h>
#include <facet/graph/render_graph.h>
#include <facet/render/camera.h>
#include <facet/shader/compiler.h>
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
    CameraView camera;               // add_passes only; the passes below take matrices
    DisplaySettings display;
    bool skybox = true;
    BrdfModel brdf = BrdfModel::gltf;  // design.md "BRDF models": lights, environment, views
    bool multiscatter = false;       // energy compensation (needs IBL: LUT and irradiance)
    bool dominant_direction = false; // three lookups fitted to the specular lobe (render/specular_lobes.h) instead of one along R
    // With dominant_direction, the groups of issue 13's measure (index 2 x band + metal; bands
    // of roughness 0.2 wide from 0.2, metal: metallic >= 0.5) whose materials bend the lookup:
    // a material reaching none of them (material_shading_groups) reads along R. The automatic
    // choice clears the groups where the plain lookup is predicted within the target.
    std::array<bool, 8> dominant_groups{true, true, true, true, true, true, true, true};
    // And the groups whose bent lookup may be two fitted lookups of equal weight instead of
    // three (one table read and one cube read fewer): a material gets them where every
    // bending group it reaches allows them. By default the bands from kTwoLookupsRoughness
    // (render/specular_lobes.h); the automatic choice adds smoother ones where two are
    // predicted within its margin, or where the target is out of reach and two are predicted
    // within kTwoLookupsTolerance of the frame's worst (render/shading_choice.h).
    std::array<bool, 8> two_lookup_groups = kDefaultTwoLookupGroups;
    std::vector<Light> lights;       // every punctual light of the frame
    // Bright regions taken out of the environment before the bake (light extraction),
    // shaded as disk lights with the full BRDF; the skybox shows them again.
    std::vector<DiskLight> environment_lights;
    // First specular level baked without the extracted lights (the smooth ones below it
    // hold them): the disks' specular fades in across the level below it.
    uint32_t environment_light_level = 0;
    std::vector<View> views;         // extra images, each RGBA32F, one sample per pixel
    // The rasterizer's floor, for benchmarks: the same draws, depth test and MSAA, each
    // fragment writing its material's base colour factor (no texture, no lighting).
    bool flat_floor = false;
};

struct FrameImages {
    ImageHandle hdr;  // RGBA32F linear radiance, before exposure
    ImageHandle ldr;  // RGBA8, tone-mapped and encoded
    std::vector<std::pair<View, ImageHandle>> views;
};

// Where the forward pass draws: images of the caller's graph (imported from a host
// engine, or created in the graph). `color`: any format the device can render to, any
// sample count; `depth`: a depth format, same size and samples. With `resolve` (single
// sample, colour's format) the MSAA colour is resolved into it and not stored.
struct ForwardTargets {
    ImageHandle color;
    ImageHandle depth;
    ImageHandle resolve;     // optional
    bool clear_color = true;  // to transparent black (alpha = coverage, as the skybox expects); else load
    bool clear_depth = true;  // to 0 (reversed Z: infinitely far); else load
    bool store_depth = true;  // keep the depth for the host's later passes
};

// The targets' new versions after the pass.
struct ForwardOutputs {
    ImageHandle color, depth, resolve;
};

class ForwardRenderer {
public:
    // `frames_in_flight` slots of per-frame data (camera, lights, disks): the pass writes
    // slot `frame` when it is recorded, so the host must have waited for the work last
    // recorded with that slot (its frame fence) before recording the slot again. Every
    // pass of one slot in one frame shares its camera and lights. An Error when the
    // device cannot make the samplers or slot buffers; frames_in_flight 0: UsageError.
    // Device failures while a pass records (a slot's lights buffer growing) reach the
    // caller as the Error of the run that records it (GraphExecutor, GraphRun).
    static Result<std::unique_ptr<ForwardRenderer>> create(Context& context, ProgramCache& programs,
                                                           uint32_t frames_in_flight = 1);
    ~ForwardRenderer();

    uint32_t frames_in_flight() const { return static_cast<uint32_t>(slots_.size()); }

    // The programs' frame: Facet's own RGBA32F MSAA target resolved to `hdr`, the
    // look-at camera of `settings`, then the skybox (when on and an environment is
    // given), the display transform and one pass per requested view.
    Result<FrameImages> add_passes(RenderGraph& graph, const GpuScene& scene, const FrameSettings& settings,
                                   const std::optional<IblInputs>& ibl, uint32_t frame = 0);

    // The forward pass alone into the caller's targets, with the caller's matrices;
    // `settings` gives the lights and the shading options (its size, samples, camera,
    // skybox, display and views are not used). Linear HDR out: nothing after it. Where an
    // instance transmits (KHR_materials_transmission), the opaque scene is first drawn
    // without it into a transient mipmapped image of the targets' size (a graphics pass and
    // one compute pass per mip level), which the transmissive surfaces read.
    Result<ForwardOutputs> add_forward_pass(RenderGraph& graph, const GpuScene& scene, const FrameSettings& settings,
                                            const CameraMatrices& camera, const ForwardTargets& targets,
                                            const std::optional<IblInputs>& ibl, uint32_t frame = 0);

    // Composites the environment (and the extracted lights of `settings`) under `hdr`
    // (RGBA32F or RGBA16F, storage-capable, alpha = coverage) as seen by `camera`;
    // returns the new version of `hdr`.
    Result<ImageHandle> add_skybox_pass(RenderGraph& graph, ImageHandle hdr, const FrameSettings& settings,
                                        const CameraMatrices& camera, const IblInputs& ibl, uint32_t frame = 0);
    // The same with the look-at camera of `settings` (its width and height give the aspect).
    Result<ImageHandle> add_skybox_pass(RenderGraph& graph, ImageHandle hdr, const FrameSettings& settings,
                                        const IblInputs& ibl, uint32_t frame = 0);

    // One component view (an AOV) of the scene into a new single-sample RGBA32F image of
    // settings.width x height; returns it.
    Result<ImageHandle> add_view_pass(RenderGraph& graph, const GpuScene& scene, View view,
                                      const FrameSettings& settings, const CameraMatrices& camera,
                                      const std::optional<IblInputs>& ibl, uint32_t frame = 0);

    // Pipeline variants created so far (each a distinct feature set).
    size_t pipeline_variants() const { return variants_.size(); }

private:
    struct DrawList {
        std::vector<uint32_t> opaque;  // instance indices
        std::vector<uint32_t> blend;   // back to front
    };
    struct Target {
        VkFormat color = VK_FORMAT_UNDEFINED, depth = VK_FORMAT_UNDEFINED;
        VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    };
    // Per-frame buffers of one slot, host-visible, written when a pass is recorded and
    // grown (never shrunk) when a frame has more lights than they hold.
    struct Slot {
        Buffer frame, lights;
    };
    // The extracted disks as pipeline constants, made once per pass by pipelines(): all of
    // them, and those a lobe of each roughness tells apart (render/lobe_disks.h), filled as
    // materials of that roughness ask (a grid of spheres has 49 instances and 7 roughnesses).
    struct PassDisks {
        std::vector<ShaderDefine> all;
        std::map<float, std::vector<ShaderDefine>> by_roughness;
    };
    Result<const Pipeline*> material_pipeline(const GpuScene& scene, uint32_t instance, View view,
                                              const Target& target, bool ibl, const FrameSettings& settings,
                                              PassDisks& disks);
    // `opaque_background`: only the instances the transmission background draws (the others null).
    Result<std::vector<const Pipeline*>> pipelines(const GpuScene& scene, View view, const Target& target,
                                                   bool ibl, const FrameSettings& settings,
                                                   bool opaque_background = false);
    DrawList draw_list(const GpuScene& scene, glm::vec3 camera_position) const;
    // Adds one graphics pass drawing every instance that has a pipeline in `pipelines`
    // (shared by the forward pass, the views and the transmission background); `background`,
    // when valid, is what transmissive surfaces see behind them (sampled).
    ForwardOutputs add_draw_pass(RenderGraph& graph, const std::string& name, const GpuScene& scene,
                                 const FrameSettings& settings, const CameraMatrices& camera,
                                 const ForwardTargets& targets, const std::optional<IblInputs>& ibl,
                                 std::vector<const Pipeline*> pipelines, uint32_t frame, ImageHandle background = {});
    // KHR_materials_transmission: the opaque scene without the transmissive instances drawn
    // into a mipmapped RGBA16F image of the target's size (premultiplied colour, alpha its
    // coverage); returns it, or an invalid handle where no instance transmits.
    Result<ImageHandle> add_transmission_background(RenderGraph& graph, const GpuScene& scene,
                                                    const FrameSettings& settings, const CameraMatrices& camera,
                                                    uint32_t width, uint32_t height,
                                                    const std::optional<IblInputs>& ibl, uint32_t frame);
    Slot& slot(uint32_t frame);
    ForwardRenderer(Context& context, ProgramCache& programs, uint32_t frames_in_flight);

    Context& context_;
    ProgramCache& programs_;
    std::vector<Slot> slots_;
    Sampler nearest_, lut_sampler_, background_sampler_;
    // Binding 25 where there is no transmission background: transparent black.
    Image no_background_;
    VkImageView no_background_view_ = VK_NULL_HANDLE;
    // The fitted lookups' table (render/specular_lobes.h), uploaded once.
    Image lobe_table_;
    VkImageView lobe_table_view_ = VK_NULL_HANDLE;
    std::set<std::string> variants_;
};

}  // namespace facet
