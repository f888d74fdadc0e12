#version 460
// The texel list (as cube_texels.comp writes it) made from blocks of equirectangular
// texels directly: each entry's radiance x solid angle is the exact sum over its texels,
// its direction their radiance-weighted mean, its spread a cap of the same mean resultant
// length. The diffuse convolution then sees the input itself, not its resampling to a cube.
#include "ibl/equirect.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform readonly image2D equirect;
layout(std430, binding = 1) writeonly buffer Texels { vec4 texels[]; };  // 2 per entry

layout(push_constant) uniform Params {
    uint block;  // texels per block side
} params;

void main() {
    ivec2 size = imageSize(equirect);
    uvec2 blocks = (uvec2(size) + params.block - 1u) / params.block;
    uvec2 id = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(id, blocks))) return;
    vec3 radiance_solid_angle = vec3(0.0);
    vec3 weighted_direction = vec3(0.0);
    float weight = 0.0, solid_angle_sum = 0.0;
    uvec2 end = min((id + 1u) * params.block, uvec2(size));
    for (uint y = id.y * params.block; y < end.y; ++y) {
        // Solid angle of a texel of row y: (2 pi / W) (sin(theta_top) - sin(theta_bottom)).
        float theta0 = FACET_PI * (0.5 - float(y) / float(size.y));
        float theta1 = FACET_PI * (0.5 - float(y + 1u) / float(size.y));
        float solid_angle = (2.0 * FACET_PI / float(size.x)) * (sin(theta0) - sin(theta1));
        float child_cos = 1.0 - solid_angle / (2.0 * FACET_PI);
        for (uint x = id.x * params.block; x < end.x; ++x) {
            vec3 d = equirect_direction((vec2(x, y) + 0.5) / vec2(size));
            vec3 radiance = imageLoad(equirect, ivec2(x, y)).rgb;
            radiance_solid_angle += radiance * solid_angle;
            float w = (dot(radiance, vec3(0.2126, 0.7152, 0.0722)) + 1e-6) * solid_angle;
            weighted_direction += w * 0.5 * (1.0 + child_cos) * d;
            weight += w;
            solid_angle_sum += solid_angle;
        }
    }
    float mean_length = length(weighted_direction) / weight;
    vec3 direction = normalize(weighted_direction);
    float cos_sigma = clamp(2.0 * mean_length - 1.0, -1.0, 1.0);
    uint index = id.y * blocks.x + id.x;
    texels[2u * index] = vec4(direction, 1.0 - cos_sigma * cos_sigma);
    texels[2u * index + 1u] = vec4(radiance_solid_angle, solid_angle_sum);
}
