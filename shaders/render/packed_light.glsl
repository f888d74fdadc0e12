#ifndef FACET_PACKED_LIGHT_GLSL
#define FACET_PACKED_LIGHT_GLSL
// The light the renderers upload, declared once: the forward pass's lights
// (render/forward_interface.glsl), the reference pass's (render/reference.comp) and the
// skybox's extracted disks (render/skybox.comp) are arrays of PackedLight, and the C++
// side fills engine/render/light_data.h's LightData (tests/cpu/gpu_layout_test.cpp checks
// the two layouts against each other). The unpack functions turn it into
// facet/shading.glsl's types, whose functions hold the falloff and the shading.
#include "facet/shading.glsl"

struct PackedLight {
    vec4 position_range;   // xyz position (metres), w range (0 = infinite); disk: x = 1 / (2 - 2 cos theta),
                           // y = 1 / (2 sin theta)
    vec4 direction_type;   // xyz the direction the light travels, w the type: FACET_LIGHT_*
                           // (0 directional, 1 point, 2 spot) or 3, a disk extracted from
                           // the environment
    vec4 color_intensity;  // rgb colour, a intensity (lux or candela); disk: radiance x a
    vec4 cone;             // spot: x = 1 / (cos inner - cos outer), y = -cos outer * x;
                           // disk: x = cos of the angular radius, y = the angular radius,
                           // z = its sine, w = the cap's solid angle 2 pi (1 - cos)
};

FacetPunctualLight unpack_punctual_light(PackedLight light) {
    FacetPunctualLight p;
    p.type = uint(light.direction_type.w);
    p.position = light.position_range.xyz;
    p.range_m = light.position_range.w;
    p.direction = light.direction_type.xyz;
    p.intensity = light.color_intensity.rgb * light.color_intensity.a;
    p.cone_scale = light.cone.x;
    p.cone_offset = light.cone.y;
    return p;
}

FacetDiskLight unpack_disk_light(PackedLight light) {
    FacetDiskLight d;
    d.direction = -light.direction_type.xyz;  // unit (render/light_data.h)
    d.cos_radius = light.cone.x;
    d.angular_radius = light.cone.y;
    d.sin_radius = light.cone.z;
    d.solid_angle = light.cone.w;
    d.inv_chord2 = light.position_range.x;
    d.inv_diameter = light.position_range.y;
    d.radiance = light.color_intensity.rgb * light.color_intensity.a;
    return d;
}

#endif
