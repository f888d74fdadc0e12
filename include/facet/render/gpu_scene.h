#pragma once
// A Scene on the GPU: one vertex and one index buffer, instance and material buffers,
// textures with full mip chains (sRGB for colour, linear for data) and their samplers,
// plus the 1x1 defaults bound where a material has no texture. Uploaded once, outside
// any render graph; the forward pass reads it.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include <facet/core/result.h>
#include <facet/gpu/resources.h>
#include <facet/scene/scene.h>

namespace facet {

class Context;

enum class TextureSlot {
    base_color,
    metallic_roughness,
    normal,
    occlusion,
    emissive,
    clearcoat,            // KHR_materials_clearcoat: R
    clearcoat_roughness,  // G
    clearcoat_normal,
    specular,        // KHR_materials_specular: A
    specular_color,  // RGB, sRGB
    iridescence,            // KHR_materials_iridescence: R
    iridescence_thickness,  // G
    anisotropy,             // KHR_materials_anisotropy: RG direction, B strength
    sheen_color,            // KHR_materials_sheen: RGB, sRGB
    sheen_roughness,        // A
    transmission,           // KHR_materials_transmission: R
    thickness,              // KHR_materials_volume: G
    count
};

// std140 (= std430 here: vec4 and mat4 members only) layouts of
// shaders/render/forward_interface.glsl's Instance and Material blocks.
struct GpuInstance {
    glm::mat4 world;
    glm::mat4 normal_matrix;
};
struct GpuMaterial {
    glm::vec4 base_color;
    glm::vec4 emissive_f0;
    glm::vec4 factors;
    glm::vec4 extra;
    glm::vec4 clearcoat;  // KHR_materials_clearcoat: factor, roughness, normal texture scale
    glm::vec4 specular_color;  // KHR_materials_specular's colour (rgb)
    glm::vec4 iridescence;     // KHR_materials_iridescence: factor, film ior, thickness minimum, maximum (nm)
    glm::vec4 anisotropy;      // KHR_materials_anisotropy: strength, rotation (radians)
    glm::vec4 sheen;           // KHR_materials_sheen: colour (rgb, linear), roughness (a)
    glm::vec4 transmission;    // KHR_materials_transmission: factor; KHR_materials_volume: thickness, attenuation distance (0: none)
    glm::vec4 attenuation;     // KHR_materials_volume: attenuation colour (rgb)
};

struct GpuTexture {
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
};

// Errors: create and update_materials return an Error (with its VkResult) when the
// device fails (out of memory, device lost, a wait timed out); nothing is left half made.
// UsageError marks programmer misuse (update_materials with another material count).
class GpuScene {
public:
    // Uploads the scene's geometry, materials and textures. `scene` must outlive it.
    static Result<std::unique_ptr<GpuScene>> create(Context& context, const Scene& scene);
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    const Scene& scene() const { return scene_; }
    // New factors for the same materials (textures and alpha modes unchanged), uploaded
    // now; call between frames.
    Status update_materials(const std::vector<Material>& materials);
    VkBuffer vertices() const { return vertices_.handle(); }
    VkBuffer indices() const { return indices_.handle(); }
    // Uniform buffers of GpuInstance and GpuMaterial, one element every instance_stride() /
    // material_stride() bytes (the size rounded up to minUniformBufferOffsetAlignment), so
    // that each draw binds its own element at i x stride, range sizeof(element).
    VkBuffer instances() const { return instances_.handle(); }
    VkBuffer materials() const { return materials_.handle(); }
    VkDeviceSize instance_stride() const { return instance_stride_; }
    VkDeviceSize material_stride() const { return material_stride_; }
    // The material's texture in a slot, or the slot's default (white; flat normal).
    GpuTexture texture(uint32_t material, TextureSlot slot) const;
    bool has_texture(uint32_t material, TextureSlot slot) const;
    // Whether the material's occlusion is R of its metallic-roughness texture (both slots
    // then hold that texture): its two textures are one image, or were packed into one
    // (R from the occlusion, G and B from the metallic-roughness image) because they share
    // coordinates, transform, sampler and size, so that a fragment reads one texel for both.
    bool occlusion_in_metallic_roughness(uint32_t material) const;
    // Black 1x1 cube and 2D images for the IBL bindings of a scene without an environment.
    VkImageView black_cube() const { return black_cube_view_; }
    VkImageView black_2d() const { return black_2d_view_; }
    VkSampler default_sampler() const { return default_sampler_.handle(); }
    uint64_t texture_bytes() const { return texture_bytes_; }

private:
    GpuScene(Context& context, const Scene& scene);  // throws internally; create() returns the Error
    Image& texture_image(uint32_t image, bool srgb);
    Image& packed_occlusion_image(uint32_t occlusion, uint32_t metallic_roughness);
    Context& context_;
    const Scene& scene_;
    Buffer vertices_, indices_, instances_, materials_;
    VkDeviceSize instance_stride_ = 0, material_stride_ = 0;
    std::map<std::pair<uint32_t, bool>, Image> textures_;  // (scene image, sRGB) -> image
    std::map<std::pair<uint32_t, uint32_t>, Image> packed_;  // (occlusion, metallic-roughness image) -> packed
    std::vector<Sampler> samplers_;                         // one per scene sampler
    Sampler default_sampler_;
    Image white_srgb_, white_linear_, flat_normal_, black_cube_, black_2d_;
    VkImageView black_cube_view_ = VK_NULL_HANDLE, black_2d_view_ = VK_NULL_HANDLE;
    std::vector<std::array<GpuTexture, size_t(TextureSlot::count)>> material_textures_;
    std::vector<std::array<bool, size_t(TextureSlot::count)>> material_has_;
    std::vector<bool> occlusion_packed_;
    uint64_t texture_bytes_ = 0;
};

}  // namespace facet
