// The forward pass: pipelines per material feature set, the draw order, and one graphics
// pass drawing the scene into the caller's targets with the caller's matrices. The
// frame's camera and lights are written into the slot's buffers when the pass is
// recorded, not when the graph is built.
#include <facet/render/forward_renderer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include <facet/gpu/context.h>
#include <facet/gpu/pipeline.h>
#include <facet/graph/graph_run.h>
#include <facet/render/gpu_scene.h>
#include <facet/render/shading_method.h>
#include <facet/render/specular_lobes.h>
#include "render/lobe_disks.h"
#include <facet/gpu/transfer.h>
#include <facet/shader/program_cache.h>
#include "render/forward_data.h"
#include "render/glsl_literal.h"
#include "core/guarded.h"

namespace facet {
using namespace forward;

namespace {

VkSamplerCreateInfo clamped_linear() {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    return info;
}

// The transmission background's: every mip level, linearly blended.
VkSamplerCreateInfo mipmapped_clamped_linear() {
    VkSamplerCreateInfo info = clamped_linear();
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    info.maxLod = VK_LOD_CLAMP_NONE;
    return info;
}

// KHR_texture_transform's matrix as a GLSL mat3x2 constructor (column-major, as stored).
std::string uv_transform_literal(const std::array<float, 6>& m) {
    std::string s = "mat3x2(";
    for (size_t i = 0; i < 6; ++i) s += (i ? ", " : "") + glsl_float_literal(m[i]);
    return s + ")";
}

// The normal map's tangent axes under the transform, as a mat2 constructor: the uv
// derivatives turn by M^-1 (M the transform's 2x2 part), [dp/du' dp/dv'] = [dp/du dp/dv] M^-1,
// and the map's frame is T = dp/du, B = -dp/dv (glTF: +Y up the image, v down it), so
// [T' B'] = [T B] F M^-1 F with F = diag(1, -1): the inverse with its off-diagonal signs
// flipped, each column normalised (a rotation by theta turns the frame by theta). The
// identity for a degenerate M.
std::string tangent_frame_literal(const std::array<float, 6>& m) {
    const double a = m[0], b = m[1], c = m[2], d = m[3], det = a * d - b * c;
    glm::dvec2 u(1.0, 0.0), v(0.0, 1.0);
    if (std::abs(det) > 1e-12) {
        u = glm::normalize(glm::dvec2(d, b) / det);
        v = glm::normalize(glm::dvec2(c, a) / det);
    }
    return "mat2(" + glsl_float_literal(u.x) + ", " + glsl_float_literal(u.y) + ", " + glsl_float_literal(v.x) + ", " +
           glsl_float_literal(v.y) + ")";
}

}  // namespace

Result<std::unique_ptr<ForwardRenderer>> ForwardRenderer::create(Context& context, ProgramCache& programs,
                                                                 uint32_t frames_in_flight) {
    return guarded([&]() -> Result<std::unique_ptr<ForwardRenderer>> {
        return std::unique_ptr<ForwardRenderer>(new ForwardRenderer(context, programs, frames_in_flight));
    });
}

ForwardRenderer::ForwardRenderer(Context& context, ProgramCache& programs, uint32_t frames_in_flight)
    : context_(context),
      programs_(programs),
      nearest_(or_throw(Sampler::create(context, VK_FILTER_NEAREST, false, false, "nearest sampler"))),
      lut_sampler_(or_throw(Sampler::create(context, clamped_linear(), "brdf lut sampler"))),
      background_sampler_(or_throw(Sampler::create(context, mipmapped_clamped_linear(), "transmission background sampler"))) {
    ImageDesc clear;
    clear.format = VK_FORMAT_R8G8B8A8_UNORM;
    no_background_ = or_throw(Image::create(context, clear, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                            "no transmission background"));
    const uint8_t transparent[4] = {0, 0, 0, 0};
    or_throw(upload_image(context, no_background_, 0, 0, std::as_bytes(std::span<const uint8_t>(transparent)),
                          VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
    no_background_view_ = or_throw(no_background_.view());
    if (frames_in_flight == 0) throw UsageError("ForwardRenderer: frames_in_flight must be at least 1");
    ImageDesc table;
    table.width = kSpecularLobeTableWidth;
    table.height = kSpecularLobeTableHeight;
    lobe_table_ = or_throw(Image::create(context, table, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                         "specular lobe table"));
    const std::vector<float> texels = specular_lobe_table_texels();
    or_throw(upload_image(context, lobe_table_, 0, 0, std::as_bytes(std::span<const float>(texels)),
                          VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
    lobe_table_view_ = or_throw(lobe_table_.view());
    slots_.resize(frames_in_flight);
    for (uint32_t f = 0; f < frames_in_flight; ++f) {
        const std::string n = " (frame slot " + std::to_string(f) + ")";
        Slot& s = slots_[f];
        s.frame = or_throw(Buffer::create(context, sizeof(FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                          MemoryUsage::upload, "frame constants" + n));
        // Room for a typical frame's lights up front, so that steady frames never grow them.
        s.lights = or_throw(Buffer::create(context, 16 * sizeof(LightData), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           MemoryUsage::upload, "frame lights" + n));
    }
}

ForwardRenderer::~ForwardRenderer() = default;

ForwardRenderer::Slot& ForwardRenderer::slot(uint32_t frame) {
    if (frame >= slots_.size())
        throw UsageError("ForwardRenderer: frame slot " + std::to_string(frame) + " of " +
                         std::to_string(slots_.size()));
    return slots_[frame];
}

Result<const Pipeline*> ForwardRenderer::material_pipeline(const GpuScene& scene, uint32_t instance, View view,
                                                           const Target& target, bool ibl,
                                                           const FrameSettings& settings, PassDisks& pass_disks) {
    const Instance& in = scene.scene().instances.at(instance);
    const Primitive& primitive = scene.scene().primitives.at(in.primitive);
    const uint32_t material = primitive.material;
    const Material& m = scene.scene().materials.at(material);
    std::vector<ShaderDefine> defines;
    auto define_if = [&](bool on, const char* name) {
        if (on) defines.push_back({name, "1"});
    };
    const TextureRef* refs[] = {&m.base_color_texture,          &m.metallic_roughness_texture, &m.normal_texture,
                                &m.occlusion_texture,           &m.emissive_texture,           &m.clearcoat_texture,
                                &m.clearcoat_roughness_texture, &m.clearcoat_normal_texture,   &m.specular_texture,
                                &m.specular_color_texture,      &m.iridescence_texture,        &m.iridescence_thickness_texture,
                                &m.anisotropy_texture,          &m.sheen_color_texture,        &m.sheen_roughness_texture,
                                &m.transmission_texture,        &m.thickness_texture};
    const char* maps[] = {"HAS_BASE_COLOR_MAP",     "HAS_METALLIC_ROUGHNESS_MAP", "HAS_NORMAL_MAP",
                          "HAS_OCCLUSION_MAP",      "HAS_EMISSIVE_MAP",           "HAS_CLEARCOAT_MAP",
                          "HAS_CLEARCOAT_ROUGHNESS_MAP", "HAS_CLEARCOAT_NORMAL_MAP", "HAS_SPECULAR_MAP",
                          "HAS_SPECULAR_COLOR_MAP", "HAS_IRIDESCENCE_MAP", "HAS_IRIDESCENCE_THICKNESS_MAP",
                          "HAS_ANISOTROPY_MAP",     "HAS_SHEEN_COLOR_MAP",        "HAS_SHEEN_ROUGHNESS_MAP",
                          "HAS_TRANSMISSION_MAP",   "HAS_THICKNESS_MAP"};
    const char* uvs[] = {"BASE_COLOR_UV", "METALLIC_ROUGHNESS_UV", "NORMAL_UV",           "OCCLUSION_UV",
                         "EMISSIVE_UV",   "CLEARCOAT_UV",          "CLEARCOAT_ROUGHNESS_UV", "CLEARCOAT_NORMAL_UV",
                         "SPECULAR_UV",   "SPECULAR_COLOR_UV", "IRIDESCENCE_UV", "IRIDESCENCE_THICKNESS_UV",
                         "ANISOTROPY_UV", "SHEEN_COLOR_UV", "SHEEN_ROUGHNESS_UV", "TRANSMISSION_UV", "THICKNESS_UV"};
    static_assert(std::size(refs) == size_t(TextureSlot::count) && std::size(maps) == std::size(refs) &&
                  std::size(uvs) == std::size(refs));
    const bool coated = m.clearcoat > 0.0f, film = m.iridescence > 0.0f, stretched = m.anisotropy > 0.0f,
               sheen = m.has_sheen(), through = m.has_transmission();
    for (size_t t = 0; t < std::size(refs); ++t) {
        const TextureSlot slot = TextureSlot(t);
        if (!scene.has_texture(material, slot)) continue;
        const bool coat_slot = slot == TextureSlot::clearcoat || slot == TextureSlot::clearcoat_roughness ||
                               slot == TextureSlot::clearcoat_normal;
        if (coat_slot && !coated) continue;  // no layer: its textures are not read
        const bool film_slot = slot == TextureSlot::iridescence || slot == TextureSlot::iridescence_thickness;
        if (film_slot && !film) continue;
        if (slot == TextureSlot::anisotropy && !stretched) continue;
        if ((slot == TextureSlot::sheen_color || slot == TextureSlot::sheen_roughness) && !sheen) continue;
        if ((slot == TextureSlot::transmission || slot == TextureSlot::thickness) && !through) continue;
        define_if(true, maps[t]);
        // The texture's coordinates where they are not TEXCOORD_0 as is: the uv set, then
        // KHR_texture_transform as a constant of the material's pipeline (no buffer read).
        const TextureRef& ref = *refs[t];
        const char* set = ref.uv_set == 1 ? "in_uv1" : "in_uv";
        if (ref.transformed()) {
            std::string uv = "(";
            uv.append(uv_transform_literal(ref.uv_transform)).append(" * vec3(").append(set).append(", 1.0))");
            defines.push_back({uvs[t], uv});
            if (slot == TextureSlot::normal)
                defines.push_back({"NORMAL_TANGENT_FRAME", tangent_frame_literal(ref.uv_transform)});
            if (slot == TextureSlot::clearcoat_normal)
                defines.push_back({"CLEARCOAT_NORMAL_TANGENT_FRAME", tangent_frame_literal(ref.uv_transform)});
        } else if (ref.uv_set == 1) {
            defines.push_back({uvs[t], set});
        }
    }
    define_if(scene.occlusion_in_metallic_roughness(material), "OCCLUSION_IN_METALLIC_ROUGHNESS");
    define_if(m.alpha_mode == AlphaMode::opaque, "ALPHA_OPAQUE");
    define_if(m.alpha_mode == AlphaMode::mask, "ALPHA_MASK");
    const bool blend = m.alpha_mode == AlphaMode::blend && view == View::final_color;
    define_if(blend, "ALPHA_BLEND");
    define_if(m.double_sided, "DOUBLE_SIDED");
    // A mirroring world matrix (negative determinant) turns the winding around: its
    // front faces are clockwise on screen, so it culls the other side.
    const bool mirrored = glm::determinant(glm::mat3(in.world)) < 0.0f;
    define_if(mirrored && m.double_sided, "MIRRORED");
    define_if(m.unlit || primitive.topology != Topology::triangles, "UNLIT");
    define_if(primitive.topology == Topology::points, "POINTS");
    define_if(coated, "CLEARCOAT");
    define_if(film, "FACET_IRIDESCENCE");
    define_if(stretched, "FACET_ANISOTROPY");
    define_if(sheen, "FACET_SHEEN");
    define_if(through, "FACET_TRANSMISSION");
    // A view of the surface itself is written before any light is looked at
    // (FACET_SURFACE_VIEW): none of the environment's defines (its lookups, the disks), so that
    // one pipeline serves it under any lighting, a fraction of the lit one's to build (lavapipe:
    // ~7 ms against ~90).
    const bool surface_view = view_of_surface(view);
    define_if(surface_view, "FACET_SURFACE_VIEW");
    const bool lit_ibl = ibl && !surface_view;
    define_if(lit_ibl, "USE_IBL");
    define_if(settings.brdf == BrdfModel::thesis, "BRDF_THESIS");
    define_if(lit_ibl && settings.multiscatter, "MULTISCATTER");
    // A mirror (roughness 0) reads level 0 of the specular cube, which holds the extracted
    // lights (the split level is at least 1 where there are lights): the disks' specular
    // counts for none of its lookup (facet_disk_specular_weight), and its fitted lookups all
    // read R at level 0. Neither is compiled in, unless a layer or lobe of its own (a
    // clearcoat, a transmission, a sheen's or a film's disk diffuse) reads the disks.
    const bool disks_at_own_roughness = !coated && !film && !sheen && !through;
    const bool mirror = m.roughness == 0.0f && settings.environment_light_level >= 1 && disks_at_own_roughness;
    // A material whose roughness is a constant of its pipeline (no roughness texture, no layer
    // or lobe of another roughness reading the disks) gets the disks its lobe tells apart
    // (render/lobe_disks.h): a rough lobe integrates a softbox's pieces as one cap, and the
    // caps it is three times wider than as points (FACET_DISK_POINTS).
    const bool constant_roughness = !scene.has_texture(material, TextureSlot::metallic_roughness);
    const std::vector<ShaderDefine>* disks = &pass_disks.all;
    if (lit_ibl && !mirror && !settings.environment_lights.empty() && constant_roughness && disks_at_own_roughness) {
        auto found = pass_disks.by_roughness.find(m.roughness);
        if (found == pass_disks.by_roughness.end()) {
            const std::vector<DiskLight> merged = disks_for_lobe(settings.environment_lights, m.roughness);
            std::vector<ShaderDefine> merged_defines = pass_disks.all;
            if (merged.size() < settings.environment_lights.size()) {
                auto made = disk_light_defines(merged, "the forward pass");
                if (!made) return made.error();
                merged_defines = std::move(*made);
            }
            // The caps this lobe is much wider than, as points (facet_disk_point_lobe).
            uint32_t points = 0;
            for (size_t i = 0; i < merged.size(); ++i)
                if (disk_is_point_for_lobe(merged[i], m.roughness)) points |= 1u << i;
            if (points) merged_defines.push_back({"FACET_DISK_POINTS", std::to_string(points)});
            found = pass_disks.by_roughness.emplace(m.roughness, std::move(merged_defines)).first;
        }
        disks = &found->second;
    }
    // The fitted lookups where the material reaches a group that needs them; two of them
    // instead of three where every such group allows it (FrameSettings::two_lookup_groups).
    bool bend = false, two = true;
    const std::array<bool, 8> reached = material_shading_groups(m);
    for (size_t g = 0; g < reached.size(); ++g) {
        if (!reached[g] || !settings.dominant_groups[g]) continue;
        bend = true;
        two = two && settings.two_lookup_groups[g];
    }
    const bool fitted = lit_ibl && settings.dominant_direction && bend && !mirror;
    define_if(fitted, "DOMINANT_DIRECTION");
    define_if(fitted && two, "FACET_TWO_LOOKUPS");
    define_if(settings.flat_floor, "FLAT_FLOOR");
    if (lit_ibl && !mirror) defines.insert(defines.end(), disks->begin(), disks->end());  // none without IBL
    defines.push_back({"VIEW", std::to_string(int(view))});

    Pipeline::GraphicsDesc desc;
    desc.color_formats = {target.color};
    desc.depth_format = target.depth;
    desc.samples = target.samples;
    desc.cull = m.double_sided || primitive.topology != Topology::triangles ? VK_CULL_MODE_NONE
                : mirrored                                                  ? VK_CULL_MODE_FRONT_BIT
                                                                            : VK_CULL_MODE_BACK_BIT;
    desc.topology = primitive.topology == Topology::points  ? VK_PRIMITIVE_TOPOLOGY_POINT_LIST
                    : primitive.topology == Topology::lines ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST
                                                            : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    desc.vertex_bindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    desc.vertex_attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                              {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                              {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
                              {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
                              {4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color)},
                              {5, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv1)}};
    desc.depth_test = true;
    desc.depth_write = !blend;
    desc.alpha_blend = blend;
    auto pipeline = programs_.graphics("render/forward.vert", "render/forward.frag", desc, defines);
    if (pipeline) {
        std::string key = std::to_string(target.samples) + "|cull" + std::to_string(desc.cull) + "|t" +
                          std::to_string(desc.topology);
        for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
        variants_.insert(key);
    }
    return pipeline;
}

namespace {
// What the transmission background draws: opaque (or masked) instances without a transmission.
bool in_transmission_background(const Scene& scene, uint32_t instance) {
    const Material& m = scene.materials.at(scene.primitives.at(scene.instances.at(instance).primitive).material);
    return m.alpha_mode != AlphaMode::blend && !m.has_transmission();
}
}  // namespace

Result<std::vector<const Pipeline*>> ForwardRenderer::pipelines(const GpuScene& gpu, View view, const Target& target,
                                                                bool ibl, const FrameSettings& s,
                                                                bool opaque_background) {
    const Scene& scene = gpu.scene();
    // The disks as constants of every material's pipeline, written once for the pass.
    PassDisks disks;
    if (ibl) {
        auto defines = disk_light_defines(s.environment_lights, "the forward pass");
        if (!defines) return defines.error();
        disks.all = std::move(*defines);
    }
    std::vector<const Pipeline*> out(scene.instances.size(), nullptr);
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        if (opaque_background && !in_transmission_background(scene, i)) continue;
        auto p = material_pipeline(gpu, i, view, target, ibl, s, disks);
        if (!p) return p.error();
        out[i] = *p;
    }
    return out;
}

ForwardRenderer::DrawList ForwardRenderer::draw_list(const GpuScene& gpu, glm::vec3 camera_position) const {
    const Scene& scene = gpu.scene();
    DrawList list;
    std::vector<std::pair<float, uint32_t>> blended;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const Primitive& p = scene.primitives.at(instance.primitive);
        if (scene.materials.at(p.material).alpha_mode != AlphaMode::blend) {
            list.opaque.push_back(i);
            continue;
        }
        const glm::vec3 centre = glm::vec3(instance.world * glm::vec4(0.5f * (p.bounds_min + p.bounds_max), 1.0f));
        blended.push_back({glm::length(centre - camera_position), i});
    }
    // Back to front, ties in declaration order, so that images are reproducible.
    std::stable_sort(blended.begin(), blended.end(), [](auto& a, auto& b) { return a.first > b.first; });
    for (auto& b : blended) list.blend.push_back(b.second);
    return list;
}

ForwardOutputs ForwardRenderer::add_draw_pass(RenderGraph& graph, const std::string& name, const GpuScene& gpu,
                                              const FrameSettings& s, const CameraMatrices& camera,
                                              const ForwardTargets& targets, const std::optional<IblInputs>& ibl,
                                              std::vector<const Pipeline*> pipelines, uint32_t frame,
                                              ImageHandle background) {
    // What the slot's buffers will hold, computed now and written when the pass is recorded.
    FrameData data{};
    data.view_projection = camera.projection * camera.view;
    data.camera_position = glm::vec4(camera.position(), 1.0f);
    data.ibl = glm::vec4(ibl ? ibl->intensity : 0.0f, ibl ? float(ibl->specular_levels - 1) : 0.0f,
                         float(s.environment_light_level), 0.0f);
    const uint32_t disks = ibl ? uint32_t(s.environment_lights.size()) : 0u;
    data.counts = glm::uvec4(uint32_t(s.lights.size()), disks, 0, 0);
    std::vector<LightData> lights;
    lights.reserve(s.lights.size());
    for (const Light& l : s.lights) lights.push_back(light_data(l));

    const DrawList list = draw_list(gpu, camera.position());
    // Instances without a pipeline are not drawn (the transmission background's).
    std::vector<uint32_t> order;
    for (const std::vector<uint32_t>* part : {&list.opaque, &list.blend})
        for (uint32_t i : *part)
            if (pipelines[i]) order.push_back(i);

    // The execute step is built before the setup step runs: it names the resources by
    // the handles passed in (a view does not depend on the version).
    ForwardOutputs out;
    const bool resolve = targets.resolve.valid();
    graph.add_graphics_pass(name, [&](PassBuilder& b) {
        if (ibl) {
            if (ibl->irradiance.valid()) b.sample(ibl->irradiance);
            b.sample(ibl->specular);
            b.sample(ibl->lut);
        }
        if (background.valid()) b.sample(background);
        out.color = b.color_attachment(targets.color);
        out.depth = b.depth_attachment(targets.depth);
        if (resolve) out.resolve = b.color_attachment(targets.resolve);
    }, [this, &gpu, frame, data, lights = std::move(lights), order = std::move(order), pipelines = std::move(pipelines),
        ibl, background, color = targets.color, depth = targets.depth, resolve_target = targets.resolve, clear_color = targets.clear_color,
        clear_depth = targets.clear_depth, store_depth = targets.store_depth](PassContext& pc) {
        Slot& slot = slots_[frame];
        std::memcpy(slot.frame.mapped(), &data, sizeof data);
        or_throw(slot.frame.flush());
        write_lights(context_, slot.lights, lights, "frame lights");
        const VkDeviceSize lights_bytes = std::max<size_t>(1, lights.size()) * sizeof(LightData);

        const uint32_t w = pc.desc(color).width, h = pc.desc(color).height;
        VkCommandBuffer cmd = pc.cmd();
        VkRenderingAttachmentInfo c{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        c.imageView = pc.view(color, ImageRange::mip(0));
        c.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        c.loadOp = clear_color ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        c.storeOp = resolve_target.valid() ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
        c.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        if (resolve_target.valid()) {
            c.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
            c.resolveImageView = pc.view(resolve_target, ImageRange::mip(0));
            c.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        }
        VkRenderingAttachmentInfo d{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        d.imageView = pc.view(depth, ImageRange::mip(0));
        d.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        d.loadOp = clear_depth ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        d.storeOp = store_depth ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
        d.clearValue.depthStencil = {0.0f, 0};  // reversed Z: 0 is infinitely far
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {w, h}};
        info.layerCount = 1;
        info.colorAttachmentCount = 1;
        info.pColorAttachments = &c;
        info.pDepthAttachment = &d;
        vkCmdBeginRendering(cmd, &info);
        VkViewport viewport{0, 0, float(w), float(h), 0, 1};
        VkRect2D scissor{{0, 0}, {w, h}};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);

        const Scene& scene = gpu.scene();
        const VkDeviceSize offset = 0;
        const VkBuffer vertices = gpu.vertices();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
        vkCmdBindIndexBuffer(cmd, gpu.indices(), 0, VK_INDEX_TYPE_UINT32);
        // Bindings 4..6 are the IBL or black defaults.
        VkImageView irradiance = gpu.black_cube(), specular = gpu.black_cube(), lut = gpu.black_2d();
        VkSampler cube_sampler = gpu.default_sampler();
        if (ibl) {
            if (ibl->irradiance.valid()) irradiance = pc.view(ibl->irradiance);
            specular = pc.view(ibl->specular);
            lut = pc.view(ibl->lut);
            cube_sampler = ibl->cube_sampler;
        }
        const DescriptorWrite behind =
            background.valid() ? DescriptorWrite::sampled_image(pc.view(background), background_sampler_.handle())
                               : DescriptorWrite::sampled_image(no_background_view_, lut_sampler_.handle());
        for (uint32_t i : order) {
            const Primitive& p = scene.primitives[scene.instances[i].primitive];
            const Pipeline* pipeline = pipelines[i];
            pipeline->bind(cmd);
            auto tex = [&](TextureSlot texture) {
                GpuTexture t = gpu.texture(p.material, texture);
                return DescriptorWrite::sampled_image(t.view, t.sampler);
            };
            const DescriptorWrite writes[] = {
                DescriptorWrite::uniform_buffer(slot.frame.handle()),
                DescriptorWrite::storage_buffer(slot.lights.handle(), 0, lights_bytes),
                DescriptorWrite::uniform_buffer(gpu.instances(), i * gpu.instance_stride(), sizeof(GpuInstance)),
                DescriptorWrite::uniform_buffer(gpu.materials(), p.material * gpu.material_stride(),
                                                sizeof(GpuMaterial)),
                DescriptorWrite::sampled_image(irradiance, cube_sampler),
                DescriptorWrite::sampled_image(specular, cube_sampler),
                // clamped: NdotV near 1 must not wrap to NdotV = 0
                DescriptorWrite::sampled_image(lut, lut_sampler_.handle()),
                tex(TextureSlot::base_color),
                tex(TextureSlot::metallic_roughness),
                tex(TextureSlot::normal),
                tex(TextureSlot::occlusion),
                tex(TextureSlot::emissive),
                DescriptorWrite::sampled_image(lobe_table_view_, lut_sampler_.handle()),
                tex(TextureSlot::clearcoat),
                tex(TextureSlot::clearcoat_roughness),
                tex(TextureSlot::clearcoat_normal),
                tex(TextureSlot::specular),
                tex(TextureSlot::specular_color),
                tex(TextureSlot::iridescence),
                tex(TextureSlot::iridescence_thickness),
                tex(TextureSlot::anisotropy),
                tex(TextureSlot::sheen_color),
                tex(TextureSlot::sheen_roughness),
                tex(TextureSlot::transmission),
                tex(TextureSlot::thickness),
                behind};
            pipeline->push_descriptors(cmd, writes);
            vkCmdDrawIndexed(cmd, p.index_count, 1, p.first_index, int32_t(p.vertex_offset), 0);
        }
        vkCmdEndRendering(cmd);
    });
    return out;
}

Result<ForwardOutputs> ForwardRenderer::add_forward_pass(RenderGraph& graph, const GpuScene& gpu,
                                                         const FrameSettings& s, const CameraMatrices& camera,
                                                         const ForwardTargets& targets,
                                                         const std::optional<IblInputs>& ibl, uint32_t frame) {
    slot(frame);  // a slot out of range is misuse, caught now rather than when recorded
    if (!targets.color.valid() || !targets.depth.valid())
        return Error{"the forward pass needs a colour and a depth target"};
    const ImageDesc& color = graph.resource(targets.color).image_desc;
    const ImageDesc& depth = graph.resource(targets.depth).image_desc;
    if (aspect_of(color.format) != VK_IMAGE_ASPECT_COLOR_BIT)
        return Error{"the forward pass's colour target '" + graph.resource(targets.color).name + "' is not a colour format"};
    if (!(aspect_of(depth.format) & VK_IMAGE_ASPECT_DEPTH_BIT))
        return Error{"the forward pass's depth target '" + graph.resource(targets.depth).name + "' has no depth"};
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(context_.physical_device(), color.format, &properties);
    if (!(properties.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT))
        return Error{"the device cannot render to the colour target '" + graph.resource(targets.color).name +
                     "' (format " + std::to_string(int(color.format)) + ")"};
    if (depth.width != color.width || depth.height != color.height || depth.samples != color.samples)
        return Error{"the forward pass's depth target differs from the colour target in size or samples"};
    if (targets.resolve.valid()) {
        const ImageDesc& r = graph.resource(targets.resolve).image_desc;
        if (r.format != color.format || r.width != color.width || r.height != color.height ||
            r.samples != VK_SAMPLE_COUNT_1_BIT || color.samples == VK_SAMPLE_COUNT_1_BIT)
            return Error{"the resolve target must be single-sample, of the MSAA colour target's format and size"};
    }
    const Target target{color.format, depth.format, color.samples};
    auto final_pipelines = pipelines(gpu, View::final_color, target, ibl.has_value(), s);
    if (!final_pipelines) return final_pipelines.error();
    auto background = add_transmission_background(graph, gpu, s, camera, color.width, color.height, ibl, frame);
    if (!background) return background.error();
    return add_draw_pass(graph, "forward", gpu, s, camera, targets, ibl, std::move(*final_pipelines), frame,
                         *background);
}

Result<ImageHandle> ForwardRenderer::add_transmission_background(RenderGraph& graph, const GpuScene& gpu,
                                                                 const FrameSettings& s, const CameraMatrices& camera,
                                                                 uint32_t width, uint32_t height,
                                                                 const std::optional<IblInputs>& ibl, uint32_t frame) {
    const Scene& scene = gpu.scene();
    const bool any = std::any_of(scene.instances.begin(), scene.instances.end(), [&](const Instance& in) {
        return scene.materials.at(scene.primitives.at(in.primitive).material).has_transmission();
    });
    if (!any) return ImageHandle{};
    ImageDesc desc;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.width = width;
    desc.height = height;
    desc.mip_levels = uint32_t(std::floor(std::log2(double(std::max(width, height))))) + 1;
    ImageDesc depth_desc;
    depth_desc.format = VK_FORMAT_D32_SFLOAT;
    depth_desc.width = width;
    depth_desc.height = height;
    const Target target{desc.format, depth_desc.format, VK_SAMPLE_COUNT_1_BIT};
    auto opaque = pipelines(gpu, View::final_color, target, ibl.has_value(), s, true);
    if (!opaque) return opaque.error();
    auto downsample = programs_.compute("render/transmission_mips.comp");
    if (!downsample) return downsample.error();
    ForwardTargets targets;
    targets.color = graph.create_image("transmission background", desc);
    targets.depth = graph.create_image("transmission background depth", depth_desc);
    targets.store_depth = false;
    ImageHandle current = add_draw_pass(graph, "transmission background", gpu, s, camera, targets, ibl,
                                        std::move(*opaque), frame).color;
    const ImageHandle image = targets.color;
    for (uint32_t m = 1; m < desc.mip_levels; ++m) {
        graph.add_compute_pass("transmission background mip " + std::to_string(m), [&](PassBuilder& b) {
            b.read_storage(current, ImageRange::mip(m - 1));
            current = b.write_storage(current, ImageRange::mip(m));
        }, [p = *downsample, image, m, w = desc.mip_width(m), h = desc.mip_height(m)](PassContext& pc) {
            p->bind(pc.cmd());
            const DescriptorWrite writes[] = {DescriptorWrite::storage_image(pc.view(image, ImageRange::mip(m - 1))),
                                              DescriptorWrite::storage_image(pc.view(image, ImageRange::mip(m)))};
            p->push_descriptors(pc.cmd(), writes);
            vkCmdDispatch(pc.cmd(), (w + 7) / 8, (h + 7) / 8, 1);
        });
    }
    return current;
}

Result<ImageHandle> ForwardRenderer::add_view_pass(RenderGraph& graph, const GpuScene& gpu, View view,
                                                   const FrameSettings& s, const CameraMatrices& camera,
                                                   const std::optional<IblInputs>& ibl, uint32_t frame) {
    slot(frame);
    if (s.width == 0 || s.height == 0) return Error{"the image size must be at least 1x1"};
    ImageDesc desc;
    desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    desc.width = s.width;
    desc.height = s.height;
    ImageDesc depth_desc = desc;
    depth_desc.format = VK_FORMAT_D32_SFLOAT;
    const Target target{desc.format, depth_desc.format, VK_SAMPLE_COUNT_1_BIT};
    auto view_pipelines = pipelines(gpu, view, target, ibl.has_value(), s);
    if (!view_pipelines) return view_pipelines.error();
    ForwardTargets targets;
    targets.color = graph.create_image(std::string("view ") + view_name(view), desc);
    targets.depth = graph.create_image("view depth", depth_desc);
    targets.store_depth = false;
    return add_draw_pass(graph, std::string("view ") + view_name(view), gpu, s, camera, targets, ibl,
                         std::move(*view_pipelines), frame)
        .color;
}

}  // namespace facet
