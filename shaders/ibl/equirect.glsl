#ifndef FACET_EQUIRECT_GLSL
#define FACET_EQUIRECT_GLSL
// Equirectangular mapping fixed in design.md (the thesis' SampleEquirectangular):
// u = atan2(d.z, d.x) / 2pi + 0.5, v = asin(d.y) / pi + 0.5, and v = 1 is the top row
// of the image, so image row 0 is +Y, the centre column is +X, u = 0.75 is +Z. The C++
// side is engine/io/equirect.h (tests/gpu/shared_constants_test.cpp compares the two).

#include "facet/shared_constants.h"

// Direction for image coordinates uv_image in [0,1]^2 with uv_image.y = 0 at the top row.
vec3 equirect_direction(vec2 uv_image) {
    float phi = (uv_image.x - 0.5) * 2.0 * facet_pi;   // atan2(d.z, d.x)
    float theta = (0.5 - uv_image.y) * facet_pi;       // asin(d.y), +pi/2 at the top row
    float c = cos(theta);
    return vec3(c * cos(phi), sin(theta), c * sin(phi));
}

// Image coordinates (row 0 = top) of direction d (unit length).
vec2 equirect_uv(vec3 d) {
    float u = atan(d.z, d.x) / (2.0 * facet_pi) + 0.5;
    float v = asin(clamp(d.y, -1.0, 1.0)) / facet_pi + 0.5;
    return vec2(u, 1.0 - v);
}

// The texel of a size.x x size.y image (row 0 = top) that holds direction d (unit length).
uvec2 equirect_texel(vec3 d, uvec2 size) {
    return min(uvec2(equirect_uv(d) * vec2(size)), size - 1u);
}

// Latitude (radians) at row coordinate `row` of an image `height` rows tall (row y spans
// [y, y + 1]): +pi/2 at the top edge, -pi/2 at the bottom edge.
float equirect_latitude(float row, uint height) {
    return facet_pi * (0.5 - row / float(height));
}

// Solid angle of a texel of row y: (2 pi / W) (sin(latitude_top) - sin(latitude_bottom)).
float equirect_texel_solid_angle(uint y, uvec2 size) {
    float latitude_top = equirect_latitude(float(y), size.y);
    float latitude_bottom = equirect_latitude(float(y + 1u), size.y);
    return (2.0 * facet_pi / float(size.x)) * (sin(latitude_top) - sin(latitude_bottom));
}

// A direction inside texel `texel` for jitter in [0, 1)^2, uniform in solid angle across
// the texel: linear in longitude and in sin(latitude).
vec3 equirect_texel_direction(uvec2 texel, vec2 jitter, uvec2 size) {
    float latitude_top = equirect_latitude(float(texel.y), size.y);
    float latitude_bottom = equirect_latitude(float(texel.y + 1u), size.y);
    float sin_lat = mix(sin(latitude_bottom), sin(latitude_top), jitter.y);
    float cos_lat = sqrt(max(0.0, 1.0 - sin_lat * sin_lat));
    float phi = ((float(texel.x) + jitter.x) / float(size.x) - 0.5) * 2.0 * facet_pi;
    return vec3(cos_lat * cos(phi), sin_lat, cos_lat * sin(phi));
}

#endif
