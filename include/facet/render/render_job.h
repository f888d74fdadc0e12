#pragma once
// A whole rendering job, as facet-render, facet-viewer and facet-bench run it: load a
// model and an environment, get the image-based lighting (a saved bake, the bake cache's
// entry, or a fresh bake: ibl/baked_environment.h), then draw frames through a long-lived
// GraphExecutor that imports the baked images. The programs keep only their command
// lines, file naming and UI; an engine uses the pieces (ForwardRenderer, GraphExecutor,
// BakedEnvironment) directly.
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/graph/graph_run.h>
#include <facet/ibl/bake_settings.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/render/forward_renderer.h>
#include <facet/render/reference_renderer.h>
#include <facet/render/shading_method.h>
#include <facet/scene/gltf_loader.h>
#include <facet/scene/scene.h>

namespace facet {

class BakedEnvironment;
class Context;
class GpuScene;
class ProgramCache;

struct RenderJob {
    std::string model = "builtin:spheres";
    std::string env = "builtin:sky";  // "none": no image-based lighting
    std::optional<std::string> preset;
    uint32_t env_width = 1024;  // built-in environments
    uint32_t max_env_width = kDefaultMaxEnvironmentWidth;  // wider files are downsampled while read
    GltfLimits model_limits;    // memory budget of a glTF model (scene/gltf_loader.h)
    int model_scene = -1;       // the glTF file's scene to draw (-1: its default scene)
    bool sanitize = false;
    IblSettings ibl;
    FrameSettings frame;  // camera: see below; lights: the scene's plus extra_lights
    std::optional<std::array<float, 3>> orbit;  // theta, phi (degrees), radius
    std::optional<glm::vec3> target;
    float fov_deg = 45.0f;
    bool gltf_camera = false;  // the file's first camera instead of framing the bounds
    std::vector<Light> extra_lights;
    float ibl_intensity = 1.0f;
    // How the environment lights surfaces (render/shading_method.h); automatic by default.
    // The older switches below add their part (to the plain split sum when automatic).
    ShadingMethod shading = ShadingMethod::automatic;
    // The automatic choice takes the cheapest method whose predicted error is within this in
    // every group of issue 13's measure (a fraction, 0 < target_error < 1; create() returns an
    // Error otherwise).
    double target_error = 0.03;
    // Predict a method named explicitly too (a probe render and the truth at 480 pixels: about
    // 0.3 s per session on lavapipe); the automatic choice always predicts.
    bool predict_named_method = false;
    bool extract_lights = false;  // suns and lamps out of the map, shaded as disk lights
    LightExtractionSettings extraction;  // what counts as a light (ibl/light_extraction.h)
    std::string shader_dir;       // read shaders from here (hot reload); empty: embedded (programs: FACET_SHADER_DIR)
    std::string shader_cache_dir; // on-disk SPIR-V cache (apps/shader_cache.h); empty: none
    // Pipelines shared with other sessions on the same Context (nullptr: the session compiles
    // and builds its own, from shader_dir and shader_cache_dir, as every session used to).
    // Each session's first frame otherwise creates every pipeline it draws with again: about
    // 2-4 s on lavapipe for builtin:spheres with IBL. The caller owns the cache (and its
    // ShaderCompiler, whose options then stand for shader_dir and shader_cache_dir, which
    // are not read) and keeps it until the last session using it is destroyed; create()
    // returns an Error for a cache of another Context. ProgramCache is not synchronised: the
    // sessions sharing one are created and drawn from one thread at a time. Their
    // reload_shaders() rebuilds the whole cache, every sharing session's pipelines with it.
    ProgramCache* programs = nullptr;
    std::string ibl_dir;          // a saved bake (facet-bake's files) used instead of baking: `env` and the
                                  // bake's settings are then not read (the bake's input is the environment)
    std::string bake_cache_dir;   // bakes kept by bake key (facet/cache/directory_cache.h); empty: none
    uint64_t bake_cache_max_bytes = 4ull << 30;
};

struct RenderedImages {
    uint32_t width = 0, height = 0;
    std::vector<float> hdr;    // RGBA linear radiance, before exposure
    std::vector<uint8_t> ldr;  // RGBA8, display-encoded
    std::vector<std::pair<View, std::vector<float>>> views;
    std::vector<PassTiming> timings;
    std::vector<PassTiming> pass_wall;  // pass by pass only: submit-to-done wall time per pass
    double wall_ms = 0;
};

using ProgressFn = std::function<void(const std::string& line)>;

// Everything loaded and baked, ready to render frames. Errors: every call returns what the user's
// files, the data or the device can cause as an Error (with its VkResult for device
// failures); no exception leaves it.
class RenderSession {
public:
    // What creating a session reports, and where its caller may stop it (a viewer loading
    // on a worker thread while it draws the previous session): progress lines, the
    // bake's passes as they finish, and `stop`, asked at the bake's safe points
    // (ibl/bake_settings.h) and between the loading steps ("model", "environment",
    // "shading", "scene"). A stopped creation frees what it made and returns an Error for
    // which is_cancelled() is true. A saved bake (RenderJob::ibl_dir) loads unstopped.
    struct Callbacks {
        ProgressFn progress;
        BakePassFn bake_pass_done;
        BakeStopFn stop;
    };

    static Result<std::unique_ptr<RenderSession>> create(Context& context, const RenderJob& job,
                                                         const ProgressFn& progress = {});
    static Result<std::unique_ptr<RenderSession>> create(Context& context, const RenderJob& job,
                                                         const Callbacks& callbacks);
    // The same with a scene built by the caller (job.model and job.preset are ignored).
    static Result<std::unique_ptr<RenderSession>> create(Context& context, const RenderJob& job, Scene scene,
                                                         const ProgressFn& progress = {});
    static Result<std::unique_ptr<RenderSession>> create(Context& context, const RenderJob& job, Scene scene,
                                                         const Callbacks& callbacks);
    ~RenderSession();

    // Draws one frame with the job's settings and reads every image back. With
    // `pass_by_pass`, each pass is its own submission (waited for), so that GPU time is
    // attributed to the right pass on drivers that defer rasterisation (lavapipe).
    Result<RenderedImages> render_frame(bool pass_by_pass = false);
    // The same frame from the reference renderer (render/reference_renderer.h): Monte
    // Carlo over the whole environment until the noise target; views as requested.
    Result<RenderedImages> render_reference(const ReferenceSettings& settings,
                                            const ReferenceRenderer::Progress& progress = {},
                                            ReferenceStats* stats = nullptr);

    // The frame's passes (forward, skybox, tone mapping, views) in a caller's graph, with
    // the baked images imported, for hosts that add their own passes after them (the
    // viewer's copy to the swapchain). The graph must run before the next call.
    Result<FrameImages> add_frame_passes(RenderGraph& graph);
    // Camera, size and display for the next frames.
    FrameSettings& frame_settings();
    // The pieces a host's own graph uses with the lower-level passes
    // (render/forward_renderer.h): the renderer (one frame slot), the scene on the GPU,
    // the pipeline cache (RenderJob::programs when shared), and the baked images imported
    // into `graph` (none without IBL).
    ForwardRenderer& renderer();
    const GpuScene& gpu_scene() const;
    ProgramCache& programs();
    std::optional<IblInputs> import_baked(RenderGraph& graph);
    // Every material's base colour, metalness, roughness and occlusion factors replaced
    // (textures, when kept, still multiply them, as in glTF), or the scene's own back.
    struct MaterialFactors {
        glm::vec3 albedo{1.0f};
        float metallic = 0.0f, roughness = 0.5f, occlusion = 1.0f;
        // Each input as a factor alone or times the model's texture (the thesis' choice).
        bool albedo_texture = true, metal_rough_texture = true, occlusion_texture = true;
    };
    // An Error when the device fails uploading them (the GPU scene keeps the old materials).
    Status override_materials(const std::optional<MaterialFactors>& factors);
    // Shader hot reload: every pipeline built again from the current sources, all or
    // nothing (a compile error keeps the last good ones and is returned). Between frames.
    // With a shared cache (RenderJob::programs) that is every pipeline of the cache, so
    // between the frames of every session sharing it: their pipelines are replaced in
    // place (ProgramCache::reload), and none of them may have recorded work pending.
    Result<size_t> reload_shaders();
    // IBL methods this environment takes outside their domain (ibl/method_domain.h).
    const std::vector<std::string>& warnings() const;
    // The shading method in use and why (the automatic choice included).
    const ShadingChoice& shading() const;

    const Scene& scene() const;
    const CameraView& camera() const;
    const FrameSettings& frame() const;
    // The environment as resolved and baked here; nullptr without IBL and with a saved
    // bake (RenderJob::ibl_dir), whose environment baked() describes.
    const EnvironmentSource* environment() const;
    // The image-based lighting in use (its metadata name the bake's input); nullptr without.
    const BakedEnvironment* baked() const;
    const std::vector<PassTiming>& bake_timings() const;
    size_t pipeline_variants() const;

    struct State;

private:
    explicit RenderSession(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace facet
