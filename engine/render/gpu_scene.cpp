#include <facet/render/gpu_scene.h>

#include <algorithm>
#include <cmath>
#include <bit>
#include <cstring>
#include <span>

#include <facet/core/result.h>
#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include "core/guarded.h"

namespace facet {
namespace {

template <class T>
std::span<const std::byte> bytes_of(const std::vector<T>& v) {
    return std::as_bytes(std::span<const T>(v));
}

Buffer make_buffer(Context& context, std::span<const std::byte> data, VkBufferUsageFlags usage, const char* name) {
    // Never zero-sized: a scene without lights or textures still binds every buffer.
    Buffer buffer = or_throw(Buffer::create(context, std::max<VkDeviceSize>(data.size(), 64),
                                            usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::gpu_only, name));
    if (!data.empty()) or_throw(upload_buffer(context, buffer, data));
    return buffer;
}

VkSamplerAddressMode address_mode(uint32_t wrap) {
    switch (wrap) {
    case 1: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case 2: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    default: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    }
}

VkSamplerCreateInfo sampler_info(const TextureSampler& s) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = s.mag_linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    info.minFilter = s.min_linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    info.mipmapMode = s.mip_linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = address_mode(s.wrap_u);
    info.addressModeV = address_mode(s.wrap_v);
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.maxLod = s.use_mips ? VK_LOD_CLAMP_NONE : 0.0f;
    return info;
}

VkImageSubresourceRange mips(uint32_t first, uint32_t count) { return {VK_IMAGE_ASPECT_COLOR_BIT, first, count, 0, 1}; }

// Uploads mip 0 and fills the chain with linear 2x2 blits (sRGB images filter in linear
// space), leaving every level SHADER_READ_ONLY for fragment shaders.
Image upload_texture(Context& context, const TextureImage& t, bool srgb) {
    ImageDesc desc;
    desc.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    desc.width = t.width;
    desc.height = t.height;
    desc.mip_levels = std::bit_width(std::max(t.width, t.height));
    Image image = or_throw(Image::create(
        context, desc, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
        t.name + (srgb ? " (sRGB)" : " (linear)")));
    Buffer staging = or_throw(
        Buffer::create(context, t.rgba.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload, "texture staging"));
    std::memcpy(staging.mapped(), t.rgba.data(), t.rgba.size());
    or_throw(staging.flush());
    or_throw(context.submit_and_wait([&](VkCommandBuffer cmd) {
        VkImage img = image.handle();
        image_barrier(cmd, img, mips(0, desc.mip_levels), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {t.width, t.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.handle(), img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        for (uint32_t m = 1; m < desc.mip_levels; ++m) {
            image_barrier(cmd, img, mips(m - 1, 1), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
            blit.srcOffsets[1] = {int32_t(desc.mip_width(m - 1)), int32_t(desc.mip_height(m - 1)), 1};
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
            blit.dstOffsets[1] = {int32_t(desc.mip_width(m)), int32_t(desc.mip_height(m)), 1};
            vkCmdBlitImage(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &blit, VK_FILTER_LINEAR);
        }
        if (desc.mip_levels > 1)
            image_barrier(cmd, img, mips(0, desc.mip_levels - 1), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                          VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                          VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        image_barrier(cmd, img, mips(desc.mip_levels - 1, 1), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }, "a texture upload"));
    return image;
}

Image solid_image(Context& context, VkFormat format, std::array<uint8_t, 4> rgba, uint32_t layers, const char* name) {
    ImageDesc desc;
    desc.format = format;
    desc.array_layers = layers;
    desc.cube = layers == 6;
    Image image = or_throw(Image::create(context, desc, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, name));
    const auto data = std::as_bytes(std::span<const uint8_t>(rgba));
    for (uint32_t layer = 0; layer < layers; ++layer)
        or_throw(upload_image(context, image, 0, layer, data, VK_IMAGE_LAYOUT_UNDEFINED,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
    return image;
}

// The elements one every `stride` bytes (each bound alone as a uniform block).
template <typename T>
std::vector<std::byte> strided(const std::vector<T>& elements, VkDeviceSize stride) {
    std::vector<std::byte> out(elements.size() * stride);
    for (size_t i = 0; i < elements.size(); ++i) std::memcpy(out.data() + i * stride, &elements[i], sizeof(T));
    return out;
}

VkDeviceSize uniform_stride(const Context& context, VkDeviceSize size) {
    const VkDeviceSize align = std::max<VkDeviceSize>(context.properties().limits.minUniformBufferOffsetAlignment, 16);
    return (size + align - 1) / align * align;
}

std::vector<GpuMaterial> gpu_materials(const std::vector<Material>& materials) {
    std::vector<GpuMaterial> out;
    for (const Material& m : materials)
        out.push_back({m.base_color, glm::vec4(m.emissive, m.dielectric_f0),
                       glm::vec4(m.metallic, m.roughness, m.normal_scale, m.occlusion_strength),
                       glm::vec4(m.alpha_cutoff, m.specular_factor, m.occlusion, 0.0f),
                       glm::vec4(m.clearcoat, m.clearcoat_roughness, m.clearcoat_normal_scale, 0.0f),
                       glm::vec4(m.specular_color, 0.0f),
                       glm::vec4(m.iridescence, m.iridescence_ior, m.iridescence_thickness_minimum,
                                 m.iridescence_thickness_maximum),
                       glm::vec4(m.anisotropy, m.anisotropy_rotation, 0.0f, 0.0f),
                       glm::vec4(m.sheen_color, m.sheen_roughness),
                       // An infinite attenuation distance (none) as 0: the shader tests for it.
                       glm::vec4(m.transmission, m.thickness,
                                 std::isfinite(m.attenuation_distance) ? m.attenuation_distance : 0.0f, 0.0f),
                       glm::vec4(m.attenuation_color, 0.0f)});
    return out;
}

}  // namespace

Status GpuScene::update_materials(const std::vector<Material>& materials) {
    if (materials.size() != scene_.materials.size()) throw UsageError("update_materials: the material count changed");
    return upload_buffer(context_, materials_, strided(gpu_materials(materials), material_stride_));
}

Result<std::unique_ptr<GpuScene>> GpuScene::create(Context& context, const Scene& scene) {
    return guarded([&]() -> Result<std::unique_ptr<GpuScene>> {
        return std::unique_ptr<GpuScene>(new GpuScene(context, scene));
    });
}

GpuScene::GpuScene(Context& context, const Scene& scene)
    : context_(context),
      scene_(scene),
      default_sampler_(or_throw(Sampler::create(context, sampler_info({}), "default texture sampler"))) {
    vertices_ = make_buffer(context, bytes_of(scene.vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "scene vertices");
    indices_ = make_buffer(context, bytes_of(scene.indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "scene indices");
    std::vector<GpuInstance> instances;
    for (const Instance& i : scene.instances)
        instances.push_back({i.world, glm::mat4(glm::transpose(glm::inverse(glm::mat3(i.world))))});
    instance_stride_ = uniform_stride(context, sizeof(GpuInstance));
    material_stride_ = uniform_stride(context, sizeof(GpuMaterial));
    instances_ = make_buffer(context, strided(instances, instance_stride_), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                             "scene instances");
    materials_ = make_buffer(context, strided(gpu_materials(scene.materials), material_stride_),
                             VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "scene materials");

    white_srgb_ = solid_image(context, VK_FORMAT_R8G8B8A8_SRGB, {255, 255, 255, 255}, 1, "default white (sRGB)");
    white_linear_ = solid_image(context, VK_FORMAT_R8G8B8A8_UNORM, {255, 255, 255, 255}, 1, "default white");
    flat_normal_ = solid_image(context, VK_FORMAT_R8G8B8A8_UNORM, {128, 128, 255, 255}, 1, "default flat normal");
    black_2d_ = solid_image(context, VK_FORMAT_R8G8B8A8_UNORM, {0, 0, 0, 255}, 1, "default black");
    black_cube_ = solid_image(context, VK_FORMAT_R8G8B8A8_UNORM, {0, 0, 0, 255}, 6, "default black cube");
    black_2d_view_ = or_throw(black_2d_.view());
    black_cube_view_ = or_throw(black_cube_.view());
    for (size_t i = 0; i < scene.samplers.size(); ++i)
        samplers_.push_back(
            or_throw(Sampler::create(context, sampler_info(scene.samplers[i]), "gltf sampler " + std::to_string(i))));

    for (const Material& m : scene.materials) {
        const TextureRef refs[] = {m.base_color_texture,          m.metallic_roughness_texture, m.normal_texture,
                                   m.occlusion_texture,           m.emissive_texture,           m.clearcoat_texture,
                                   m.clearcoat_roughness_texture, m.clearcoat_normal_texture,   m.specular_texture,
                                   m.specular_color_texture,      m.iridescence_texture,        m.iridescence_thickness_texture,
                                   m.anisotropy_texture,          m.sheen_color_texture,        m.sheen_roughness_texture,
                                   m.transmission_texture,        m.thickness_texture};
        static_assert(std::size(refs) == size_t(TextureSlot::count));
        std::array<GpuTexture, size_t(TextureSlot::count)> slots{};
        std::array<bool, size_t(TextureSlot::count)> has{};
        for (size_t s = 0; s < slots.size(); ++s) {
            const bool srgb = s == size_t(TextureSlot::base_color) || s == size_t(TextureSlot::emissive) ||
                              s == size_t(TextureSlot::specular_color) || s == size_t(TextureSlot::sheen_color);
            const TextureRef& ref = refs[s];
            if (ref.valid() && size_t(ref.image) < scene.images.size()) {
                Image& image = texture_image(uint32_t(ref.image), srgb);
                slots[s].view = or_throw(image.view());
                slots[s].sampler = ref.sampler >= 0 && size_t(ref.sampler) < samplers_.size()
                                       ? samplers_[size_t(ref.sampler)].handle()
                                       : default_sampler_.handle();
                has[s] = true;
            } else {
                const bool normal = s == size_t(TextureSlot::normal) || s == size_t(TextureSlot::clearcoat_normal);
                Image& fallback = normal ? flat_normal_ : srgb ? white_srgb_ : white_linear_;
                slots[s] = {or_throw(fallback.view()), default_sampler_.handle()};
            }
        }
        // The occlusion and metallic-roughness textures read as one where they can be.
        const TextureRef& ao = m.occlusion_texture;
        const TextureRef& mr = m.metallic_roughness_texture;
        const bool both = has[size_t(TextureSlot::occlusion)] && has[size_t(TextureSlot::metallic_roughness)] &&
                          ao.sampler == mr.sampler && ao.uv_set == mr.uv_set && ao.uv_transform == mr.uv_transform;
        const TextureImage* ao_image = both ? &scene.images[size_t(ao.image)] : nullptr;
        const TextureImage* mr_image = both ? &scene.images[size_t(mr.image)] : nullptr;
        const bool packed = both && (ao.image == mr.image || (ao_image->width == mr_image->width &&
                                                              ao_image->height == mr_image->height));
        if (packed && ao.image != mr.image) {
            const VkImageView view = or_throw(packed_occlusion_image(uint32_t(ao.image), uint32_t(mr.image)).view());
            slots[size_t(TextureSlot::metallic_roughness)].view = view;
            slots[size_t(TextureSlot::occlusion)].view = view;
        }
        material_textures_.push_back(slots);
        material_has_.push_back(has);
        occlusion_packed_.push_back(packed);
    }
}

Image& GpuScene::texture_image(uint32_t image, bool srgb) {
    const auto key = std::make_pair(image, srgb);
    auto it = textures_.find(key);
    if (it == textures_.end()) {
        it = textures_.emplace(key, upload_texture(context_, scene_.images[image], srgb)).first;
        texture_bytes_ += scene_.images[image].rgba.size() * 4 / 3;
    }
    return it->second;
}

Image& GpuScene::packed_occlusion_image(uint32_t occlusion, uint32_t metallic_roughness) {
    const auto key = std::make_pair(occlusion, metallic_roughness);
    auto it = packed_.find(key);
    if (it == packed_.end()) {
        const TextureImage& ao = scene_.images[occlusion];
        const TextureImage& mr = scene_.images[metallic_roughness];
        TextureImage packed;
        packed.name = ao.name + " + " + mr.name;
        packed.width = mr.width;
        packed.height = mr.height;
        packed.rgba = mr.rgba;
        for (size_t i = 0; i < packed.rgba.size(); i += 4) packed.rgba[i] = ao.rgba[i];  // R: occlusion
        it = packed_.emplace(key, upload_texture(context_, packed, false)).first;
        texture_bytes_ += packed.rgba.size() * 4 / 3;
    }
    return it->second;
}

bool GpuScene::occlusion_in_metallic_roughness(uint32_t material) const { return occlusion_packed_.at(material); }

GpuTexture GpuScene::texture(uint32_t material, TextureSlot slot) const {
    return material_textures_.at(material)[size_t(slot)];
}

bool GpuScene::has_texture(uint32_t material, TextureSlot slot) const {
    return material_has_.at(material)[size_t(slot)];
}

}  // namespace facet
