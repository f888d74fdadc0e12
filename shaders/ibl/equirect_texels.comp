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
        float solid_angle = equirect_texel_solid_angle(y, uvec2(size));
        float child_cos = 1.0 - solid_angle / (2.0 * facet_pi);
        for (uint x = id.x * params.block; x < end.x; ++x) {
            vec3 d = equirect_direction((vec2(x, y) + 0.5) / vec2(size));
            vec3 radiance = imageLoad(equirect, ivec2(x, y)).rgb;
            radiance_solid_angle += radiance * solid_angle;
            float w = (facet_luminance(radiance) + 1e-6) * solid_angle;
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
