#version 460
// One level of a bake's output in RGBA16F (convert_to_half): each value rounded to a half
// by the store. A compute pass, not a blit: lavapipe blits by drawing, which compiles a
// fragment and a vertex shader with LLVM in every process (about 0.1 s on its queue).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0, rgba32f) uniform readonly image2DArray source;
layout(binding = 1, rgba16f) uniform writeonly image2DArray destination;

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(destination);
    if (id.x >= size.x || id.y >= size.y) return;
    imageStore(destination, id, imageLoad(source, id));
}
