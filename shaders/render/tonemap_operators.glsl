#ifndef FACET_TONEMAP_OPERATORS_GLSL
#define FACET_TONEMAP_OPERATORS_GLSL
// The tone mapping operators and the display encoding, once, for the tonemap pass
// (render/tonemap.comp) and the bake's 8-bit previews (render/tonemap_preview.comp).

// Reinhard x / (1 + x), the thesis' operator.
vec3 reinhard(vec3 x) {
    return x / (1.0 + x);
}

// ACES filmic, Narkowicz 2015's fit of the reference rendering transform.
vec3 aces_narkowicz(vec3 x) {
    x *= 0.6;  // the fit is made for this pre-exposure (Narkowicz's note)
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// Khronos PBR Neutral (Khronos 2024): linear below the compression start, hue kept.
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

// The sRGB transfer function (IEC 61966-2-1), linear -> encoded.
vec3 srgb_encode(vec3 linear) {
    vec3 low = linear * 12.92;
    vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
    return mix(low, high, greaterThan(linear, vec3(0.0031308)));
}

#endif
