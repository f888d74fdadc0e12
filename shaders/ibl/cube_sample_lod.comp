#version 460
// The thesis' cheapest alternatives: a trilinear sample of the environment cube's own mip
// chain in direction n at a given lod, as irradiance (`lowmip`) or as a rough specular
// level (`mips`). Exact for a uniform sky; a box-filtered radiance otherwise.
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform samplerCube environment;
layout(binding = 1, rgba32f) uniform writeonly image2DArray target;

layout(push_constant) uniform Params {
    float lod;
} params;

void main() {
    uint n = uint(imageSize(target).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 normal = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    imageStore(target, ivec3(id), vec4(textureLod(environment, normal, params.lod).rgb, 1.0));
}
