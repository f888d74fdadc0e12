#version 460
#ifdef FACET_SUBGROUP_REDUCE
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
// The largest value and the number of NaN, Inf and negative values of one level of a
// bake's output, accumulated into range.values[2 * slot] (the largest finite value's
// bits: non-negative floats order like their bits) and [2 * slot + 1] (the count).
// bake_environment decides from them, without reading the texels back, whether the
// output is sound and whether it fits RGBA16F (whose largest value is 65504).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0, rgba32f) uniform readonly image2DArray level;
layout(binding = 1, std430) buffer Range { uint values[]; } range;
layout(push_constant) uniform Params { uint slot; } params;

// Rows per invocation: the reduction below (and its atomics) is paid once per 8 rows of
// texels, not per row (add_output_range_passes dispatches accordingly).
const int ROWS = 8;

#ifndef FACET_SUBGROUP_REDUCE
shared float group_peak[64];
shared uint group_bad[64];
#endif

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(level);
    float peak = 0.0;
    uint bad = 0u;
    if (id.x < size.x && id.z < size.z) {
        int first = (id.y / 8) * 8 * ROWS + id.y % 8;  // rows first, first + 8, ... of the group's band
        for (int r = 0; r < ROWS; ++r) {
            int y = first + 8 * r;
            if (y >= size.y) break;
            vec4 v = imageLoad(level, ivec3(id.x, y, id.z));
            for (int c = 0; c < 4; ++c) {
                bool sound = !isnan(v[c]) && !isinf(v[c]) && v[c] >= 0.0;
                bad += sound ? 0u : 1u;
                if (sound) peak = max(peak, v[c]);
            }
        }
    }
#ifdef FACET_SUBGROUP_REDUCE
    // One atomic per subgroup, not per texel (every invocation gets here: no early return).
    float subgroup_peak = subgroupMax(peak);
    uint subgroup_bad = subgroupAdd(bad);
    if (subgroupElect()) {
        atomicMax(range.values[2u * params.slot], floatBitsToUint(subgroup_peak));
        if (subgroup_bad > 0u) atomicAdd(range.values[2u * params.slot + 1u], subgroup_bad);
    }
#else
    // One atomic per workgroup, not per texel.
    uint i = gl_LocalInvocationIndex;
    group_peak[i] = peak;
    group_bad[i] = bad;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1u) {
        if (i < stride) {
            group_peak[i] = max(group_peak[i], group_peak[i + stride]);
            group_bad[i] += group_bad[i + stride];
        }
        barrier();
    }
    if (i == 0u) {
        atomicMax(range.values[2u * params.slot], floatBitsToUint(group_peak[0]));
        if (group_bad[0] > 0u) atomicAdd(range.values[2u * params.slot + 1u], group_bad[0]);
    }
#endif
}
