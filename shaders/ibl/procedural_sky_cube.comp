#version 460
// builtin:sky straight into the environment cube's level 0: each texel averages 4 x 4
// directions spread over its area, as equirect_to_cube.comp does with bilinear samples of
// the sky's equirect, but of the sky itself: 16 evaluations of the model a texel instead of
// 16 equirect lookups (on lavapipe 26 against 65 ms for 256^2 faces). A second pass
// (FACET_SUN_TEXELS) makes the texels near the sun again with 16 x 16 taps. With FACET_MIRROR
// the same texels also go to `mirror` (specular level 0).
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0, rgba32f) uniform writeonly image2DArray cube;
#ifdef FACET_MIRROR
layout(binding = 1, rgba32f) uniform writeonly image2DArray mirror;
#endif

#include "ibl/procedural_sky.glsl"

#ifdef FACET_SUN_TEXELS
const uint TAPS = 16u;
#else
const uint TAPS = 4u;
#endif

void main() {
    uint n = uint(imageSize(cube).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
#ifdef FACET_SUN_TEXELS
    // The second pass: 16 x 16 taps where the sun's disk may reach the texel (its radius plus
    // two texels, which are at most 2 / n radians across: the cosine of that is the zenith's
    // w here). 4 x 4 taps quantise the disk's coverage of a texel, and so its power, by up to
    // 8% on 64^2 faces. The other texels stop here, and lavapipe's vectors with none near
    // the sun skip the loop.
    vec3 centre = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    if (dot(centre, params.sun_direction_cos_radius.xyz) < params.zenith_radiance.w) return;
#endif
    vec3 sum = vec3(0.0);
    for (uint j = 0u; j < TAPS; ++j) {
        for (uint i = 0u; i < TAPS; ++i) {
            vec2 st = (vec2(id.xy) + (vec2(i, j) + 0.5) / float(TAPS)) / float(n);
            vec3 d = normalize(cube_direction(id.z, st));
            sum += sky_radiance(d, sky_ground(d.y), sky_open(d.y));
        }
    }
    vec4 texel = vec4(sum / float(TAPS * TAPS), 1.0);
    imageStore(cube, ivec3(id), texel);
#ifdef FACET_MIRROR
    imageStore(mirror, ivec3(id), texel);
#endif
}
