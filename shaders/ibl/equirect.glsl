#ifndef FACET_EQUIRECT_GLSL
#define FACET_EQUIRECT_GLSL
// Equirectangular mapping fixed in design.md (the thesis' SampleEquirectangular):
// u = atan2(d.z, d.x) / 2pi + 0.5, v = asin(d.y) / pi + 0.5, and v = 1 is the top row
// of the image, so image row 0 is +Y, the centre column is +X, u = 0.75 is +Z.

const float FACET_PI = 3.14159265358979323846;

// Direction for image coordinates uv_image in [0,1]^2 with uv_image.y = 0 at the top row.
vec3 equirect_direction(vec2 uv_image) {
    float phi = (uv_image.x - 0.5) * 2.0 * FACET_PI;   // atan2(d.z, d.x)
    float theta = (0.5 - uv_image.y) * FACET_PI;       // asin(d.y), +pi/2 at the top row
    float c = cos(theta);
    return vec3(c * cos(phi), sin(theta), c * sin(phi));
}

// Image coordinates (row 0 = top) of direction d (unit length).
vec2 equirect_uv(vec3 d) {
    float u = atan(d.z, d.x) / (2.0 * FACET_PI) + 0.5;
    float v = asin(clamp(d.y, -1.0, 1.0)) / FACET_PI + 0.5;
    return vec2(u, 1.0 - v);
}

#endif
