#version 460
// HDR -> display: exposure, one of the tone mapping operators, then gamma.
// Operators: 0 none (clamp), 1 Reinhard x / (1 + x) and 2 exposure 1 - exp(-x) (the
// thesis' two), 3 ACES (Narkowicz 2015 fit), 4 Khronos PBR Neutral (Khronos 2024).
// Gamma 0 means the sRGB transfer function (IEC 61966-2-1), else x^(1/gamma).
#include "render/tonemap_operators.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D hdr_image;
layout(binding = 1, rgba8) uniform writeonly image2D ldr_image;

layout(push_constant) uniform Params {
    float exposure;
    uint tonemap;
    float gamma;
} params;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(ldr_image)))) return;
    vec4 hdr = texelFetch(hdr_image, texel, 0);
    vec3 x = max(hdr.rgb, vec3(0.0)) * params.exposure;
    vec3 mapped;
    switch (params.tonemap) {
    case 1u: mapped = reinhard(x); break;
    case 2u: mapped = 1.0 - exp(-x); break;
    case 3u: mapped = aces_narkowicz(x); break;
    case 4u: mapped = khronos_pbr_neutral(x); break;
    default: mapped = x; break;
    }
    mapped = clamp(mapped, 0.0, 1.0);
    vec3 encoded = params.gamma > 0.0 ? pow(mapped, vec3(1.0 / params.gamma)) : srgb_encode(mapped);
    imageStore(ldr_image, texel, vec4(encoded, clamp(hdr.a, 0.0, 1.0)));
}
