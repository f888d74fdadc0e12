#version 460
// The thesis' cheapest irradiance: a trilinear sample of a low level of the environment
// cube in direction n. Exact for a uniform sky; a box-filtered radiance otherwise.
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform samplerCube environment;
layout(binding = 1, rgba32f) uniform writeonly image2DArray irradiance;

layout(push_constant) uniform Params {
    float lod;
} params;

void main() {
    uint n = uint(imageSize(irradiance).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 normal = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    imageStore(irradiance, ivec3(id), vec4(textureLod(environment, normal, params.lod).rgb, 1.0));
}
