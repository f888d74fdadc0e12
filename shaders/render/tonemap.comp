#version 460
// HDR -> display: exposure, one of the tone mapping operators, then gamma.
// Operators: 0 none (clamp), 1 Reinhard x / (1 + x) and 2 exposure 1 - exp(-x) (the
// thesis' two), 3 ACES (Narkowicz 2015 fit), 4 Khronos PBR Neutral (Khronos 2024).
// Gamma 0 means the sRGB transfer function (IEC 61966-2-1), else x^(1/gamma).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D hdr_image;
layout(binding = 1, rgba8) uniform writeonly image2D ldr_image;

layout(push_constant) uniform Params {
    float exposure;
    uint tonemap;
    float gamma;
} params;

vec3 aces_narkowicz(vec3 x) {
    x *= 0.6;  // the fit is made for this pre-exposure (Narkowicz's note)
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 khronos_pbr_neutral(vec3 color) {
    const float start_compression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(color.r, min(color.g, color.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    color -= offset;
    float peak = max(color.r, max(color.g, color.b));
    if (peak < start_compression) return color;
    const float d = 1.0 - start_compression;
    float new_peak = 1.0 - d * d / (peak + d - start_compression);
    color *= new_peak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(color, vec3(new_peak), g);
}

vec3 srgb_encode(vec3 linear) {
    vec3 low = linear * 12.92;
    vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
    return mix(low, high, greaterThan(linear, vec3(0.0031308)));
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(ldr_image)))) return;
    vec4 hdr = texelFetch(hdr_image, texel, 0);
    vec3 x = max(hdr.rgb, vec3(0.0)) * params.exposure;
    vec3 mapped;
    switch (params.tonemap) {
    case 1u: mapped = x / (1.0 + x); break;
    case 2u: mapped = 1.0 - exp(-x); break;
    case 3u: mapped = aces_narkowicz(x); break;
    case 4u: mapped = khronos_pbr_neutral(x); break;
    default: mapped = x; break;
    }
    mapped = clamp(mapped, 0.0, 1.0);
    vec3 encoded = params.gamma > 0.0 ? pow(mapped, vec3(1.0 / params.gamma)) : srgb_encode(mapped);
    imageStore(ldr_image, texel, vec4(encoded, clamp(hdr.a, 0.0, 1.0)));
}
