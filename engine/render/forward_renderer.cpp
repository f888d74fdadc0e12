#include <facet/render/forward_renderer.h>

#include <algorithm>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include <facet/gpu/context.h>
#include <facet/gpu/pipeline.h>
#include <facet/graph/graph_run.h>
#include <facet/render/gpu_scene.h>
#include <facet/shader/program_cache.h>

namespace facet {
namespace {

constexpr VkFormat hdr_format = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat depth_format = VK_FORMAT_D32_SFLOAT;

// std140 layout of Frame in shaders/render/forward_interface.glsl.
struct FrameData {
    glm::mat4 view_projection;
    glm::vec4 camera_position;
    glm::vec4 ibl;
    glm::uvec4 counts;
};

struct LightData {
    glm::vec4 position_range;
    glm::vec4 direction_type;
    glm::vec4 color_intensity;
    glm::vec4 cone;
};

struct DrawConstants {
    uint32_t instance;
    uint32_t material;
};

struct SkyConstants {
    glm::mat4 inverse_view_projection;
    float lod;
    float intensity;
    uint32_t disks;
    float pad;
};

LightData disk_data(const DiskLight& d) {
    LightData data{};
    data.direction_type = glm::vec4(-d.direction, 3.0f);  // the direction the light travels
    data.color_intensity = glm::vec4(d.radiance, 1.0f);
    data.cone = glm::vec4(std::cos(d.angular_radius), d.angular_radius, 0.0f, 0.0f);
    return data;
}

LightData light_data(const Light& l) {
    LightData d{};
    d.position_range = glm::vec4(l.position, l.range);
    d.direction_type = glm::vec4(glm::normalize(l.direction), float(int(l.type)));
    d.color_intensity = glm::vec4(l.color, l.intensity);
    // KHR_lights_punctual's smooth cone: scale and offset of the cosine.
    const float cos_outer = std::cos(l.outer_cone), cos_inner = std::cos(l.inner_cone);
    const float scale = 1.0f / std::max(cos_inner - cos_outer, 1e-4f);
    d.cone = glm::vec4(scale, -cos_outer * scale, 0.0f, 0.0f);
    return d;
}

const std::vector<VkDescriptorType>& forward_bindings() {
    static const std::vector<VkDescriptorType> b = {
        VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
    return b;
}

VkSamplerCreateInfo clamped_linear() {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    return info;
}

void set_viewport(VkCommandBuffer cmd, uint32_t w, uint32_t h) {
    VkViewport viewport{0, 0, float(w), float(h), 0, 1};
    VkRect2D scissor{{0, 0}, {w, h}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace

ForwardRenderer::ForwardRenderer(Context& context, ProgramCache& programs)
    : context_(context),
      programs_(programs),
      frame_(context, sizeof(FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::upload, "frame constants"),
      nearest_(context, VK_FILTER_NEAREST, false, false, "nearest sampler"),
      lut_sampler_(context, clamped_linear(), "brdf lut sampler") {}

ForwardRenderer::~ForwardRenderer() = default;

Result<const Pipeline*> ForwardRenderer::material_pipeline(const GpuScene& scene, uint32_t material, View view,
                                                           VkSampleCountFlagBits samples, bool ibl,
                                                           const FrameSettings& settings) {
    const Material& m = scene.scene().materials.at(material);
    std::vector<ShaderDefine> defines;
    auto define_if = [&](bool on, const char* name) {
        if (on) defines.push_back({name, "1"});
    };
    define_if(scene.has_texture(material, TextureSlot::base_color), "HAS_BASE_COLOR_MAP");
    define_if(scene.has_texture(material, TextureSlot::metallic_roughness), "HAS_METALLIC_ROUGHNESS_MAP");
    define_if(scene.has_texture(material, TextureSlot::normal), "HAS_NORMAL_MAP");
    define_if(scene.has_texture(material, TextureSlot::occlusion), "HAS_OCCLUSION_MAP");
    define_if(scene.has_texture(material, TextureSlot::emissive), "HAS_EMISSIVE_MAP");
    define_if(m.alpha_mode == AlphaMode::mask, "ALPHA_MASK");
    const bool blend = m.alpha_mode == AlphaMode::blend && view == View::final_color;
    define_if(blend, "ALPHA_BLEND");
    define_if(m.double_sided, "DOUBLE_SIDED");
    define_if(ibl, "USE_IBL");
    define_if(settings.height_correlated, "HEIGHT_CORRELATED");
    define_if(ibl && settings.multiscatter, "MULTISCATTER");
    define_if(ibl && settings.dominant_direction, "DOMINANT_DIRECTION");
    defines.push_back({"VIEW", std::to_string(int(view))});

    Pipeline::GraphicsDesc desc;
    desc.bindings = forward_bindings();
    desc.push_constant_bytes = sizeof(DrawConstants);
    desc.color_formats = {hdr_format};
    desc.depth_format = depth_format;
    desc.samples = samples;
    desc.cull = m.double_sided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
    desc.vertex_bindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    desc.vertex_attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                              {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                              {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
                              {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)}};
    desc.depth_test = true;
    desc.depth_write = !blend;
    desc.alpha_blend = blend;
    auto pipeline = programs_.graphics("render/forward.vert", "render/forward.frag", desc, defines);
    if (pipeline) {
        std::string key = std::to_string(samples) + (m.double_sided ? "|two-sided" : "");
        for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
        variants_.insert(key);
    }
    return pipeline;
}

Result<ImageHandle> ForwardRenderer::add_skybox_pass(RenderGraph& graph, ImageHandle hdr, const FrameSettings& s,
                                                     const IblInputs& ibl) {
    const VkDescriptorType bindings[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    auto sky = programs_.compute("render/skybox.comp", bindings, sizeof(SkyConstants));
    if (!sky) return sky.error();
    std::vector<LightData> disks;
    for (const DiskLight& d : s.environment_lights) disks.push_back(disk_data(d));
    sky_disks_ = Buffer(context_, std::max<size_t>(1, disks.size()) * sizeof(LightData),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::upload, "skybox disks");
    if (!disks.empty()) std::memcpy(sky_disks_.mapped(), disks.data(), disks.size() * sizeof(LightData));
    sky_disks_.flush();
    glm::mat4 rotation = s.camera.view();
    rotation[3] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const float aspect = float(s.width) / float(s.height);
    const SkyConstants constants{glm::inverse(s.camera.projection(aspect) * rotation), 0.0f, ibl.intensity,
                                 uint32_t(disks.size()), 0.0f};
    ImageHandle written;
    graph.add_compute_pass("skybox", [&](PassBuilder& b) {
        b.sample(ibl.cube);
        written = b.read_write_storage(hdr);
    }, [p = *sky, constants, hdr, cube = ibl.cube, sampler = ibl.cube_sampler, w = s.width, h = s.height,
        disk_buffer = sky_disks_.handle()](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::sampled_image(pc.view(cube), sampler),
                                          DescriptorWrite::storage_image(pc.view(hdr)),
                                          DescriptorWrite::storage_buffer(disk_buffer)};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), constants);
        vkCmdDispatch(pc.cmd(), group_count(w, 8), group_count(h, 8), 1);
    });
    return written;
}

ForwardRenderer::DrawList ForwardRenderer::draw_list(const GpuScene& gpu, const CameraView& camera) const {
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
        blended.push_back({glm::length(centre - camera.position), i});
    }
    // Back to front, ties in declaration order, so that images are reproducible.
    std::stable_sort(blended.begin(), blended.end(), [](auto& a, auto& b) { return a.first > b.first; });
    for (auto& b : blended) list.blend.push_back(b.second);
    return list;
}

Result<FrameImages> ForwardRenderer::add_passes(RenderGraph& graph, const GpuScene& gpu, const FrameSettings& s,
                                                const std::optional<IblInputs>& ibl) {
    if (s.width == 0 || s.height == 0) return Error{"the image size must be at least 1x1"};
    const VkSampleCountFlagBits samples = VkSampleCountFlagBits(s.samples);
    if (s.samples != 1 && s.samples != 2 && s.samples != 4 && s.samples != 8)
        return Error{"MSAA samples must be 1, 2, 4 or 8, not " + std::to_string(s.samples)};
    const Scene& scene = gpu.scene();
    const float aspect = float(s.width) / float(s.height);
    const glm::mat4 view = s.camera.view();
    const glm::mat4 projection = s.camera.projection(aspect);

    FrameData frame{};
    frame.view_projection = projection * view;
    frame.camera_position = glm::vec4(s.camera.position, 1.0f);
    frame.ibl = glm::vec4(ibl ? ibl->intensity : 0.0f, ibl ? float(ibl->specular_levels - 1) : 0.0f,
                          float(s.environment_light_level), 0.0f);
    const uint32_t disks = ibl ? uint32_t(s.environment_lights.size()) : 0u;
    frame.counts = glm::uvec4(uint32_t(s.lights.size()), disks, 0, 0);
    std::memcpy(frame_.mapped(), &frame, sizeof frame);
    frame_.flush();
    std::vector<LightData> lights;
    for (const Light& l : s.lights) lights.push_back(light_data(l));
    for (uint32_t i = 0; i < disks; ++i) lights.push_back(disk_data(s.environment_lights[i]));
    lights_ = Buffer(context_, std::max<size_t>(1, lights.size()) * sizeof(LightData),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::upload, "frame lights");
    if (!lights.empty()) std::memcpy(lights_.mapped(), lights.data(), lights.size() * sizeof(LightData));
    lights_.flush();

    // Pipelines first, so that a compile error leaves the graph untouched.
    const DrawList list = draw_list(gpu, s.camera);
    std::vector<const Pipeline*> final_pipelines(scene.instances.size());
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const uint32_t material = scene.primitives.at(scene.instances[i].primitive).material;
        auto p = material_pipeline(gpu, material, View::final_color, samples, ibl.has_value(), s);
        if (!p) return p.error();
        final_pipelines[i] = *p;
    }
    std::vector<std::vector<const Pipeline*>> view_pipelines;
    for (View v : s.views) {
        std::vector<const Pipeline*> pipelines(scene.instances.size());
        for (uint32_t i = 0; i < scene.instances.size(); ++i) {
            const uint32_t material = scene.primitives.at(scene.instances[i].primitive).material;
            auto p = material_pipeline(gpu, material, v, VK_SAMPLE_COUNT_1_BIT, ibl.has_value(), s);
            if (!p) return p.error();
            pipelines[i] = *p;
        }
        view_pipelines.push_back(std::move(pipelines));
    }
    const bool draw_sky = s.skybox && ibl.has_value();

    FrameImages out;
    ImageDesc hdr_desc;
    hdr_desc.format = hdr_format;
    hdr_desc.width = s.width;
    hdr_desc.height = s.height;
    out.hdr = graph.create_image("hdr colour", hdr_desc);
    ImageDesc msaa_desc = hdr_desc;
    msaa_desc.samples = samples;
    ImageHandle color = samples == VK_SAMPLE_COUNT_1_BIT ? out.hdr : graph.create_image("msaa colour", msaa_desc);
    ImageDesc depth_desc = msaa_desc;
    depth_desc.format = depth_format;
    ImageHandle depth = graph.create_image("depth", depth_desc);

    // Descriptors shared by every draw of a pass; bindings 4..6 are IBL or black defaults.
    struct Shared {
        VkBuffer frame, lights, instances, materials;
        VkDeviceSize lights_size;
        VkSampler lut_sampler;  // clamped: NdotV near 1 must not wrap to NdotV = 0
    };
    const Shared shared{frame_.handle(), lights_.handle(), gpu.instances(), gpu.materials(), lights_.size(),
                        lut_sampler_.handle()};
    auto record_draws = [&gpu, shared, ibl](PassContext& pc, const std::vector<uint32_t>& order,
                                            const std::vector<const Pipeline*>& pipelines) {
        const Scene& scene = gpu.scene();
        VkCommandBuffer cmd = pc.cmd();
        const VkDeviceSize offset = 0;
        const VkBuffer vertices = gpu.vertices();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
        vkCmdBindIndexBuffer(cmd, gpu.indices(), 0, VK_INDEX_TYPE_UINT32);
        VkImageView irradiance = gpu.black_cube(), specular = gpu.black_cube(), lut = gpu.black_2d();
        VkSampler cube_sampler = gpu.default_sampler();
        if (ibl) {
            if (ibl->irradiance.valid()) irradiance = pc.view(ibl->irradiance);
            specular = pc.view(ibl->specular);
            lut = pc.view(ibl->lut);
            cube_sampler = ibl->cube_sampler;
        }
        for (uint32_t i : order) {
            const Instance& instance = scene.instances[i];
            const Primitive& p = scene.primitives[instance.primitive];
            const Pipeline* pipeline = pipelines[i];
            pipeline->bind(cmd);
            auto tex = [&](TextureSlot slot) {
                GpuTexture t = gpu.texture(p.material, slot);
                return DescriptorWrite::sampled_image(t.view, t.sampler);
            };
            const DescriptorWrite writes[] = {
                DescriptorWrite::uniform_buffer(shared.frame),
                DescriptorWrite::storage_buffer(shared.lights, 0, shared.lights_size),
                DescriptorWrite::storage_buffer(shared.instances),
                DescriptorWrite::storage_buffer(shared.materials),
                DescriptorWrite::sampled_image(irradiance, cube_sampler),
                DescriptorWrite::sampled_image(specular, cube_sampler),
                DescriptorWrite::sampled_image(lut, shared.lut_sampler),
                tex(TextureSlot::base_color),
                tex(TextureSlot::metallic_roughness),
                tex(TextureSlot::normal),
                tex(TextureSlot::occlusion),
                tex(TextureSlot::emissive)};
            pipeline->push_descriptors(cmd, writes);
            pipeline->push_constants(cmd, DrawConstants{i, p.material});
            vkCmdDrawIndexed(cmd, p.index_count, 1, p.first_index, int32_t(p.vertex_offset), 0);
        }
    };
    auto declare_ibl = [&ibl](PassBuilder& b) {
        if (!ibl) return;
        if (ibl->irradiance.valid()) b.sample(ibl->irradiance);
        b.sample(ibl->specular);
        b.sample(ibl->lut);
    };
    auto begin = [](PassContext& pc, VkImageView color_view, VkImageView resolve_view, VkImageView depth_view,
                    bool load_color, uint32_t w, uint32_t h) {
        VkRenderingAttachmentInfo c{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        c.imageView = color_view;
        c.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        c.loadOp = load_color ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
        c.storeOp = resolve_view ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
        c.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        if (resolve_view) {
            c.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
            c.resolveImageView = resolve_view;
            c.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        }
        VkRenderingAttachmentInfo d{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        d.imageView = depth_view;
        d.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        d.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        d.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        d.clearValue.depthStencil = {0.0f, 0};  // reversed Z: 0 is infinitely far
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {w, h}};
        info.layerCount = 1;
        info.colorAttachmentCount = 1;
        info.pColorAttachments = &c;
        info.pDepthAttachment = &d;
        vkCmdBeginRendering(pc.cmd(), &info);
        set_viewport(pc.cmd(), w, h);
    };

    std::vector<uint32_t> order = list.opaque;
    order.insert(order.end(), list.blend.begin(), list.blend.end());
    const bool resolve = samples != VK_SAMPLE_COUNT_1_BIT;
    graph.add_graphics_pass("forward", [&](PassBuilder& b) {
        declare_ibl(b);
        color = b.color_attachment(color);
        depth = b.depth_attachment(depth);
        out.hdr = resolve ? b.color_attachment(out.hdr) : color;
    }, [=, hdr = out.hdr](PassContext& pc) {
        begin(pc, pc.view(color), resolve ? pc.view(hdr) : VK_NULL_HANDLE, pc.view(depth), false, s.width, s.height);
        record_draws(pc, order, final_pipelines);
        vkCmdEndRendering(pc.cmd());
    });

    if (draw_sky) {
        auto composited = add_skybox_pass(graph, out.hdr, s, *ibl);
        if (!composited) return composited.error();
        out.hdr = *composited;
    }

    ImageDesc ldr_desc = hdr_desc;
    ldr_desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    auto ldr = add_tonemap_pass(graph, programs_, nearest_, out.hdr, graph.create_image("display colour", ldr_desc),
                                s.display);
    if (!ldr) return ldr.error();
    out.ldr = *ldr;

    for (size_t v = 0; v < s.views.size(); ++v) {
        ImageHandle target = graph.create_image(std::string("view ") + view_name(s.views[v]), hdr_desc);
        ImageDesc view_depth_desc = hdr_desc;
        view_depth_desc.format = depth_format;
        ImageHandle view_depth = graph.create_image("view depth", view_depth_desc);
        graph.add_graphics_pass(std::string("view ") + view_name(s.views[v]), [&](PassBuilder& b) {
            declare_ibl(b);
            target = b.color_attachment(target);
            view_depth = b.depth_attachment(view_depth);
        }, [=, pipelines = view_pipelines[v]](PassContext& pc) {
            begin(pc, pc.view(target), VK_NULL_HANDLE, pc.view(view_depth), false, s.width, s.height);
            record_draws(pc, order, pipelines);
            vkCmdEndRendering(pc.cmd());
        });
        out.views.push_back({s.views[v], target});
    }
    return out;
}

}  // namespace facet
