#version 460
// The environment seen directly (the thesis' skybox), composited under the resolved
// frame: the forward pass clears to transparent black and its alpha is the coverage
// (opaque geometry) or the "over" alpha (blended geometry), so colour + (1 - alpha) sky
// is the frame over the sky, antialiased edges included. One cube sample per pixel in a
// compute pass costs a small fraction of drawing the sky into every MSAA sample.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform samplerCube environment;
#ifdef FRAME_RGBA16F
layout(binding = 1, rgba16f) uniform image2D frame;  // a host's half-float target
#else
layout(binding = 1, rgba32f) uniform image2D frame;
#endif
// Lights extracted from the environment (render/forward_interface.glsl's Light, type 3):
// the sky shows them where the map was filled.
struct Disk {
    vec4 position_range;
    vec4 direction_type;
    vec4 color_intensity;
    vec4 cone;
};
layout(binding = 2, std430) readonly buffer Disks { Disk disks[]; };

layout(push_constant) uniform Sky {
    mat4 inverse_view_projection;  // of the view without translation
    float lod;
    float intensity;
    uint disk_count;
} sky;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(frame);
    if (any(greaterThanEqual(p, size))) return;
    vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
    // Reversed Z: depth 0 is infinitely far; a depth just above it is a far point.
    vec4 far = sky.inverse_view_projection * vec4(ndc, 1e-6, 1.0);
    vec3 direction = normalize(far.xyz / far.w);
    vec4 color = imageLoad(frame, p);
    vec3 background = textureLod(environment, direction, sky.lod).rgb;
    for (uint i = 0u; i < sky.disk_count; ++i)
        if (dot(direction, -normalize(disks[i].direction_type.xyz)) >= disks[i].cone.x)
            background += disks[i].color_intensity.rgb * disks[i].color_intensity.a;
    background *= sky.intensity;
    float coverage = clamp(color.a, 0.0, 1.0);
    imageStore(frame, p, vec4(color.rgb + (1.0 - coverage) * background, 1.0));
}
