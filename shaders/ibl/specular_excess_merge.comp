#version 460
// Coarser excess blocks for a rougher level (specular_hybrid.comp): each the sum of
// factor x factor blocks of a finer grid of the input's blocks (excess radiance x solid
// angle, and the luminance-weighted direction, both unnormalised, so sums stay exact).
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Fine { vec4 fine[]; };
layout(std430, binding = 1) writeonly buffer Coarse { vec4 coarse[]; };

layout(push_constant) uniform Params {
    uvec2 fine_size;  // blocks per row and column of the fine grid
    uint factor;
} params;

void main() {
    uvec2 size = (params.fine_size + params.factor - 1u) / params.factor;
    uvec2 id = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(id, size))) return;
    vec3 direction = vec3(0.0), excess = vec3(0.0);
    float flag = 0.0;
    uvec2 end = min((id + 1u) * params.factor, params.fine_size);
    for (uint y = id.y * params.factor; y < end.y; ++y)
        for (uint x = id.x * params.factor; x < end.x; ++x) {
            uint i = y * params.fine_size.x + x;
            direction += fine[2u * i].xyz;
            excess += fine[2u * i + 1u].rgb;
            flag = max(flag, fine[2u * i + 1u].w);
        }
    uint index = id.y * size.x + id.x;
    coarse[2u * index] = vec4(direction, 0.0);
    coarse[2u * index + 1u] = vec4(excess, length(direction) > 0.0 ? flag : 0.0);
}
