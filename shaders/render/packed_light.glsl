#ifndef FACET_PACKED_LIGHT_GLSL
#define FACET_PACKED_LIGHT_GLSL
// The packed light the renderers upload (four vec4: position_range, direction_type,
// color_intensity, cone; render/forward_interface.glsl's Light, the reference pass's
// lights) read into facet/shading.glsl's types. Taken member by member so that any block
// of that layout can be passed.
#include "facet/shading.glsl"

// position_range: xyz position, w range (0 = infinite); direction_type: xyz direction the
// light travels, w type (0 directional, 1 point, 2 spot); color_intensity: rgb colour,
// a intensity; cone: x = 1 / (cos inner - cos outer), y = -cos outer * x.
FacetPunctualLight unpack_punctual_light(vec4 position_range, vec4 direction_type, vec4 color_intensity, vec4 cone) {
    FacetPunctualLight p;
    p.type = uint(direction_type.w);
    p.position = position_range.xyz;
    p.range_m = position_range.w;
    p.direction = direction_type.xyz;
    p.intensity = color_intensity.rgb * color_intensity.a;
    p.cone_scale = cone.x;
    p.cone_offset = cone.y;
    return p;
}

// A disk (type 3): direction_type.xyz the direction its light travels, color_intensity
// radiance, cone: x = cos of the angular radius, y = the angular radius.
FacetDiskLight unpack_disk_light(vec4 direction_type, vec4 color_intensity, vec4 cone) {
    FacetDiskLight d;
    d.direction = -normalize(direction_type.xyz);
    d.cos_radius = cone.x;
    d.angular_radius = cone.y;
    d.radiance = color_intensity.rgb * color_intensity.a;
    return d;
}

#endif
