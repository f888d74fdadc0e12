#ifndef FACET_BRDF_GLSL
#define FACET_BRDF_GLSL
// The Cook-Torrance terms, once, with the thesis' names. Every pass that shades or
// bakes includes this file. Conventions: alpha = roughness^2 (Burley 2012); k of
// Schlick-GGX is k_direct = (r+1)^2/8 for punctual lights and k_ibl = r^2/2 for
// image-based lighting (Karis 2013), r = roughness.
#include "shared_constants.h"

const float PI = facet_pi;

// Smallest alpha used in D: alpha = 0 would make D a Dirac delta (infinite at NdotH = 1).
const float MIN_ALPHA = 1e-4;

// GGX / Trowbridge-Reitz normal distribution (Walter et al. 2007, eq. 33):
// D = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
float D_GGX(float NdotH, float roughness) {
    float alpha = max(roughness * roughness, MIN_ALPHA);
    float a2 = alpha * alpha;
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

// Schlick's approximation of the Fresnel reflectance (Schlick 1994).
vec3 F_Schlick(float cosTheta, vec3 F0) {
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}

// Fresnel for ambient light on a rough surface: the grazing reflectance is capped at
// max(1 - roughness, F0) (Lagarde's variant used by the thesis for the IBL kd/ks split).
vec3 F_SchlickRoughness(float cosTheta, vec3 F0, float roughness) {
    return F0 + (max(vec3(1.0 - roughness), F0) - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}

float k_direct(float roughness) {
    return (roughness + 1.0) * (roughness + 1.0) / 8.0;
}

float k_ibl(float roughness) {
    return roughness * roughness / 2.0;
}

// Schlick-GGX geometry term for one direction: G1 = n.v / (n.v (1 - k) + k).
// At n.v = 0 and k = 0 the limit is 1 at the boundary; return 0 there (no light).
float G_SchlickGGX(float NdotV, float k) {
    float denominator = NdotV * (1.0 - k) + k;
    return denominator > 0.0 ? NdotV / denominator : 0.0;
}

// Smith's separable shadowing-masking with Schlick-GGX for view and light.
float G_Smith(float NdotV, float NdotL, float k) {
    return G_SchlickGGX(NdotV, k) * G_SchlickGGX(NdotL, k);
}

// Height-correlated Smith visibility V = G / (4 n.l n.v) for GGX, as in the glTF 2.0
// specification (Appendix B; Heitz 2014, eq. 99).
float V_SmithGGXCorrelated(float NdotV, float NdotL, float alpha) {
    float a2 = alpha * alpha;
    float gv = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
    float gl = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
    float denominator = gv + gl;
    return denominator > 0.0 ? 0.5 / denominator : 0.0;
}

#endif
