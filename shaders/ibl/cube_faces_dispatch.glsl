#ifndef FACET_CUBE_FACES_DISPATCH_GLSL
#define FACET_CUBE_FACES_DISPATCH_GLSL
// The texel group this invocation makes under dispatch_cube_faces (engine/ibl/
// cube_texel_list.cpp): `texels` texels side by side in x from the returned x, its row y,
// its face z. Where a row holds at least as many groups as the workgroup is wide, the
// workgroups tile the face 8 x 8 as before; where it holds fewer (irradiance at 32^2 with 8
// texels an invocation on a CPU device: 4 groups a row), the workgroup's invocations take
// the face's groups row after row instead, so that no lane of its rows idles (lavapipe runs
// a row of 8 invocations as one SIMD vector). Compute shaders only, included after their
// local size's layout: glslang folds gl_WorkGroupSize where it is read, (1, 1, 1) before it.
uvec3 cube_texel_group(uint n, uint texels) {
    uint columns = (n + texels - 1u) / texels;
    if (columns >= gl_WorkGroupSize.x)
        return uvec3(gl_GlobalInvocationID.x * texels, gl_GlobalInvocationID.y, gl_GlobalInvocationID.z);
    uint index = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * (gl_WorkGroupSize.x * gl_WorkGroupSize.y) +
                 gl_LocalInvocationIndex;
    return uvec3((index % columns) * texels, index / columns, gl_WorkGroupID.z);
}

#endif
