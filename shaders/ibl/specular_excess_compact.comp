#version 460
// The blocks with an excess (specular_excess.comp), in block order, packed at the front of
// the list: list.count, then 2 vec4 per entry (the direction normalised). One workgroup; each invocation takes a
// contiguous run of blocks, so the order (and every later sum) is the same on every run.
layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;
layout(std430, binding = 0) readonly buffer Blocks { vec4 blocks[]; };
layout(std430, binding = 1) writeonly buffer List {
    uint count;
    uint pad0, pad1, pad2;
    vec4 entries[];
} list;

layout(push_constant) uniform Params { uint block_count; } params;

shared uint offsets[256];

void main() {
    uint i = gl_LocalInvocationIndex;
    uint per = (params.block_count + 255u) / 256u;
    uint begin = min(i * per, params.block_count), end = min(begin + per, params.block_count);
    uint mine = 0u;
    for (uint b = begin; b < end; ++b) mine += blocks[2u * b + 1u].w > 0.0 ? 1u : 0u;
    offsets[i] = mine;
    barrier();
    // Inclusive prefix sum (Hillis-Steele).
    for (uint step = 1u; step < 256u; step *= 2u) {
        uint add = i >= step ? offsets[i - step] : 0u;
        barrier();
        offsets[i] += add;
        barrier();
    }
    uint out_index = offsets[i] - mine;
    for (uint b = begin; b < end; ++b) {
        if (blocks[2u * b + 1u].w > 0.0) {
            list.entries[2u * out_index] = vec4(normalize(blocks[2u * b].xyz), 0.0);
            list.entries[2u * out_index + 1u] = blocks[2u * b + 1u];
            ++out_index;
        }
    }
    if (i == 255u) list.count = offsets[255];
}
