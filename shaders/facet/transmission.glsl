#ifndef FACET_TRANSMISSION_GLSL
#define FACET_TRANSMISSION_GLSL
// KHR_materials_transmission and KHR_materials_volume (included by facet/shading.glsl).
//
// The extension's dielectric base is mix(diffuse, specular_btdf x baseColor, transmission)
// under the model's Fresnel mix; its BTDF is the specular lobe "sampled along the view
// vector" (thin-walled: two faces back to back, no average refraction): for light along l
// below the surface, the lobe of l mirrored above it, l' = l - 2 (n.l) n, h = normalize(v +
// l'). So the transmitted light is
//     transmission x albedo x kd(v.h) x D V(n.v, |n.l|) x |n.l| x incident,
// kd the model's diffuse weight at v.h (glTF: (1 - specular max3(F_dielectric)) (1 - metallic);
// the thesis: (1 - F)(1 - metallic)), D V the model's specular lobe at the transmission's
// roughness, roughness x clamp(2 ior - 2, 0, 1): microfacet refraction blurs less as the index
// nears 1 (the scaling of the Khronos glTF sample viewer; the lobe of ior 1.5 is the
// extension's alpha = roughness^2).
// Under the environment the same lobe is a split sum: the prefiltered radiance behind the
// surface at the transmission's roughness times the integral of kd D V |n.l|, which the
// model's LUT (A, B) at that roughness gives as (A + B) - w (F0 A + B) (1 - metallic) for
// Schlick's F (facet_transmission_albedo). Behind the surface is the environment along the
// view ray through the exit point, or the opaque scene drawn there (the forward pass's
// transmission background, render/forward.frag).
// KHR_materials_volume: a thickness under the surface refracts the view ray by the index (the
// exit point where the refracted ray has crossed the thickness) and attenuates the
// transmitted light to attenuation_colour^(distance / attenuation_distance) (Beer-Lambert).

// The dielectric's index of refraction from its F0 (the inverse of F0 = ((ior - 1) / (ior + 1))^2).
float facet_ior_from_f0(float f0) {
    float r = sqrt(clamp(f0, 0.0, 0.99));
    return (1.0 + r) / (1.0 - r);
}

// Puts KHR_materials_transmission on the surface: weight 0..1 and the dielectric's index.
void facet_surface_transmission(inout FacetSurface s, float weight, float ior) {
    s.transmission = weight;
    s.transmission_roughness = s.roughness * clamp(2.0 * ior - 2.0, 0.0, 1.0);
}

// l mirrored through the surface's plane.
vec3 facet_mirrored(vec3 n, vec3 l) { return l - 2.0 * dot(n, l) * n; }

// Radiance `incident` along l (unit, below the surface: n.l < 0) transmitted towards v.
vec3 facet_transmit_light(FacetSurface s, vec3 v, float NdotV, vec3 l, vec3 incident, bool punctual) {
    float NdotL = -dot(s.n, l);
    vec3 lm = facet_mirrored(s.n, l);
    vec3 h = normalize(v + lm);
    vec3 F, kd;
    facet_fresnel(s, clamp(dot(v, h), 0.0, 1.0), F, kd);
    FacetSurface t = s;
    t.roughness = s.transmission_roughness;
    float dg = facet_specular_dg(t, NdotV, NdotL, clamp(dot(s.n, h), 0.0, 1.0), punctual);
    return s.transmission * s.albedo * kd * dg * incident * NdotL;
}

// The transmitted lobe's albedo under uniform light behind the surface, from the model's
// LUT value at (n.v, transmission roughness): the integral of kd(v.h) D V |n.l| (Schlick's F:
// the integral of F D V n.l is F0 A + B; kd's F is the largest channel's for glTF, per
// channel for the thesis).
vec3 facet_transmission_albedo(FacetSurface s, vec4 lut) {
    float lobe = lut.x + lut.y;
    if (s.brdf == FACET_BRDF_GLTF) {
        float f0 = facet_max3(s.dielectric_f0);
        return vec3((lobe - s.specular_factor * (f0 * lut.x + lut.y)) * (1.0 - s.metallic));
    }
    return (lobe - s.specular_weight * (s.F0 * lut.x + lut.y)) * (1.0 - s.metallic);
}

// The light a volume of attenuation colour c (rgb) and distance d (0: none) lets through
// along `path` (Beer-Lambert: c^(path / d)).
vec3 facet_volume_transmittance(vec3 c, float d, float path) {
    return d > 0.0 ? pow(max(c, vec3(1e-6)), vec3(path / d)) : vec3(1.0);
}

#endif
