// RenderSession::render_reference (the reference mode for a whole frame) and the helpers
// every frame of a session shares: importing the baked IBL images, reading images back.
#include <algorithm>
#include <chrono>
#include <cstring>

#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/render/gpu_scene.h>
#include "render/render_session_state.h"
#include "core/guarded.h"

namespace facet {

// The baked images enter a frame's graph as imported resources, already readable by
// shaders, and are left that way for the next frame.
std::optional<IblInputs> import_ibl(RenderSession::State& s, RenderGraph& graph) {
    if (!s.baked) return std::nullopt;
    return import_baked_environment(graph, *s.baked, s.job.ibl_intensity);
}

std::vector<float> read_floats(Context& context, const Image& image, VkImageLayout layout) {
    auto bytes = or_throw(read_image(context, image, 0, 0, layout));
    std::vector<float> values(bytes.size() / sizeof(float));
    std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
    return values;
}

Result<FrameImages> RenderSession::add_frame_passes(RenderGraph& graph) {
    State& s = *state_;
    return s.renderer->add_passes(graph, *s.gpu_scene, s.frame, import_ibl(s, graph));
}

FrameSettings& RenderSession::frame_settings() { return state_->frame; }
ForwardRenderer& RenderSession::renderer() { return *state_->renderer; }
const GpuScene& RenderSession::gpu_scene() const { return *state_->gpu_scene; }
ProgramCache& RenderSession::programs() { return *state_->programs; }
std::optional<IblInputs> RenderSession::import_baked(RenderGraph& graph) { return facet::import_ibl(*state_, graph); }

const std::vector<std::string>& RenderSession::warnings() const { return state_->warnings; }
const ShadingChoice& RenderSession::shading() const { return state_->shading.choice; }

Result<size_t> RenderSession::reload_shaders() { return state_->programs->reload(); }

Status RenderSession::override_materials(const std::optional<MaterialFactors>& factors) {
    State& s = *state_;
    if (s.materials.empty()) s.materials = s.scene.materials;
    const int had_textures = s.textures_on;
    s.scene.materials = s.materials;
    s.textures_on = !factors ? 7
                             : (factors->albedo_texture ? 1 : 0) | (factors->metal_rough_texture ? 2 : 0) |
                                   (factors->occlusion_texture ? 4 : 0);
    if (factors)
        for (Material& m : s.scene.materials) {
            m.base_color = glm::vec4(factors->albedo, m.base_color.a);
            m.metallic = factors->metallic;
            m.roughness = factors->roughness;
            m.occlusion = factors->occlusion;
            if (!factors->albedo_texture) m.base_color_texture = {};
            if (!factors->metal_rough_texture) m.metallic_roughness_texture = {};
            if (!factors->occlusion_texture) m.occlusion_texture = {};
        }
    // Factors alone: new buffer contents. A texture switched on or off: other shader
    // variants and descriptors, so the GPU scene is built again.
    if (had_textures == s.textures_on) return s.gpu_scene->update_materials(s.scene.materials);
    auto rebuilt = GpuScene::create(*s.context, s.scene);
    if (!rebuilt) return rebuilt.error();
    s.gpu_scene = std::move(*rebuilt);
    return Ok{};
}

Result<RenderedImages> RenderSession::render_reference(const ReferenceSettings& settings,
                                                       const ReferenceRenderer::Progress& progress,
                                                       ReferenceStats* stats_out) try {
    State& s = *state_;
    Context& context = *s.context;
    const auto start = std::chrono::steady_clock::now();
    if (!s.reference) {
        s.reference = std::make_unique<ReferenceRenderer>(context, *s.programs);
        if (s.baked) {
            // The reference integrates the very texels the bake started from (before any
            // light extraction: the whole environment).
            std::vector<float> texels = s.original_texels;
            if (texels.empty())
                texels = read_floats(context, s.baked->environment(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
            const BakeMetadata& m = s.baked->metadata();
            or_throw(s.reference->set_environment(texels, m.width, m.height, s.job.ibl_intensity));
        }
    }
    // The surface each pixel sees, one sample per pixel.
    const std::vector<View> surface_views = {View::normal, View::position, View::basecolor, View::metallic,
                                             View::roughness, View::specular_f0, View::emissive,
                                             View::clearcoat, View::clearcoat_normal, View::iridescence,
                                             View::anisotropy, View::sheen, View::transmission};
    FrameSettings surface_frame = s.frame;
    surface_frame.views = surface_views;
    for (View v : s.frame.views)
        if (std::find(surface_views.begin(), surface_views.end(), v) == surface_views.end())
            surface_frame.views.push_back(v);
    const ResourceState sampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    RenderGraph surface_graph;
    auto surface_images = s.renderer->add_passes(surface_graph, *s.gpu_scene, surface_frame, import_ibl(s, surface_graph));
    if (!surface_images) return surface_images.error();
    for (auto& [view, handle] : surface_images->views) surface_graph.export_image(handle, sampled);
    CompiledGraph surface_compiled = surface_graph.compile();
    GraphRun surface_run(context, surface_compiled);
    if (Status done = surface_run.submit_and_wait(); !done) return done.error();
    auto view_image = [&](View v) -> const Image* {
        for (auto& [view, handle] : surface_images->views)
            if (view == v) return surface_run.transient_image(handle);
        return nullptr;
    };
    const ReferenceSurface surface{view_image(View::normal),    view_image(View::position), view_image(View::basecolor),
                                   view_image(View::metallic),  view_image(View::roughness), view_image(View::specular_f0),
                                   view_image(View::emissive), view_image(View::clearcoat),
                                   view_image(View::clearcoat_normal), view_image(View::iridescence),
                                   view_image(View::anisotropy), view_image(View::sheen),
                                   view_image(View::transmission)};
    auto stats = s.reference->accumulate(surface, s.frame, settings, progress);
    if (!stats) return stats.error();
    if (stats_out) *stats_out = *stats;

    // Sums -> radiance, the skybox under it, the display transform.
    RenderGraph graph;
    const ResourceState storage{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
    Image& acc = s.reference->accumulation();
    ImageHandle accumulation = graph.import_image("accumulation", {acc.handle(), acc.desc(), storage, storage});
    ImageHandle normal = graph.import_image("normal", {surface.normal->handle(), surface.normal->desc(), sampled, sampled});
    ImageDesc hdr_desc = acc.desc();
    auto hdr = s.reference->add_resolve_pass(graph, accumulation, normal, graph.create_image("reference", hdr_desc));
    if (!hdr) return hdr.error();
    const std::optional<IblInputs> ibl = import_ibl(s, graph);
    ImageHandle frame = *hdr;
    if (ibl && s.frame.skybox) {
        auto sky = s.renderer->add_skybox_pass(graph, frame, s.frame, *ibl);
        if (!sky) return sky.error();
        frame = *sky;
    }
    if (!s.nearest)
        s.nearest = std::make_unique<Sampler>(
            or_throw(Sampler::create(context, VK_FILTER_NEAREST, false, false, "display nearest")));
    ImageDesc ldr_desc = hdr_desc;
    ldr_desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    auto ldr = add_tonemap_pass(graph, *s.programs, *s.nearest, frame, graph.create_image("display colour", ldr_desc),
                                s.frame.display);
    if (!ldr) return ldr.error();
    graph.export_image(frame, readable);
    graph.export_image(*ldr, readable);
    CompiledGraph compiled = graph.compile();
    GraphRun run(context, compiled);
    if (Status done = run.submit_and_wait(); !done) return done.error();

    RenderedImages out;
    out.width = s.frame.width;
    out.height = s.frame.height;
    out.hdr = read_floats(context, *run.transient_image(frame), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    auto ldr_bytes = or_throw(read_image(context, *run.transient_image(*ldr), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
    out.ldr.resize(ldr_bytes.size());
    std::memcpy(out.ldr.data(), ldr_bytes.data(), ldr_bytes.size());
    for (View v : s.frame.views)
        for (auto& [view, handle] : surface_images->views)
            if (view == v)
                out.views.push_back({v, read_floats(context, *surface_run.transient_image(handle),
                                                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)});
    out.timings = run.timings();
    out.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
} catch (const VulkanError& e) {  // a readback's or an upload's failure (or_throw above)
    return Error{e.what(), e.result()};
}

}  // namespace facet
