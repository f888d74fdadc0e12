#version 460
// Diffuse irradiance by the thesis' Riemann sum over the hemisphere around n: phi and
// theta in steps of `step` radians, each sample L(w) cos(theta) sin(theta) from the
// cube's level 0. Midpoints of the steps, normalised by the sum of cos sin weights so
// that a uniform sky gives exactly its radiance (the sum of weights tends to pi / step^2).
#include "facet/shared_constants.h"
#include "ibl/cube.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform samplerCube environment;
layout(binding = 1, rgba32f) uniform writeonly image2DArray irradiance;

layout(push_constant) uniform Params {
    float step;
} params;

void main() {
    uint n = uint(imageSize(irradiance).x);
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= n || id.y >= n) return;
    vec3 normal = normalize(cube_direction(id.z, (vec2(id.xy) + 0.5) / float(n)));
    vec3 up = abs(normal.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 right = normalize(cross(up, normal));
    up = cross(normal, right);
    int phi_steps = max(1, int(round(2.0 * facet_pi / params.step)));
    int theta_steps = max(1, int(round(0.5 * facet_pi / params.step)));
    float dphi = 2.0 * facet_pi / float(phi_steps), dtheta = 0.5 * facet_pi / float(theta_steps);
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (int p = 0; p < phi_steps; ++p) {
        float phi = (float(p) + 0.5) * dphi;
        for (int t = 0; t < theta_steps; ++t) {
            float theta = (float(t) + 0.5) * dtheta;
            vec3 tangent = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
            vec3 w = tangent.x * right + tangent.y * up + tangent.z * normal;
            float weight = cos(theta) * sin(theta);
            sum += textureLod(environment, w, 0.0).rgb * weight;
            weight_sum += weight;
        }
    }
    imageStore(irradiance, ivec3(id), vec4(sum / weight_sum, 1.0));
}
