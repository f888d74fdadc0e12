#ifndef FACET_CUBE_GLSL
#define FACET_CUBE_GLSL
// Cube-map faces as the Vulkan specification selects them ("Cube Map Face Selection"):
// faces +X, -X, +Y, -Y, +Z, -Z; on a face, s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2,
// and texel (i, j) has s = (i + 0.5) / N, t = (j + 0.5) / N. This inverts that table.

// Unnormalised direction through face coordinates (s, t) in [0, 1] of `face`.
vec3 cube_direction(uint face, vec2 st) {
    float sc = 2.0 * st.x - 1.0;
    float tc = 2.0 * st.y - 1.0;
    switch (face) {
        case 0u: return vec3(1.0, -tc, -sc);
        case 1u: return vec3(-1.0, -tc, sc);
        case 2u: return vec3(sc, 1.0, tc);
        case 3u: return vec3(sc, -1.0, -tc);
        case 4u: return vec3(sc, -tc, 1.0);
        default: return vec3(-sc, -tc, -1.0);
    }
}

// Solid angle of the face rectangle [x0, x1] x [y0, y1] in face coordinates in [-1, 1]:
// the integral of (1 + x^2 + y^2)^(-3/2), whose antiderivative is atan(xy / sqrt(1 + x^2 + y^2)).
float cube_area_element(float x, float y) {
    return atan(x * y, sqrt(x * x + y * y + 1.0));
}
float cube_texel_solid_angle(vec2 lo, vec2 hi) {
    return cube_area_element(lo.x, lo.y) - cube_area_element(lo.x, hi.y) - cube_area_element(hi.x, lo.y) +
           cube_area_element(hi.x, hi.y);
}

// Solid angle of texel (i, j) of an N x N face.
float cube_texel_solid_angle(uvec2 texel, uint n) {
    vec2 lo = vec2(texel) / float(n) * 2.0 - 1.0;
    vec2 hi = vec2(texel + 1u) / float(n) * 2.0 - 1.0;
    return cube_texel_solid_angle(lo, hi);
}

#endif
