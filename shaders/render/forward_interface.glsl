#ifndef FACET_FORWARD_INTERFACE_GLSL
#define FACET_FORWARD_INTERFACE_GLSL
// What the forward pass's shaders share with engine/render/forward_pass.cpp: the
// descriptor bindings, the buffer layouts and the push constants. The C++ mirrors are in
// engine/render/forward_data.h, light_data.h and include/facet/render/gpu_scene.h;
// tests/cpu/gpu_layout_test.cpp checks their sizes and offsets against this file's
// (std140 / std430, vec4-aligned).
#include "render/packed_light.glsl"

layout(binding = 0, std140) uniform Frame {
    mat4 view_projection;
    vec4 camera_position;  // xyz
    vec4 ibl;              // x: intensity, y: highest specular level (roughness 1), z: first level without the extracted lights
    uvec4 counts;          // x: punctual lights, y: disk lights extracted from the environment (compiled in: forward.frag)
} frame;

// The punctual lights (frame.counts.x).
layout(binding = 1, std430) readonly buffer Lights { PackedLight lights[]; };

// The draw's instance and material: one element each, bound per draw at its offset
// (GpuScene's strides) as uniform blocks, not indexed in a storage buffer: a CPU device
// (lavapipe) loads a storage buffer one lane at a time, a uniform block at an offset that
// is the same for every lane once for all of them (a few percent of the forward pass:
// README, Speed).
struct InstanceData {
    mat4 world;
    mat4 normal_matrix;  // inverse transpose of world's 3x3, in a mat4 for alignment
};
layout(binding = 2, std140) uniform Instance { InstanceData instance; };

struct MaterialData {
    vec4 base_color;
    vec4 emissive_f0;  // rgb emissive, a dielectric F0
    vec4 factors;      // metallic, roughness, normal scale, occlusion strength
    vec4 extra;        // alpha cutoff, specular factor, occlusion factor
    vec4 clearcoat;    // KHR_materials_clearcoat: factor, roughness, normal texture scale
    vec4 specular_color;  // KHR_materials_specular's colour (rgb)
    vec4 iridescence;     // KHR_materials_iridescence: factor, film ior, thickness minimum, maximum (nm)
    vec4 anisotropy;      // KHR_materials_anisotropy: strength, rotation (radians)
    vec4 sheen;           // KHR_materials_sheen: colour (rgb, linear), roughness (a)
    vec4 transmission;    // KHR_materials_transmission: factor; KHR_materials_volume: thickness, attenuation distance (0: none)
    vec4 attenuation;     // KHR_materials_volume: attenuation colour (rgb)
};
layout(binding = 3, std140) uniform Material { MaterialData material; };

layout(binding = 4) uniform samplerCube irradiance_map;  // E / pi
layout(binding = 5) uniform samplerCube specular_map;    // GGX prefiltered, roughness by level
layout(binding = 6) uniform sampler2D brdf_lut;          // A, B by (NdotV, roughness)
layout(binding = 7) uniform sampler2D base_color_map;
layout(binding = 8) uniform sampler2D metallic_roughness_map;
layout(binding = 9) uniform sampler2D normal_map;
layout(binding = 10) uniform sampler2D occlusion_map;
layout(binding = 11) uniform sampler2D emissive_map;
layout(binding = 12) uniform sampler2D specular_lobes;  // the fitted lookups (render/specular_lobes.h)
layout(binding = 13) uniform sampler2D clearcoat_map;            // KHR_materials_clearcoat: R x weight
layout(binding = 14) uniform sampler2D clearcoat_roughness_map;  // G x roughness
layout(binding = 15) uniform sampler2D clearcoat_normal_map;     // the layer's normal, tangent space
layout(binding = 16) uniform sampler2D specular_factor_map;      // KHR_materials_specular: A x specularFactor
layout(binding = 17) uniform sampler2D specular_color_map;       // RGB (sRGB) x specularColorFactor
layout(binding = 18) uniform sampler2D iridescence_map;          // KHR_materials_iridescence: R x factor
layout(binding = 19) uniform sampler2D iridescence_thickness_map;  // G: minimum .. maximum thickness
layout(binding = 20) uniform sampler2D anisotropy_map;           // KHR_materials_anisotropy: RG direction, B strength
layout(binding = 21) uniform sampler2D sheen_color_map;          // KHR_materials_sheen: RGB (sRGB) x sheenColorFactor
layout(binding = 22) uniform sampler2D sheen_roughness_map;      // A x sheenRoughnessFactor
layout(binding = 23) uniform sampler2D transmission_map;         // KHR_materials_transmission: R x transmissionFactor
layout(binding = 24) uniform sampler2D thickness_map;            // KHR_materials_volume: G x thicknessFactor
// What transmissive surfaces see behind them: the opaque scene drawn without them
// (premultiplied colour, alpha its coverage; mipmapped), transparent black elsewhere.
layout(binding = 25) uniform sampler2D transmission_background;

#endif
