#version 460
// The transmission background's mip m from mip m - 1: each texel the mean of its (up to)
// four parents, colour premultiplied by coverage, so that a blurred edge of the opaque scene
// fades into the environment behind it (render/forward.frag: scene + (1 - alpha) environment).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba16f) uniform readonly image2D parent;
layout(binding = 1, rgba16f) uniform writeonly image2D child;

void main() {
    ivec2 size = imageSize(child), parent_size = imageSize(parent);
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(id, size))) return;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) sum += imageLoad(parent, min(id * 2 + ivec2(i, j), parent_size - 1));
    imageStore(child, id, 0.25 * sum);
}
