#ifndef FACET_LIST_LANES_GLSL
#define FACET_LIST_LANES_GLSL
// Reading a list from a buffer (a texel list, the excess, the filtered samples) that every
// invocation walks alike. lavapipe reads a buffer lane by lane: an entry all lanes share
// costs a scalar load per lane and component. Where FACET_LIST_LANES is above 1 (a CPU
// device whose subgroups are its SIMD vectors; list_lanes in engine/ibl/cube_texel_list.cpp),
// the subgroup's lanes read gl_SubgroupSize consecutive entries at once, one each, and
// each entry is then broadcast from its lane in turn (an element extract on lavapipe): an
// eighth of the loads, the same sums in the same order. Elsewhere a lane reads every entry
// itself, as before. Every lane of the subgroup must reach the loop (no return before it):
//
//   for (uint base = 0u; base < count; base += LIST_STEP) {
//       vec4 a = list[list_index(base, count)];
//       for (uint j = 0u; j < list_chunk(base, count); ++j) { vec4 entry = list_entry(a, j); ... }
//   }
#ifndef FACET_LIST_LANES
#define FACET_LIST_LANES 1
#endif
#if FACET_LIST_LANES > 1
#extension GL_KHR_shader_subgroup_ballot : require
#define LIST_STEP gl_SubgroupSize
uint list_index(uint base, uint count) { return min(base + gl_SubgroupInvocationID, count - 1u); }
uint list_chunk(uint base, uint count) { return min(gl_SubgroupSize, count - base); }
vec4 list_entry(vec4 lane_value, uint j) { return subgroupBroadcast(lane_value, j); }
#else
#define LIST_STEP 1u
uint list_index(uint base, uint count) { return base; }
uint list_chunk(uint base, uint count) { return 1u; }
vec4 list_entry(vec4 lane_value, uint j) { return lane_value; }
#endif

#endif
