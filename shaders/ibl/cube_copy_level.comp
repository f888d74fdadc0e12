#version 460
// Specular level 0 (roughness 0, a mirror) is the environment itself: a copy. With a
// different face size it is a trilinear resample of the matching environment level.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0, rgba32f) uniform readonly image2DArray source;
layout(binding = 1, rgba32f) uniform writeonly image2DArray destination;

void main() {
    uvec3 id = gl_GlobalInvocationID;
    uint n = uint(imageSize(destination).x);
    if (id.x >= n || id.y >= n) return;
    imageStore(destination, ivec3(id), imageLoad(source, ivec3(id)));
}
