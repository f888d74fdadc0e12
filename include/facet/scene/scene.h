#pragma once
// A scene as the renderer draws it: flat vertex and index arrays, materials in glTF's
// metallic-roughness model, decoded textures, and instances (a primitive placed by its
// node's world matrix). Loaders (glTF, built-ins) fill it; nothing here touches Vulkan.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace facet {

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec2 uv{0.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w = handedness (glTF)
    glm::vec4 color{1.0f};  // COLOR_0 (linear RGBA, alpha 1 for VEC3), multiplied into the base colour
    glm::vec2 uv1{0.0f};    // TEXCOORD_1, for textures whose texCoord is 1
};

// glTF sampler state, in Vulkan terms.
struct TextureSampler {
    bool mag_linear = true;
    bool min_linear = true;
    bool mip_linear = true;
    bool use_mips = true;
    // 0 = repeat, 1 = clamp to edge, 2 = mirrored repeat (VkSamplerAddressMode order)
    uint32_t wrap_u = 0, wrap_v = 0;
    bool operator==(const TextureSampler&) const = default;
};

// Decoded 8-bit RGBA texels, row 0 = the file's top row (glTF uv (0,0) is top-left).
struct TextureImage {
    std::string name;  // file name or "image N"
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;
    uint32_t source_width = 0, source_height = 0;  // the file's size (larger when downsampled on load)
};

struct TextureRef {
    int32_t image = -1;    // index into Scene::images; -1 = none
    int32_t sampler = -1;  // index into Scene::samplers; -1 = default sampler
    uint32_t uv_set = 0;   // 0: Vertex::uv (TEXCOORD_0), 1: Vertex::uv1 (TEXCOORD_1); higher sets are refused
    // KHR_texture_transform: uv' = M (u, v, 1), M = translation x rotation x scale, column-major
    // 3x2 (a, b, c, d, tx, ty: u' = a u + c v + tx, v' = b u + d v + ty).
    std::array<float, 6> uv_transform{1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f};
    bool valid() const { return image >= 0; }
    bool transformed() const { return uv_transform != std::array<float, 6>{1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f}; }
};

enum class AlphaMode { opaque, mask, blend };

struct Material {
    std::string name;
    glm::vec4 base_color{1.0f};
    float metallic = 1.0f;
    float roughness = 1.0f;
    glm::vec3 emissive{0.0f};
    float normal_scale = 1.0f;
    float occlusion_strength = 1.0f;
    AlphaMode alpha_mode = AlphaMode::opaque;
    float alpha_cutoff = 0.5f;
    bool double_sided = false;
    // F0 of the dielectric part: ((ior - 1) / (ior + 1))^2, 0.04 for glTF's ior 1.5
    // (KHR_materials_ior); presets set it from the thesis' reflectance table.
    float dielectric_f0 = 0.04f;
    // Scales the specular lobe and its Fresnel (KHR_materials_specular's factor):
    // 0 leaves a Lambert-only material, as the white-furnace test needs.
    float specular_factor = 1.0f;
    // KHR_materials_specular's colour: the dielectric F0 per channel is
    // min(dielectric_f0 x specular_color, 1) (and the diffuse lobe keeps 1 - specular x the
    // largest channel's Fresnel).
    glm::vec3 specular_color{1.0f};
    // Ambient occlusion as a factor (the thesis' "AO" slider), times the occlusion
    // texture's value where there is one.
    float occlusion = 1.0f;
    // KHR_materials_unlit: the colour is base colour x vertex colour, lighting ignored (the
    // loader clears the other PBR inputs, which are fallbacks for viewers without it).
    bool unlit = false;
    // KHR_materials_clearcoat: a clear dielectric layer (ior 1.5) over the material, with
    // weight `clearcoat` and its own perceptual roughness; its specular lobe is the model's
    // (design.md, "BRDF models") and the layer below is dimmed by 1 - clearcoat x F(v.h).
    float clearcoat = 0.0f;
    float clearcoat_roughness = 0.0f;
    TextureRef base_color_texture;          // sRGB
    TextureRef metallic_roughness_texture;  // linear: G = roughness, B = metalness
    TextureRef normal_texture;              // linear, tangent space
    TextureRef occlusion_texture;           // linear: R
    TextureRef emissive_texture;            // sRGB
    // KHR_materials_clearcoat's textures: R x clearcoat, G x clearcoat_roughness, and the
    // layer's own normal map (the geometry's normal without one), scaled as normalTexture.
    TextureRef clearcoat_texture;            // linear: R
    TextureRef clearcoat_roughness_texture;  // linear: G
    TextureRef clearcoat_normal_texture;     // linear, tangent space
    float clearcoat_normal_scale = 1.0f;
    // KHR_materials_specular's textures: A x specular_factor, RGB x specular_color.
    TextureRef specular_texture;        // linear: A
    TextureRef specular_color_texture;  // sRGB: RGB
    // KHR_materials_iridescence: a thin dielectric film of weight `iridescence` (0: none),
    // index iridescence_ior and thickness iridescence_thickness_maximum nm, or from the
    // minimum to the maximum by the thickness texture's G; its weight x the texture's R.
    float iridescence = 0.0f;
    float iridescence_ior = 1.3f;
    float iridescence_thickness_minimum = 100.0f;
    float iridescence_thickness_maximum = 400.0f;
    TextureRef iridescence_texture;            // linear: R
    TextureRef iridescence_thickness_texture;  // linear: G
    // KHR_materials_anisotropy: the specular lobe stretched along a direction of the tangent
    // frame, `anisotropy` 0 (none) .. 1, the direction turned by anisotropy_rotation (radians,
    // counter-clockwise from the tangent); the texture's RG a direction, its B x the strength.
    float anisotropy = 0.0f;
    float anisotropy_rotation = 0.0f;
    TextureRef anisotropy_texture;  // linear: RG direction, B strength
    // KHR_materials_sheen: a layer of fibres over the material (under a clear coat), its
    // colour (linear; black: no layer) and its own roughness (alpha = sheen_roughness^2 in the
    // Charlie distribution); the material below is scaled by 1 - max(sheen_color) E_sheen
    // (the extension's albedo scaling). The colour texture's RGB and the roughness texture's A
    // multiply the factors.
    glm::vec3 sheen_color{0.0f};
    float sheen_roughness = 0.0f;
    TextureRef sheen_color_texture;      // sRGB: RGB
    TextureRef sheen_roughness_texture;  // linear: A
    bool has_sheen() const { return sheen_color.r > 0.0f || sheen_color.g > 0.0f || sheen_color.b > 0.0f; }
    // KHR_materials_transmission: the share of the light entering the dielectric part that is
    // transmitted through the surface (a microfacet BTDF tinted by the base colour) instead of
    // re-emitted diffusely; 0 (none) .. 1, times the texture's R. Its lobe is the specular
    // lobe mirrored through the surface, its alpha (roughness x clamp(2 ior - 2, 0, 1))^2, ior
    // the dielectric's ((1 + sqrt F0) / (1 - sqrt F0): 1.5 for F0 0.04).
    float transmission = 0.0f;
    TextureRef transmission_texture;  // linear: R
    // KHR_materials_volume: the thickness of the volume behind the surface in the mesh's own
    // units (0: thin-walled, no refraction), times the texture's G; light crossing it is
    // attenuated to attenuation_color^(distance / attenuation_distance) (Beer-Lambert; the
    // distance infinite by default: no attenuation). Read with transmission only.
    float thickness = 0.0f;
    TextureRef thickness_texture;  // linear: G
    float attenuation_distance = std::numeric_limits<float>::infinity();
    glm::vec3 attenuation_color{1.0f};
    bool has_transmission() const { return transmission > 0.0f; }

    // The vertex tangents serve the normal maps: the surface's, else the clear coat's.
    bool has_normal_map() const { return normal_texture.valid() || clearcoat_normal_texture.valid(); }
    // So do an anisotropic lobe's directions.
    bool needs_tangents() const { return has_normal_map() || anisotropy > 0.0f; }
    uint32_t tangent_uv_set() const {
        return normal_texture.valid()           ? normal_texture.uv_set
               : clearcoat_normal_texture.valid() ? clearcoat_normal_texture.uv_set
                                                  : anisotropy_texture.uv_set;
    }
};

// How a primitive's indices are drawn: glTF's strips, fans and loops are converted to
// these lists when loaded. Points and lines are drawn unlit (base colour x vertex colour
// + emissive), as other viewers draw them.
enum class Topology { triangles, lines, points };

// A contiguous range of Scene::indices (a list of `topology`) using one material.
struct Primitive {
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    uint32_t vertex_offset = 0;  // added to every index of the range
    uint32_t vertex_count = 0;
    uint32_t material = 0;       // index into Scene::materials
    Topology topology = Topology::triangles;
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  // object space
};

struct Mesh {
    std::string name;
    std::vector<uint32_t> primitives;  // indices into Scene::primitives
};

// One primitive drawn with one world matrix (the node hierarchy, flattened).
struct Instance {
    uint32_t primitive = 0;
    glm::mat4 world{1.0f};
    std::string node;  // node name, for messages
};

enum class LightType { directional, point, spot };

// KHR_lights_punctual units: directional in lux (lm/m^2), point and spot in candela
// (lm/sr). Directions point where the light travels (glTF: the node's -Z).
struct Light {
    LightType type = LightType::directional;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    float range = 0.0f;  // 0 = infinite
    float inner_cone = 0.0f;                 // radians
    float outer_cone = 0.7853981633974483f;  // radians (pi/4, glTF's default)
};

struct Camera {
    std::string name;
    glm::vec3 position{0.0f, 0.0f, 3.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov = 0.7853981633974483f;  // radians
    float znear = 0.05f;
    float zfar = 0.0f;  // 0 = infinite (reverse-free, far plane chosen from the bounds)
    bool orthographic = false;
    float ymag = 1.0f;  // orthographic half height
};

struct Scene {
    std::string source;        // file path or builtin:NAME
    std::string content_hash;  // of the file bytes (and its buffers and images)
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<Primitive> primitives;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<TextureImage> images;
    std::vector<TextureSampler> samplers;
    std::vector<Instance> instances;
    std::vector<Light> lights;
    std::vector<Camera> cameras;  // in world space, from camera nodes
    // What the loader met but does not draw (an extension in extensionsUsed Facet
    // ignores, ...), one line each; the programs print them and write them in NAME.json.
    std::vector<std::string> warnings;

    // World-space bounds of all instances (min > max when empty).
    std::pair<glm::vec3, glm::vec3> world_bounds() const;
};

}  // namespace facet
