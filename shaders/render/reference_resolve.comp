#version 460
// The reference frame from its accumulated sums: mean radiance per pixel, alpha = the
// surface's coverage (so the skybox pass can composite the environment behind it).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform readonly image2D accumulation;
layout(binding = 1) uniform sampler2D normal_view;
layout(binding = 2, rgba32f) uniform writeonly image2D frame;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(frame)))) return;
    vec4 acc = imageLoad(accumulation, p);
    float coverage = texelFetch(normal_view, p, 0).a >= 0.5 ? 1.0 : 0.0;
    imageStore(frame, p, vec4(acc.a > 0.0 ? acc.rgb / acc.a : vec3(0.0), coverage));
}
