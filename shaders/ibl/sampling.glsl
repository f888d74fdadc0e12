#ifndef FACET_SAMPLING_GLSL
#define FACET_SAMPLING_GLSL
// Low-discrepancy sequences and GGX importance sampling (the thesis' "Specular IBL"
// chapter; Karis 2013; Walter et al. 2007, eq. 35-36).
#include "facet/brdf.glsl"

// Van der Corput radical inverse in base 2 (bit reversal).
float radical_inverse_vdc(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10;  // / 2^32
}

vec2 hammersley(uint i, uint n) {
    return vec2((float(i) + 0.5) / float(n), radical_inverse_vdc(i));
}

// Half vector in tangent space (z = normal) distributed by D(h) (n.h), alpha = roughness^2.
vec3 importance_sample_ggx_tangent(vec2 xi, float roughness) {
    float alpha = max(roughness * roughness, MIN_ALPHA);
    float phi = 2.0 * PI * xi.y;
    float cos_theta = sqrt((1.0 - xi.x) / (1.0 + (alpha * alpha - 1.0) * xi.x));
    float sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    return vec3(cos(phi) * sin_theta, sin(phi) * sin_theta, cos_theta);
}

// Density over solid angle of l = reflect(-v, h) for h drawn by
// importance_sample_ggx_tangent: D(h) (n.h) / (4 v.h) (Walter et al. 2007, eq. 14 and 38).
float ggx_sample_pdf(float NdotH, float VdotH, float roughness) {
    return D_GGX(NdotH, roughness) * NdotH / max(4.0 * VdotH, 1e-8);
}

#endif
