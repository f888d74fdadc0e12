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

void main() {
    uint n = uint(imageSize(cube).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 sum = vec3(0.0);
    float taps = float(params.taps);
    for (uint j = 0u; j < params.taps; ++j) {
        for (uint i = 0u; i < params.taps; ++i) {
            vec2 st = (vec2(id.xy) + (vec2(i, j) + 0.5) / taps) / float(n);
            vec3 d = normalize(cube_direction(id.z, st));
            sum += textureLod(equirect, equirect_uv(d), 0.0).rgb;
        }
    }
    vec4 texel = vec4(sum / (taps * taps), 1.0);
    imageStore(cube, ivec3(id), texel);
#ifdef FACET_MIRROR
    imageStore(mirror, ivec3(id), texel);
#endif
}
