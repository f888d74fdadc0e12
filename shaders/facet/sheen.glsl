#ifndef FACET_SHEEN_GLSL
#define FACET_SHEEN_GLSL
// KHR_materials_sheen: a layer of fibres over the material (under a clear coat), included by
// facet/shading.glsl after FacetSurface. Shaded only where FACET_SHEEN is defined before
// shading.glsl is included (render/forward.frag's variants of materials with a sheen).
// The extension's BRDF (its "Implementation Notes"):
//   f = f_sheen + f_base x s,  f_sheen = sheenColor D V,
//   D = (2 + 1 / alpha) sin(theta_h)^(1 / alpha) / (2 pi), alpha = sheenRoughness^2 ("Charlie":
//       Conty Estevez and Kulla 2017, "Production Friendly Microfacet Sheen BRDF", SIGGRAPH
//       course "Physically Based Shading in Theory and Practice"),
//   V = 1 / ((1 + Lambda(n.v) + Lambda(n.l)) 4 (n.v) (n.l)), the same paper's visibility with
//       its fitted Lambda (the extension's lambdaSheen; not Neubelt and Pettineo's / Ashikhmin's
//       1 / (4 (n.l + n.v - n.l n.v)), which the extension names as the cheaper choice),
//   s = min(1 - max3(sheenColor) E(n.v), 1 - max3(sheenColor) E(n.l)), the albedo scaling, with
//       E the lobe's directional albedo (facet/sheen_albedo.glsl, fitted), taken at most 1
//       (the fitted Lambda's lobe reflects more than it receives at grazing views for
//       sheenRoughness below about 0.25: E(n.v 0.05, r 0.1) = 1.03, E(0.01, 0.2) = 1.16; the
//       tables the extension points to store E in [0, 1]).
// The environment (facet_environment_sheen) scales the specular lobe by the extension's
// simplified scaling for image-based light, 1 - max3(sheenColor) E(n.v), the diffuse lobe by
// the min form's cosine-weighted mean (exact for a Lambertian base under uniform light), and
// takes the sheen's light as E(n.v) times the irradiance cube's E / pi along n (exact under
// uniform light; measured against the truth in tests/gpu/brdf_models_truth_test.cpp).
#include "sheen_albedo.glsl"

// Puts KHR_materials_sheen's layer on the surface: its colour (linear, 0..1; black: none) and
// roughness 0..1.
void facet_surface_sheen(inout FacetSurface s, vec3 colour, float roughness) {
    s.sheen_color = colour;
    s.sheen_roughness = roughness;
}

float facet_sheen_alpha(float roughness) { return max(roughness * roughness, 1e-6); }

// The Charlie distribution D(n.h).
float facet_sheen_d(float NdotH, float roughness) {
    float inv_alpha = 1.0 / facet_sheen_alpha(roughness);
    float sin2h = max(1.0 - NdotH * NdotH, 0.0);
    return (2.0 + inv_alpha) * pow(sin2h, 0.5 * inv_alpha) / (2.0 * PI);
}

// The extension's lambdaSheen: Conty Estevez and Kulla's fit of Lambda, exp(l(cos)) below 0.5
// and exp(2 l(0.5) - l(1 - cos)) above, its coefficients mixed by (1 - alpha)^2.
float facet_sheen_l(float x, float alpha) {
    float t = (1.0 - alpha) * (1.0 - alpha);
    float a = mix(21.5473, 25.3245, t), b = mix(3.82987, 3.32435, t), c = mix(0.19823, 0.16801, t);
    float d = mix(-1.97760, -1.27393, t), e = mix(-4.32054, -4.85967, t);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}

float facet_sheen_lambda(float cos_theta, float alpha) {
    return cos_theta < 0.5 ? exp(facet_sheen_l(cos_theta, alpha))
                           : exp(2.0 * facet_sheen_l(0.5, alpha) - facet_sheen_l(1.0 - cos_theta, alpha));
}

// V = 1 / ((1 + Lambda(n.v) + Lambda(n.l)) 4 n.v n.l).
float facet_sheen_v(float NdotV, float NdotL, float roughness) {
    float alpha = facet_sheen_alpha(roughness);
    NdotV = max(NdotV, 1e-4);
    NdotL = max(NdotL, 1e-4);
    return 1.0 / ((1.0 + facet_sheen_lambda(NdotV, alpha) + facet_sheen_lambda(NdotL, alpha)) * 4.0 * NdotV * NdotL);
}

// A fit of facet/sheen_albedo.glsl (ROWS: FACET_SHEEN_ROWS or FACET_SHEEN_MEAN_ROWS) at
// n.x (from 0.001, where the rows were fitted) and roughness: the exponent's coefficients
// blended linearly in roughness between the two rows about it (one exp; below the first row
// the value fades linearly to 0 at roughness 0).
#define FACET_SHEEN_FIT(ROWS, NdotX, roughness, result)                                        \
    {                                                                                          \
        float s_ = sqrt(clamp(NdotX, 1e-3, 1.0));                                              \
        float y_ = clamp(roughness, 0.0, 1.0) * FACET_SHEEN_ALBEDO_ROWS;                       \
        float weights_ = 0.0;                                                                  \
        vec3 low_ = vec3(0.0), high_ = vec3(0.0); /* c0 c1 c2, c3 c4 c5 */                     \
        ROWS                                                                                   \
        float exponent_ = low_.x + s_ * (low_.y + s_ * (low_.z + s_ * (high_.x + s_ * (high_.y + s_ * high_.z)))); \
        result = weights_ * exp(exponent_ / max(weights_, 1e-6));                              \
    }
#define FACET_SHEEN_ROW(j, c0, c1, c2, c3, c4, c5)                                             \
    {                                                                                          \
        float w_ = max(1.0 - abs(y_ - float(j)), 0.0);                                         \
        low_ += w_ * vec3(c0, c1, c2);                                                         \
        high_ += w_ * vec3(c3, c4, c5);                                                        \
        weights_ += w_;                                                                        \
    }

// E(n.x, roughness), the sheen lobe's directional albedo.
float facet_sheen_albedo(float NdotX, float roughness) {
    float e;
    FACET_SHEEN_FIT(FACET_SHEEN_ROWS, NdotX, roughness, e)
    return e;
}

// M(n.v, roughness): the cosine-weighted mean over n.l of min(1, max(E(n.v), E(n.l))), what
// the albedo scaling takes from a Lambertian base under uniform light.
float facet_sheen_mean_albedo(float NdotV, float roughness) {
    float m;
    FACET_SHEEN_FIT(FACET_SHEEN_MEAN_ROWS, NdotV, roughness, m)
    return m;
}
#undef FACET_SHEEN_ROW
#undef FACET_SHEEN_FIT

// 1 - max3(sheenColor) min(E(n.x), 1): the share of the material below left at n.x.
float facet_sheen_scaling(FacetSurface s, float NdotX) {
    return 1.0 - facet_max3(s.sheen_color) * min(facet_sheen_albedo(NdotX, s.sheen_roughness), 1.0);
}

// Radiance `incident` along l (unit, towards the light): `diffuse` and `specular` (the
// material below, facet_reflect_light's) scaled by the albedo scaling at v and l, and the
// sheen's f_sheen (n.l) x incident returned (zero below the horizon).
vec3 facet_sheen_light(FacetSurface s, vec3 v, float NdotV, vec3 l, vec3 incident, inout vec3 diffuse,
                       inout vec3 specular) {
    float NdotL = dot(s.n, l);
    // (Light from below the surface, which only a transmission lets through: the view's side.)
    float scaling = NdotL > 0.0 ? min(facet_sheen_scaling(s, NdotV), facet_sheen_scaling(s, NdotL))
                                : facet_sheen_scaling(s, NdotV);
    diffuse *= scaling;
    specular *= scaling;
    if (NdotL <= 0.0) return vec3(0.0);
    vec3 h = normalize(v + l);
    float lobe = facet_sheen_d(clamp(dot(s.n, h), 0.0, 1.0), s.sheen_roughness) *
                 facet_sheen_v(NdotV, NdotL, s.sheen_roughness) * NdotL;
    return s.sheen_color * lobe * incident;
}

// The environment: `specular` (facet_environment_light's, for the same surface) scaled by
// 1 - max3(sheenColor) E(n.v) (its lobe gathers light near R, where n.l is about n.v), and
// `diffuse` by 1 - max3(sheenColor) M(n.v), the min form's mean over the cosine lobe (the
// simplified scaling at n.v alone left a white Lambertian sheen up to 13% above the truth in
// the white furnace at n.v 0.2); the sheen's light returned: sheenColor E(n.v) times
// `irradiance` (E / pi along n, times the intensity) and the occlusion.
vec3 facet_environment_sheen(FacetSurface s, float NdotV, vec3 irradiance, inout vec3 diffuse, inout vec3 specular) {
    specular *= facet_sheen_scaling(s, NdotV);
    diffuse *= 1.0 - facet_max3(s.sheen_color) * facet_sheen_mean_albedo(NdotV, s.sheen_roughness);
    return s.sheen_color * facet_sheen_albedo(NdotV, s.sheen_roughness) * irradiance * s.occlusion;
}

#endif
