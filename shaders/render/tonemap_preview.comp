#version 460
// 8-bit preview of a linear HDR image: exposure, Reinhard (x / (1 + x), the thesis'
// operator), then the sRGB transfer function (IEC 61966-2-1).
#include "render/tonemap_operators.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform readonly image2D in_hdr;
layout(binding = 1, rgba8) uniform writeonly image2D out_ldr;

layout(push_constant) uniform Params {
    float exposure;
} params;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(out_ldr)))) return;
    vec3 hdr = max(imageLoad(in_hdr, texel).rgb, vec3(0.0)) * params.exposure;
    vec3 mapped = reinhard(hdr);
    imageStore(out_ldr, texel, vec4(srgb_encode(mapped), 1.0));
}
