#version 460
// Equirectangular image -> cube map level 0. Each cube texel averages taps x taps
// directions spread over its area (4 x 4 for the environment), each a bilinear sample of
// the equirect, so a small bright sun keeps its power whichever texels it falls on.
// With FACET_MIRROR the same texels also go to `mirror` (specular level 0, roughness 0:
// the environment itself), which saves the bake a pass that would read them back.
#include "ibl/cube.glsl"
#include "ibl/equirect.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform sampler2D equirect;  // repeat in u, clamp in v
layout(binding = 1, rgba32f) uniform writeonly image2DArray cube;
#ifdef FACET_MIRROR
layout(binding = 2, rgba32f) uniform writeonly image2DArray mirror;
#endif
layout(push_constant) uniform Params { uint taps; } params;

const float inv_two_pi = 1.0 / (2.0 * facet_pi);

void main() {
    uint n = uint(imageSize(cube).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 sum = vec3(0.0);
    float taps = float(params.taps);
    if (id.z == 2u || id.z == 3u) {
        // +Y, -Y: d = (sc, +-1, +-tc); longitude atan2(d.z, d.x), latitude
        // +-(pi/2 - atan(sqrt(sc^2 + tc^2))).
        float sy = id.z == 2u ? 1.0 : -1.0;
        for (uint j = 0u; j < params.taps; ++j) {
            float tc = 2.0 * (float(id.y) + (float(j) + 0.5) / taps) / float(n) - 1.0;
            for (uint i = 0u; i < params.taps; ++i) {
                float sc = 2.0 * (float(id.x) + (float(i) + 0.5) / taps) / float(n) - 1.0;
                float u = atan(sy * tc, sc) * inv_two_pi + 0.5;
                float lat = sy * (0.5 * facet_pi - atan(sqrt(sc * sc + tc * tc)));
                sum += textureLod(equirect, vec2(u, 0.5 - lat / facet_pi), 0.0).rgb;
            }
        }
    } else {
        // Side faces: d = (x(sc), -tc, z(sc)); the longitude depends on the column only,
        // the latitude is atan2(-tc, sqrt(1 + sc^2)).
        for (uint i = 0u; i < params.taps; ++i) {
            float sc = 2.0 * (float(id.x) + (float(i) + 0.5) / taps) / float(n) - 1.0;
            vec3 d = cube_direction(id.z, vec2(0.5 * (sc + 1.0), 0.5));
            float u = atan(d.z, d.x) * inv_two_pi + 0.5;
            float h = sqrt(1.0 + sc * sc);
            for (uint j = 0u; j < params.taps; ++j) {
                float tc = 2.0 * (float(id.y) + (float(j) + 0.5) / taps) / float(n) - 1.0;
                float lat = atan(-tc, h);
                sum += textureLod(equirect, vec2(u, 0.5 - lat / facet_pi), 0.0).rgb;
            }
        }
    }
    vec4 texel = vec4(sum / (taps * taps), 1.0);
    imageStore(cube, ivec3(id), texel);
#ifdef FACET_MIRROR
    imageStore(mirror, ivec3(id), texel);
#endif
}
