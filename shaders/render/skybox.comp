#version 460
// The environment seen directly (the thesis' skybox), composited under the resolved
// frame: the forward pass clears to transparent black and its alpha is the coverage
// (opaque geometry) or the "over" alpha (blended geometry), so colour + (1 - alpha) sky
// is the frame over the sky, antialiased edges included. One cube sample per pixel in a
// compute pass costs a small fraction of drawing the sky into every MSAA sample.
#include "render/disk_constants.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform samplerCube environment;
#ifdef FRAME_RGBA16F
layout(binding = 1, rgba16f) uniform image2D frame;  // a host's half-float target
#else
layout(binding = 1, rgba32f) uniform image2D frame;
#endif

layout(push_constant) uniform Sky {
    mat4 inverse_view_projection;  // of the view without translation
    float lod;
    float intensity;
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
    // The lights extracted from the environment (DISK_LIGHTS disks, constants of the
    // pipeline: render/disk_constants.glsl): the sky shows them where the map was filled.
#define FACET_SKY_DISK(i)                                                                                          \
    if (i < DISK_LIGHTS) {                                                                                         \
        FacetDiskLight disk = unpack_disk_light(FACET_DISK_LIGHT_##i);                                             \
        if (dot(direction, disk.direction) >= disk.cos_radius) background += disk.radiance;                        \
    }
    FACET_SKY_DISK(0) FACET_SKY_DISK(1) FACET_SKY_DISK(2) FACET_SKY_DISK(3) FACET_SKY_DISK(4) FACET_SKY_DISK(5)
    FACET_SKY_DISK(6) FACET_SKY_DISK(7) FACET_SKY_DISK(8) FACET_SKY_DISK(9) FACET_SKY_DISK(10) FACET_SKY_DISK(11)
    FACET_SKY_DISK(12) FACET_SKY_DISK(13) FACET_SKY_DISK(14) FACET_SKY_DISK(15)
#undef FACET_SKY_DISK
    background *= sky.intensity;
    float coverage = clamp(color.a, 0.0, 1.0);
    imageStore(frame, p, vec4(color.rgb + (1.0 - coverage) * background, 1.0));
}
