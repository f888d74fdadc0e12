#ifndef FACET_SHADING_GLSL
#define FACET_SHADING_GLSL
// Shading with Facet's baked environment and lights: the functions the forward pass
// (render/forward.frag) shades with, installed (share/facet/shaders/facet/) so that a host
// engine's own material shaders can call them: #include "facet/shading.glsl" with
// share/facet/shaders on the include path. Every function takes its textures and values as
// parameters, never a global binding, so a host passes its own.
//
// Two BRDF models (design.md, "BRDF models"), chosen per surface (FacetSurface.brdf):
// - FACET_BRDF_GLTF: glTF 2.0 appendix B: GGX D, height-correlated Smith visibility,
//   dielectric = fresnel_mix(F0 0.04, Lambert, specular) with Schlick F on v.h, metal =
//   conductor_fresnel(baseColor, specular), mixed by metalness.
// - FACET_BRDF_THESIS: the thesis' Cook-Torrance (Junakovic, "Fizikalno temeljen model
//   ostvarivanja prikaza", Zagreb 2019): GGX D, Schlick F on h.v, Smith with Schlick-GGX
//   (k = (r+1)^2/8 for punctual lights, r^2/2 for the environment), Lambert diffuse with
//   kd = (1 - F)(1 - metallic), F0 = mix(0.04, albedo, metallic).
// The environment is the split sum (Karis 2013): irradiance (E / pi) for the diffuse part,
// the prefiltered cube at lod = roughness x (levels - 1) times the model's LUT (A, B) for
// the specular part, the diffuse weighted by the cosine-weighted mean Fresnel (the LUT's
// fourth channel). Each composition exists here once: diffuse + specular for a light from
// one direction (facet_reflect_light), for a disk (facet_disk_light), for the environment
// (facet_environment_light).
#include "brdf.glsl"

const uint FACET_BRDF_GLTF = 0u;
const uint FACET_BRDF_THESIS = 1u;

// What the shading needs of a surface point (facet_surface fills the derived terms).
struct FacetSurface {
    uint brdf;              // FACET_BRDF_GLTF or FACET_BRDF_THESIS
    vec3 n;                 // unit shading normal, world space
    vec3 albedo;            // linear base colour
    float metallic;         // 0..1
    float roughness;        // perceptual, 0..1; alpha = roughness^2
    vec3 F0;                // reflectance at normal incidence, mix(dielectric F0, albedo, metallic)
    float specular_weight;  // the specular factor for the dielectric part, mixed to 1 for metals
    vec3 dielectric_f0;     // the dielectric part's F0 (0.04 for ior 1.5; coloured: facet_surface_specular_color)
    float specular_factor;  // KHR_materials_specular's factor for the dielectric part (1: none)
    float occlusion;        // ambient occlusion, 0..1: scales environment and disk lights only
    // KHR_materials_clearcoat (facet_surface_clearcoat): a clear layer of ior 1.5 over the
    // surface, weight 0 (none) .. 1, with its own roughness and normal.
    float clearcoat;
    float clearcoat_roughness;
    vec3 clearcoat_n;
    // KHR_materials_iridescence (facet_surface_iridescence): a thin dielectric film on the
    // surface, weight 0 (none) .. 1, its index of refraction and thickness in nanometres.
    // Shaded only where FACET_IRIDESCENCE is defined before this file is included (its
    // Fresnel costs every pixel, film or not, where the GPU runs both sides of a branch).
    float iridescence;
    float iridescence_ior;
    float iridescence_thickness;
    // KHR_materials_anisotropy (facet_surface_anisotropy): strength 0 (none) .. 1 and the
    // unit direction of the stretch in the surface's plane. Shaded only where
    // FACET_ANISOTROPY is defined before this file is included.
    float anisotropy;
    vec3 anisotropy_t;
    // KHR_materials_sheen (facet/sheen.glsl): its colour (black: none) and roughness.
    vec3 sheen_color;
    float sheen_roughness;
    // KHR_materials_transmission (facet/transmission.glsl): the share of the dielectric
    // base's light transmitted (0: none) and the transmitted lobe's perceptual roughness.
    // Shaded only where FACET_TRANSMISSION is defined before this file is included.
    float transmission;
    float transmission_roughness;
};

// glTF's metallic-roughness material under the model `brdf`.
FacetSurface facet_surface(uint brdf, vec3 n, vec3 albedo, float metallic, float roughness, float dielectric_f0,
                           float specular_factor, float occlusion) {
    FacetSurface s;
    s.brdf = brdf;
    s.n = n;
    s.albedo = albedo;
    s.metallic = metallic;
    s.roughness = roughness;
    s.F0 = mix(vec3(dielectric_f0), albedo, metallic);
    s.specular_weight = mix(specular_factor, 1.0, metallic);
    s.dielectric_f0 = vec3(dielectric_f0);
    s.specular_factor = specular_factor;
    s.occlusion = occlusion;
    s.clearcoat = 0.0;
    s.clearcoat_roughness = 0.0;
    s.clearcoat_n = n;
    s.iridescence = 0.0;
    s.iridescence_ior = 1.3;
    s.iridescence_thickness = 0.0;
    s.anisotropy = 0.0;
    s.anisotropy_t = vec3(1.0, 0.0, 0.0);
    s.sheen_color = vec3(0.0);
    s.sheen_roughness = 0.0;
    s.transmission = 0.0;
    s.transmission_roughness = 0.0;
    return s;
}

// KHR_materials_specular's specularColorFactor: the dielectric F0 per channel,
// min(F0 x colour, 1) (call after facet_surface).
void facet_surface_specular_color(inout FacetSurface s, vec3 colour) {
    s.dielectric_f0 = min(s.dielectric_f0 * colour, vec3(1.0));
    s.F0 = mix(s.dielectric_f0, s.albedo, s.metallic);
}

float facet_max3(vec3 x) { return max(max(x.r, x.g), x.b); }

#include "sheen.glsl"

// Puts KHR_materials_clearcoat's layer over the surface: weight 0..1, perceptual roughness,
// unit normal (the surface's where the layer has no normal map). The extension's BRDF:
// f = (1 - weight Fc(v.h)) f_surface + weight Fc(v.h) D V of the layer, Fc Schlick's with
// F0 0.04; the layer's D V is the surface's model's specular lobe (design.md).
void facet_surface_clearcoat(inout FacetSurface s, float weight, float roughness, vec3 n) {
    s.clearcoat = weight;
    s.clearcoat_roughness = roughness;
    s.clearcoat_n = n;
}

// The clear layer as a surface of its own: a dielectric of F0 0.04 with no diffuse lobe.
FacetSurface facet_clearcoat_layer(FacetSurface s) {
    FacetSurface c = facet_surface(s.brdf, s.clearcoat_n, vec3(0.0), 0.0, s.clearcoat_roughness, 0.04, 1.0, s.occlusion);
    return c;
}

// The layer's weight x Fresnel at v.h: what it reflects, and what the surface below loses.
float facet_clearcoat_fresnel(FacetSurface s, float VdotH) {
    float x = clamp(1.0 - VdotH, 0.0, 1.0), x2 = x * x;
    return s.clearcoat * (0.04 + 0.96 * x2 * x2 * x);
}

// Puts KHR_materials_anisotropy on the surface: strength 0..1 and the direction of the
// stretch (any vector not along n: its part in the surface's plane is taken, normalised).
void facet_surface_anisotropy(inout FacetSurface s, float strength, vec3 direction) {
    vec3 t = direction - s.n * dot(s.n, direction);
    float len2 = dot(t, t);
    s.anisotropy = len2 > 1e-12 ? strength : 0.0;
    s.anisotropy_t = len2 > 1e-12 ? t * inversesqrt(len2) : vec3(1.0, 0.0, 0.0);
}

// The anisotropic lobe's D V (glTF model: the extension's anisotropic GGX with
// alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha, and its height-correlated Smith
// visibility) or D G / (4 n.l n.v) (the thesis' model: the anisotropic D with the thesis'
// isotropic Schlick-GGX G), for unit l, v and h = normalize(l + v).
// facet_anisotropic_dg with the lobe's widths given: alpha_t along t, alpha_b along b.
float facet_anisotropic_dg(FacetSurface s, vec3 v, vec3 l, vec3 h, float NdotV, float NdotL, bool punctual, float at,
                           float ab) {
    vec3 t = s.anisotropy_t, b = cross(s.n, t);
    float a2 = at * ab;
    vec3 f = vec3(ab * dot(t, h), at * dot(b, h), a2 * clamp(dot(s.n, h), 0.0, 1.0));
    float w2 = a2 / max(dot(f, f), 1e-30);
    float D = a2 * w2 * w2 / PI;
    if (s.brdf == FACET_BRDF_GLTF) {
        float gv = NdotL * length(vec3(at * dot(t, v), ab * dot(b, v), NdotV));
        float gl = NdotV * length(vec3(at * dot(t, l), ab * dot(b, l), NdotL));
        return D * 0.5 / max(gv + gl, 1e-30);
    }
    float k = punctual ? k_direct(s.roughness) : k_ibl(s.roughness);
    return D * G_Smith(NdotV, NdotL, k) / max(4.0 * NdotV * NdotL, 1e-8);
}

float facet_anisotropic_dg(FacetSurface s, vec3 v, vec3 l, vec3 h, float NdotV, float NdotL, bool punctual) {
    float alpha = max(s.roughness * s.roughness, MIN_ALPHA);
    return facet_anisotropic_dg(s, v, l, h, NdotV, NdotL, punctual, mix(alpha, 1.0, s.anisotropy * s.anisotropy), alpha);
}

// The perceptual roughness whose isotropic lobe masks the view as the stretched one does:
// alpha along v's azimuth, sqrt(alpha_t^2 cos^2 phi + alpha_b^2 sin^2 phi) (Smith's masking
// of an anisotropic GGX is the isotropic one at that alpha). The glTF model's LUT read at it
// follows the stretched lobe's albedo (the thesis' G is isotropic: its albedo is the round
// lobe's); 1 for a view along n.
float facet_anisotropic_view_roughness(FacetSurface s, vec3 v) {
    float alpha = max(s.roughness * s.roughness, MIN_ALPHA);
    float at = mix(alpha, 1.0, s.anisotropy * s.anisotropy);
    float x = dot(s.anisotropy_t, v), y = dot(cross(s.n, s.anisotropy_t), v);
    float r2 = x * x + y * y;
    float a = r2 > 1e-12 ? sqrt((at * at * x * x + alpha * alpha * y * y) / r2) : alpha;
    return sqrt(a);
}

// Puts KHR_materials_iridescence's thin film on the surface: weight 0..1, the film's index
// of refraction and its thickness in nanometres.
void facet_surface_iridescence(inout FacetSurface s, float weight, float ior, float thickness_nm) {
    s.iridescence = weight;
    s.iridescence_ior = ior;
    s.iridescence_thickness = thickness_nm;
}

// The colour an interference term of optical path difference `opd_nm` and phase `shift`
// adds, integrated against the eye's sensitivity in Fourier space and taken from XYZ to
// linear Rec. 709: KHR_materials_iridescence's Gaussian fits of the CIE 1931 matching
// functions (Belcour and Barla 2017, "A Practical Extension to Microfacet Theory for the
// Modeling of Varying Iridescence", section 4).
vec3 facet_film_sensitivity(float opd_nm, vec3 shift) {
    float phase = 2.0 * PI * opd_nm * 1.0e-9;
    const vec3 amplitude = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
    const vec3 position = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
    const vec3 variance = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
    vec3 xyz = amplitude * sqrt(2.0 * PI * variance) * cos(position * phase + shift) * exp(-phase * phase * variance);
    xyz.x += 9.7470e-14 * sqrt(2.0 * PI * 4.5282e+09) * cos(2.2399e+06 * phase + shift.x) *
             exp(-4.5282e+09 * phase * phase);
    xyz /= 1.0685e-7;
    const mat3 xyz_to_rec709 = mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259,
                                    -0.4985314, 0.0415560, 1.0572252);
    return xyz_to_rec709 * xyz;
}

// The reflectance of a thin film of index `film_ior` and thickness `thickness_nm` between a
// medium of index `outside_ior` (air 1, a clear coat 1.5) and a base of normal-incidence
// reflectance base_f0, for light arriving at cos1 to the microfacet: the extension's
// F_iridescence (Belcour and Barla 2017 with Schlick's approximation at both interfaces and
// two interference orders). The film fades into the outside medium below 30 nm (no film, no
// interference).
vec3 facet_iridescence_fresnel(float outside_ior, float film_ior, float cos1, float thickness_nm, vec3 base_f0) {
    float film = mix(outside_ior, film_ior, smoothstep(0.0, 30.0, thickness_nm));
    float eta = outside_ior / film;
    float cos2_sq = 1.0 - eta * eta * (1.0 - cos1 * cos1);
    if (cos2_sq <= 0.0) return vec3(1.0);  // total internal reflection in the film
    float cos2 = sqrt(cos2_sq);
    // First interface (outside -> film) and its phase shift on reflection.
    float r0 = (film - outside_ior) / (film + outside_ior);
    r0 *= r0;
    float x1 = 1.0 - clamp(cos1, 0.0, 1.0);
    float R12 = r0 + (1.0 - r0) * x1 * x1 * x1 * x1 * x1, T121 = 1.0 - R12;
    float phi21 = film < outside_ior ? 0.0 : PI;  // pi - phi12
    // Second interface (film -> base), the base's index from its F0 (no extinction).
    vec3 sqrt_f0 = sqrt(clamp(base_f0, 0.0, 0.9999));
    vec3 base_ior = (1.0 + sqrt_f0) / (1.0 - sqrt_f0);
    vec3 r1 = (base_ior - film) / (base_ior + film);
    r1 *= r1;
    float x2 = 1.0 - cos2;
    vec3 R23 = r1 + (1.0 - r1) * x2 * x2 * x2 * x2 * x2;
    vec3 phi = vec3(phi21) + vec3(lessThan(base_ior, vec3(film))) * PI;
    float opd = 2.0 * film * thickness_nm * cos2;
    // The series of inter-reflections: the mean term, then two orders of interference.
    vec3 R123 = clamp(R12 * R23, 1e-5, 0.9999);
    vec3 r123 = sqrt(R123);
    vec3 Rs = T121 * T121 * R23 / (1.0 - R123);
    vec3 I = R12 + Rs;
    vec3 Cm = Rs - T121;
    for (int m = 1; m <= 2; ++m) {
        Cm *= r123;
        I += Cm * 2.0 * facet_film_sensitivity(float(m) * opd, float(m) * phi);
    }
    return max(I, vec3(0.0));
}

// The index of the medium over the film: a clear coat's 1.5, else air.
float facet_film_outside_ior(FacetSurface s) { return s.clearcoat > 0.0 ? 1.5 : 1.0; }

// The Fresnel term of the specular lobe and the diffuse lobe's weight at v.h.
// glTF: mix(specular x F(0.04), F(baseColor), metallic) and (1 - specular x F(0.04))
// (1 - metallic); thesis: F(F0) (the specular weight scaling it) and (1 - F)(1 - metallic).
// KHR_materials_iridescence (with FACET_IRIDESCENCE): each Schlick term mixed with the
// film's F_iridescence over the same base F0 by the film's weight.
void facet_fresnel(FacetSurface s, float VdotH, out vec3 F, out vec3 kd) {
    float x = clamp(1.0 - VdotH, 0.0, 1.0), x2 = x * x, w = x2 * x2 * x;  // (1 - v.h)^5
    if (s.brdf == FACET_BRDF_GLTF) {
        // KHR_materials_specular: F per channel, the diffuse lobe keeps 1 - its largest.
        vec3 Fd = s.dielectric_f0 + (1.0 - s.dielectric_f0) * w;
        vec3 Fm = s.albedo + (1.0 - s.albedo) * w;
#ifdef FACET_IRIDESCENCE
        if (s.iridescence > 0.0) {
            float outside = facet_film_outside_ior(s);
            Fd = mix(Fd, facet_iridescence_fresnel(outside, s.iridescence_ior, VdotH, s.iridescence_thickness,
                                                   s.dielectric_f0), s.iridescence);
            Fm = mix(Fm, facet_iridescence_fresnel(outside, s.iridescence_ior, VdotH, s.iridescence_thickness, s.albedo),
                     s.iridescence);
        }
#endif
        Fd *= s.specular_factor;
        F = mix(Fd, Fm, s.metallic);
        kd = vec3((1.0 - facet_max3(Fd)) * (1.0 - s.metallic));
    } else {
        F = s.F0 + (1.0 - s.F0) * w;
#ifdef FACET_IRIDESCENCE
        if (s.iridescence > 0.0)
            F = mix(F, facet_iridescence_fresnel(facet_film_outside_ior(s), s.iridescence_ior, VdotH,
                                                 s.iridescence_thickness, s.F0), s.iridescence);
#endif
        F *= s.specular_weight;
        kd = (1.0 - F) * (1.0 - s.metallic);
    }
}

// The specular term without F, D G / (4 n.l n.v): glTF's height-correlated visibility,
// or the thesis' Schlick-GGX with k_direct (punctual lights) or k_ibl (the environment).
float facet_specular_dg(FacetSurface s, float NdotV, float NdotL, float NdotH, bool punctual) {
    float D = D_GGX(NdotH, s.roughness);
    if (s.brdf == FACET_BRDF_GLTF)
        return D * V_SmithGGXCorrelated(NdotV, NdotL, max(s.roughness * s.roughness, MIN_ALPHA));
    float k = punctual ? k_direct(s.roughness) : k_ibl(s.roughness);
    return D * G_Smith(NdotV, NdotL, k) / max(4.0 * NdotV * NdotL, 1e-8);
}

// The Smith masking-shadowing term G of the model (the G view).
float facet_geometry(FacetSurface s, float NdotV, float NdotL, bool punctual) {
    if (s.brdf == FACET_BRDF_GLTF)
        return 4.0 * NdotV * NdotL * V_SmithGGXCorrelated(NdotV, NdotL, max(s.roughness * s.roughness, MIN_ALPHA));
    return G_Smith(NdotV, NdotL, punctual ? k_direct(s.roughness) : k_ibl(s.roughness));
}

#include "transmission.glsl"

// Radiance `incident` arriving along l (unit, towards the light) reflected towards v:
// diffuse = kd albedo / pi * incident * n.l and specular = F D G / (4 n.l n.v) * incident
// * n.l. Zero when l is below the surface. NdotV = clamp(n.v, 0, 1). `punctual` selects
// the thesis' k for punctual lights (the glTF model has one visibility term).
// A sheen (FACET_SHEEN, facet/sheen.glsl) scales both and adds its lobe to the specular.
// A clear coat (facet_surface_clearcoat) dims both by 1 - weight Fc(v.h) and adds its own
// lobe to the specular, with its normal's n.l.
// A transmission (FACET_TRANSMISSION, facet/transmission.glsl) scales the diffuse lobe by
// 1 - transmission and, for l below the surface, returns the light it transmits as `diffuse`
// (the base layer's light; its h, for the clear coat, that of l mirrored above the surface).
void facet_reflect_light(FacetSurface s, vec3 v, float NdotV, vec3 l, vec3 incident, bool punctual,
                         out vec3 diffuse, out vec3 specular) {
    diffuse = vec3(0.0);
    specular = vec3(0.0);
    float NdotL = dot(s.n, l);
    float coat_NdotL = s.clearcoat > 0.0 ? dot(s.clearcoat_n, l) : 0.0;
#ifdef FACET_TRANSMISSION
    bool through = NdotL < 0.0 && s.transmission > 0.0;
#else
    const bool through = false;
#endif
    if (NdotL <= 0.0 && coat_NdotL <= 0.0 && !through) return;
    vec3 h = normalize(v + l);
#ifdef FACET_TRANSMISSION
    if (through) {
        diffuse = facet_transmit_light(s, v, NdotV, l, incident, punctual);
        h = normalize(v + facet_mirrored(s.n, l));
    }
#endif
    float VdotH = clamp(dot(h, v), 0.0, 1.0);
    if (NdotL > 0.0) {
        vec3 F, kd;
        facet_fresnel(s, VdotH, F, kd);
        diffuse = kd * s.albedo / PI * incident * NdotL;
#ifdef FACET_TRANSMISSION
        diffuse *= 1.0 - s.transmission;
#endif
        float dg = facet_specular_dg(s, NdotV, NdotL, clamp(dot(s.n, h), 0.0, 1.0), punctual);
#ifdef FACET_ANISOTROPY
        if (s.anisotropy > 0.0) dg = facet_anisotropic_dg(s, v, l, h, NdotV, NdotL, punctual);
#endif
        specular = F * dg * incident * NdotL;
    }
#ifdef FACET_SHEEN
    vec3 sheen = facet_sheen_light(s, v, NdotV, l, incident, diffuse, specular);  // under the clear coat
    specular += sheen;
#endif
    if (s.clearcoat > 0.0) {
        float coat = facet_clearcoat_fresnel(s, VdotH);
        diffuse *= 1.0 - coat;
        specular *= 1.0 - coat;
        if (coat_NdotL > 0.0) {
            FacetSurface c = facet_clearcoat_layer(s);
            float coat_NdotV = clamp(dot(c.n, v), 0.0, 1.0);
            specular += coat * facet_specular_dg(c, coat_NdotV, coat_NdotL, clamp(dot(c.n, h), 0.0, 1.0), punctual) *
                        incident * coat_NdotL;
        }
    }
}

// Unit vectors t and b that make (t, b, n) a right-handed orthonormal frame around the
// unit vector n (any rotation about n; +Y is crossed with n unless n is nearly +-Y).
void facet_tangent_frame(vec3 n, out vec3 t, out vec3 b) {
    vec3 up = abs(n.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    t = normalize(cross(up, n));
    b = cross(n, t);
}

// Punctual lights (KHR_lights_punctual).
const uint FACET_LIGHT_DIRECTIONAL = 0u;
const uint FACET_LIGHT_POINT = 1u;
const uint FACET_LIGHT_SPOT = 2u;

struct FacetPunctualLight {
    uint type;          // FACET_LIGHT_*
    vec3 position;      // world space, metres (point, spot)
    float range_m;      // distance where the light ends (point, spot); 0: infinite
    vec3 direction;     // the direction the light travels (directional, spot); normalised here
    vec3 intensity;     // colour x intensity: lux (directional) or candela (point, spot)
    float cone_scale;   // spot: 1 / (cos inner - cos outer)
    float cone_offset;  // spot: -cos outer x cone_scale
};

// Incoming radiance scale at p and the direction l towards the light: inverse-square
// falloff windowed by the range, (1 - (d / range)^4) clamped, and the smooth spot cone,
// squared, as the KHR_lights_punctual specification recommends.
vec3 facet_punctual_incidence(FacetPunctualLight light, vec3 p, out vec3 l) {
    if (light.type == FACET_LIGHT_DIRECTIONAL) {
        l = -normalize(light.direction);
        return light.intensity;
    }
    vec3 to_light = light.position - p;
    float d2 = max(dot(to_light, to_light), 1e-8);
    l = to_light * inversesqrt(d2);
    float attenuation = 1.0 / d2;
    if (light.range_m > 0.0) {
        float ratio = d2 / (light.range_m * light.range_m);
        attenuation *= clamp(1.0 - ratio * ratio, 0.0, 1.0);
    }
    if (light.type == FACET_LIGHT_SPOT) {
        float cd = dot(normalize(light.direction), -l);
        float cone = clamp(cd * light.cone_scale + light.cone_offset, 0.0, 1.0);
        attenuation *= cone * cone;
    }
    return light.intensity * attenuation;
}

// The split sum's LUT at (n.v, roughness), made for the surface's model: scale A, bias B,
// the average albedo E_avg (multiple scattering) and the cosine-weighted mean of
// (1 - v.h)^5 over the hemisphere (the diffuse lobe's Fresnel).
vec4 facet_brdf_lut(sampler2D lut, float NdotV, float roughness) {
    return texture(lut, vec2(NdotV, roughness));
}

// The specular lobe's directional albedo (the split sum's second factor) and the diffuse
// lobe's mean weight under uniform light, from the LUT.
void facet_lut_albedo(FacetSurface s, vec4 lut, out vec3 E, out vec3 kd) {
    if (s.brdf == FACET_BRDF_GLTF) {
        vec3 Ed = s.specular_factor * (s.dielectric_f0 * lut.x + lut.y);
        E = mix(Ed, s.albedo * lut.x + lut.y, s.metallic);
        // The largest channel's Fresnel is the largest F0's at every angle: its mean is exact.
        float f0 = facet_max3(s.dielectric_f0);
        float Fd = s.specular_factor * (f0 + (1.0 - f0) * lut.w);
        kd = vec3((1.0 - Fd) * (1.0 - s.metallic));
    } else {
        E = s.specular_weight * (s.F0 * lut.x + lut.y);
        kd = (1.0 - s.specular_weight * (s.F0 + (1.0 - s.F0) * lut.w)) * (1.0 - s.metallic);
    }
}

// The same seen at NdotV: with FACET_IRIDESCENCE, a film's F_iridescence at n.v stands in
// for each F0 as the Schlick F0 that gives it there, (F - (1 - n.v)^5) / (1 - (1 - n.v)^5),
// mixed by the film's weight (the split sum cannot follow F over the lobe: measured against
// the truth in tests/gpu/brdf_models_truth_test.cpp).
void facet_lut_albedo(FacetSurface s, float NdotV, vec4 lut, out vec3 E, out vec3 kd) {
#ifdef FACET_IRIDESCENCE
    if (s.iridescence > 0.0) {
        float x = 1.0 - clamp(NdotV, 0.0, 1.0), w = min(x * x * x * x * x, 0.9999);
        float outside = facet_film_outside_ior(s);
        vec3 Fd = facet_iridescence_fresnel(outside, s.iridescence_ior, NdotV, s.iridescence_thickness,
                                            s.brdf == FACET_BRDF_GLTF ? s.dielectric_f0 : s.F0);
        vec3 d = clamp((Fd - w) / (1.0 - w), 0.0, 1.0);
        if (s.brdf == FACET_BRDF_GLTF) {
            vec3 Fm = facet_iridescence_fresnel(outside, s.iridescence_ior, NdotV, s.iridescence_thickness, s.albedo);
            s.dielectric_f0 = mix(s.dielectric_f0, d, s.iridescence);
            // The metal's F0 here (a copy: not the diffuse's albedo).
            s.albedo = mix(s.albedo, clamp((Fm - w) / (1.0 - w), 0.0, 1.0), s.iridescence);
        } else {
            s.F0 = mix(s.F0, d, s.iridescence);
        }
    }
#endif
    facet_lut_albedo(s, lut, E, kd);
}

// The prefiltered cube holds roughness level / (levels - 1) at each level. (Blending two
// levels with weights linear in alpha^2 instead, to match the lobe's width, measured worse
// against the truth under every shared environment: 6.7-25% where this lod gives 5.8-22%.)
float facet_specular_lod(float roughness, float specular_levels) {
    return roughness * (specular_levels - 1.0);
}

// Multiple scattering for lights: single scattering loses 1 - E(mu) of the energy for
// F0 = 1 (E = A + B); the lobe is scaled by 1 + F0 (1 / E - 1) (Turquin 2019). Multiply a
// light's specular by it.
vec3 facet_multiscatter_light_energy(vec3 F0, vec4 lut) {
    return 1.0 + F0 * (1.0 / max(lut.x + lut.y, 1e-3) - 1.0);
}

// A bright region taken out of the environment before the bake (light extraction): a cap
// of angular radius theta around a direction with uniform radiance inside.
struct FacetDiskLight {
    vec3 direction;        // unit, from the surface towards the cap's centre
    float cos_radius;      // cos theta
    float angular_radius;  // theta, radians
    float sin_radius;      // sin theta
    float solid_angle;     // 2 pi (1 - cos theta), steradians
    float inv_chord2;      // 1 / (2 - 2 cos theta), the squared chord of the radius
    float inv_diameter;    // 1 / (2 sin theta)
    vec3 radiance;
};

// The cap of angular radius theta (radians) around the unit vector `direction`.
FacetDiskLight facet_make_disk_light(vec3 direction, float theta, vec3 radiance) {
    FacetDiskLight d;
    d.direction = direction;
    d.cos_radius = cos(theta);
    d.angular_radius = theta;
    d.sin_radius = sin(theta);
    float half_chord = sin(0.5 * theta);  // 2 - 2 cos theta = 4 sin^2(theta / 2), exact for small caps too
    d.solid_angle = 4.0 * PI * half_chord * half_chord;
    d.inv_chord2 = 1.0 / max(4.0 * half_chord * half_chord, 1e-12);
    d.inv_diameter = 1.0 / max(2.0 * d.sin_radius, 1e-8);
    d.radiance = radiance;
    return d;
}

// The share of GGX's projected normal distribution D(h) (n.h) over a disk of radius r at
// distance d from the origin of slope space, for alpha = 1 (pass d^2 / alpha^2 and
// r^2 / alpha^2: GGX is that distribution stretched by alpha). For alpha = 1 it is the
// cosine-weighted hemisphere, so the share is the form factor of a disk parallel to the
// plane (Howell, "A Catalog of Radiation Heat Transfer Configuration Factors", B-13):
// (1 - (1 + d^2 - r^2) / sqrt((1 + (d-r)^2)(1 + (d+r)^2))) / 2, written here without
// the cancellation where the disk is small or far: the same as 2 r^2 / (s (s + t)).
float facet_ggx_disk_share(float d2, float r2) {
    float t = 1.0 + d2 - r2;
    float s = sqrt(max(t * t + 4.0 * r2, 1e-30));  // (1 + (d-r)^2)(1 + (d+r)^2) = t^2 + 4 r^2
    // One division: 2 r^2 / (s (s + t)) where t > 0, (s - t) / (2 s) = (1 - t / s) / 2 elsewhere.
    return (t > 0.0 ? 2.0 * r2 : s - t) / (t > 0.0 ? s * (s + t) : 2.0 * s);
}

// The share of a disk's area on one side of a chord at distance (1 - 2x) radii from its
// centre, x in [0, 1]: the circular segment's area, 16 / (3 pi) x^1.5 (1 - x / 3) for
// x <= 1/2 (within 0.5% of the exact (acos(1 - 2x) - (1 - 2x) sqrt(1 - (1 - 2x)^2)) / pi,
// and exactly 1/2 at x = 1/2), mirrored above.
float facet_segment_share(float x) {
    float y = min(x, 1.0 - x);
    float f = 1.6976527 * y * sqrt(y) * (1.0 - y / 3.0);
    return x <= 0.5 ? f : 1.0 - f;
}

// The cap's irradiance at a surface of normal n, over its radiance: pi sin^2(theta) (n.c)
// above the horizon (exact); where the horizon cuts it, the cap taken as a flat disk of
// radius rho = sin theta whose points rise by n.c = e above the horizon at its centre: the
// integral of the height over the visible segment, e pi rho^2 (segment share) + 2/3 (rho^2 -
// e^2)^1.5 (within 1-4% of the sum over the cap). Caps under 2 degrees (suns, lamps) are
// taken as points at the horizon, which then cuts them within their radius alone.
float facet_disk_irradiance(vec3 n, FacetDiskLight disk) {
    float sin_theta = disk.sin_radius, NdotC = dot(n, disk.direction);
    bool wide = sin_theta > 0.035;
    float cut = clamp(NdotC + sin_theta, 0.0, 2.0 * sin_theta);
    float segment = facet_segment_share(cut * disk.inv_diameter);
    float chord = max(sin_theta * sin_theta - NdotC * NdotC, 0.0);
    return NdotC >= sin_theta || !wide
               ? PI * sin_theta * sin_theta * max(NdotC, 0.0)
               : max(NdotC * PI * sin_theta * sin_theta * segment + 2.0 / 3.0 * chord * sqrt(chord), 0.0);
}

// The model's visibility G / (4 n.l n.v) for a cap's light (the environment's k for the
// thesis' model), as a quotient for the caller to fold into its one division.
void facet_disk_visibility(FacetSurface s, float NdotV, float NdotL, float a2, out float numerator,
                           out float denominator) {
    if (s.brdf == FACET_BRDF_GLTF) {
        // V_SmithGGXCorrelated
        float gv = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
        float gl = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
        numerator = gv + gl > 0.0 ? 0.5 : 0.0;
        denominator = max(gv + gl, 1e-30);
    } else {
        // G_Smith(k_ibl) / (4 n.l n.v): Schlick-GGX's n.v and n.l cancel,
        // 1 / (4 (n.v (1 - k) + k) (n.l (1 - k) + k)).
        float k = k_ibl(s.roughness);
        numerator = NdotV > 0.0 ? 1.0 : 0.0;
        denominator = max(4.0 * (NdotV * (1.0 - k) + k) * (NdotL * (1.0 - k) + k), 1e-30);
    }
}

// The cap shaded with the full BRDF (the environment's k for the thesis' model) in closed
// form, the same arithmetic for every lobe and cap: a loop over directions in the cap costs
// every pixel its longest trip on SIMD hardware (lavapipe runs both sides of every branch
// too), and this is a fifth of the 8-32-direction sums it replaced under a studio's wide
// softboxes, at the same accuracy.
// - diffuse: the cap's irradiance (exact above the horizon, within 1-4% where the horizon
//   cuts it) times the diffuse BRDF;
// - specular: the integral over the cap of F D V (n.l) taken as F V (n.l) 4 (v.h) / (n.h),
//   at the cap's centre, times the share of GGX's projected normals whose reflection falls
//   in the cap (facet_ggx_disk_share). The cap's image in slope space is taken as a disk
//   of the same area, Omega / (4 (v.h) (n.h)^3); its distance from the lobe's axis is the
//   centre's slope, or, where the lobe is narrower than the image and R near the cap, R's
//   angular distance from the centre in units of the cap's radius (which keeps the edge
//   where the cap's is), blended by r^2 / (r^2 + alpha^2 + (r x R's distance outside)^2).
//   A cap the horizon cuts is replaced by the cap between the horizon and its top,
//   carrying the visible segment's solid angle.
// Against brute-force sums over the cap (n.v 0.3-1, caps of 3-11 degrees, roughness
// 0.2-0.8, a random half of them near R), the integral's mean error is 0.1-2% where R is
// near the cap and 0.2-9% (mostly under 4%) in the tails; the final image under the shared
// environments is as close to the truth as with the sums (docs/accuracy.md).
// Occlusion not applied. facet_disk_lobe gives the parts: the cap's irradiance, and the
// specular integral without F (returned), with the cap's centre c, its half vector h and
// v.h. Per disk it works on three dot products (n.c, v.c, n.v) and needs three divisions:
// on lavapipe every division and square root costs every lane, and a studio has eight caps.
float facet_disk_lobe(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk, out float irradiance, out vec3 c,
                      out vec3 h, out float VdotH) {
    c = disk.direction;
    float sin_theta = disk.sin_radius, omega = disk.solid_angle;
    float NdotC = dot(s.n, c), VdotC = dot(v, c), nv = dot(s.n, v);
    // The cap's irradiance: facet_disk_irradiance. Caps under 2 degrees are points at the
    // horizon; where the disk is a constant of the pipeline (the forward pass) this choice
    // costs nothing, and the small cap's shading skips the horizon's arithmetic.
    bool wide = sin_theta > 0.035;
    float cut = clamp(NdotC + sin_theta, 0.0, 2.0 * sin_theta);
    float segment = facet_segment_share(cut * disk.inv_diameter);
    irradiance = facet_disk_irradiance(s.n, disk);
    // A cap the horizon cuts: its visible part stands in as the cap between the horizon and
    // the cap's top, carrying the visible segment's solid angle. Its centre, c - (n.c) n
    // (of length sqrt(1 - (n.c)^2)) turned up to the height sin_new, is needed only through
    // its dot products (cn = n.c, cv = v.c).
    float scale = wide || NdotC > 0.0 ? 1.0 : 0.0, inv_chord2 = disk.inv_chord2;
    float cn = NdotC, cv = VdotC, inv_omega = 1.0 / omega;
    if (wide && NdotC < sin_theta) {
        float sin_new = 0.5 * cut, cos_new = sqrt(max(1.0 - sin_new * sin_new, 0.0));
        float along = cos_new * inversesqrt(max(1.0 - NdotC * NdotC, 1e-12));
        c = (c - NdotC * s.n) * along + s.n * sin_new;
        cn = sin_new;
        cv = (VdotC - NdotC * nv) * along + nv * sin_new;
        // The squared chord 2 - 2 cos = 2 sin^2 / (1 + cos) (without the cancellation) and
        // its inverse, from one division.
        float sin2 = 2.0 * sin_new * sin_new, cos1 = 1.0 + cos_new;
        float reciprocal = 1.0 / max(sin2 * cos1, 1e-30);
        float chord2 = sin2 * sin2 * reciprocal;
        inv_chord2 = min(cos1 * cos1 * reciprocal, 1e12);
        scale = omega * segment * inv_chord2 / PI;  // the segment's solid angle over the new cap's, pi chord2
        omega = PI * chord2;
        inv_omega = inv_chord2 / PI;
    }
    // The centre's half vector: the slope of the cap's image, F and the diffuse weight.
    // |v + c|^2 = 2 + 2 v.c.
    float inv_length = inversesqrt(max(2.0 + 2.0 * cv, 1e-12));
    h = (v + c) * inv_length;
    VdotH = clamp((1.0 + cv) * inv_length, 1e-4, 1.0);
    float NdotH = clamp((nv + cn) * inv_length, 1e-4, 1.0);
    float alpha = max(s.roughness * s.roughness, MIN_ALPHA), a2 = alpha * alpha, inv_a2 = 1.0 / a2;
    // R's distance from the cap in radii (1 at the edge; R.c = 2 (n.v)(n.c) - v.c), and the
    // weight of the near view: the lobe narrower than the cap's image and R not far outside it,
    // r^2 / (r^2 + alpha^2 + (r x outside)^2) with r^2 = Omega q / (4 pi),
    // q = 1 / ((v.h) (n.h)^3). q and the weight from one division.
    float reach2 = (2.0 - 2.0 * (2.0 * nv * cn - cv)) * inv_chord2;
    float outside = max(sqrt(reach2) - 1.0, 0.0);
    float slope = VdotH * NdotH * NdotH * NdotH;  // 1 / q
    float rest = 1.0 + outside * outside + a2 * 4.0 * PI * inv_omega * slope;  // 1 / near
    float reciprocal = 1.0 / (slope * rest);
    float q = rest * reciprocal, near = slope * reciprocal;
    float r2 = omega / (4.0 * PI) * q;                        // Omega / (4 (v.h) (n.h)^3)
    float centre_d2 = (1.0 - NdotH * NdotH) * VdotH * NdotH * q;  // tan^2 of h's angle from n
    // The share (facet_ggx_disk_share) and the model's visibility G / (4 n.l n.v) at the
    // centre, each a quotient, from one division.
    float d2 = mix(centre_d2, r2 * reach2, near) * inv_a2, rr2 = r2 * inv_a2;
    float t = 1.0 + d2 - rr2;
    float root = sqrt(max(t * t + 4.0 * rr2, 1e-30));
    float share_numerator = t > 0.0 ? 2.0 * rr2 : root - t, share_denominator = t > 0.0 ? root * (root + t) : 2.0 * root;
    float NdotL = max(cn, 1e-4);
    float visibility_numerator, visibility_denominator;
    facet_disk_visibility(s, NdotV, NdotL, a2, visibility_numerator, visibility_denominator);
    // 4 (v.h) / (n.h) = 4 (v.h)^2 (n.h)^2 q.
    return visibility_numerator * share_numerator / (visibility_denominator * share_denominator) * NdotL * 4.0 *
           VdotH * VdotH * NdotH * NdotH * q * scale;
}

float facet_disk_lobe(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk, out float irradiance, out vec3 c,
                      out vec3 h) {
    float VdotH;
    return facet_disk_lobe(s, v, NdotV, disk, irradiance, c, h, VdotH);
}

// facet_disk_lobe for a lobe much wider than the cap (GGX's alpha at least 3 times the cap's
// angular radius where the forward pass uses it, render/lobe_disks.h): the cap as a point at
// its centre whose n.l times solid angle is the cap's irradiance over its radiance
// (facet_disk_irradiance, which keeps the horizon's cut soft), D V (n.l) Omega, corrected to
// second order for D's curvature across the cap. Against sums over caps of 3 and 11 degrees
// it is as close as the closed form (1.3% overall where R is in or near the cap, the closed
// form 1.6%; tests/gpu/shading_include_test.cpp) at about half its arithmetic: one division
// and a square root per cap, and the horizon's.
float facet_disk_point_lobe(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk, out float irradiance, out vec3 c,
                            out vec3 h, out float VdotH) {
    c = disk.direction;
    float NdotC = dot(s.n, c), VdotC = dot(v, c);
    irradiance = facet_disk_irradiance(s.n, disk);
    float inv_length = inversesqrt(max(2.0 + 2.0 * VdotC, 1e-12));
    h = (v + c) * inv_length;
    VdotH = clamp((1.0 + VdotC) * inv_length, 1e-4, 1.0);
    float NdotH = clamp((dot(s.n, v) + NdotC) * inv_length, 0.0, 1.0);
    float alpha = max(s.roughness * s.roughness, MIN_ALPHA), a2 = alpha * alpha;
    float NdotL = max(NdotC, 1e-4);
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;  // D = a2 / (pi d^2)
    float visibility_numerator, visibility_denominator;
    facet_disk_visibility(s, NdotV, NdotL, a2, visibility_numerator, visibility_denominator);
    // D's curvature across the cap (second order): GGX in slope space is f(u) = (1 + u)^-2
    // with u = |m|^2 / alpha^2, and its mean over a disk of radius r there is f + r^2 / 8
    // times its Laplacian, f (1 + (r^2 / alpha^2) (2 u - 1) / (1 + u)^2). With r^2 =
    // Omega / (4 pi (v.h) (n.h)^3), the cap's image as a disk of the same area (as in
    // facet_disk_lobe), and 1 + u = d / (alpha^2 (n.h)^2), the factor is
    // 1 + Omega (2 (1 - (n.h)^2) - alpha^2 (n.h)^2) / (4 pi (v.h) (n.h) d^2).
    // Its departure from 1 is at most r^2 / alpha^2 = 1 / (4 k^2 (v.h)(n.h)^3) for a cap k
    // times narrower than the lobe (2.8% seen from above for k = 3). The expansion holds while
    // the cap's image is small against its distance from the lobe's axis; where h nears the
    // horizon (n.v and n.l near 0) it does not, and the factor is kept within 2/3 and 4/3.
    float nh = max(NdotH, 1e-4);
    float spread = disk.solid_angle * (2.0 * (1.0 - nh * nh) - a2 * nh * nh);
    float curvature = max(4.0 * PI * VdotH * nh * d * d, 3.0 * abs(spread));
    return a2 * visibility_numerator * irradiance * (curvature + spread) /
           (PI * d * d * visibility_denominator * curvature);
}

// The cap's diffuse and specular (facet_disk_lobe, or facet_disk_point_lobe where `point`),
// occlusion not applied. A bake of Facet's
// with lights extracted holds their light in its irradiance cube (ibl/ibl_bake.h,
// SpecularSplit): a host shading its disks next to that cube adds their specular alone, or
// takes facet_disk_irradiance out of the cube's value where it adds their diffuse
// (render/forward.frag does so for sheen and iridescent surfaces).
void facet_disk_light(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk, bool point, out vec3 diffuse,
                      out vec3 specular) {
    float irradiance, VdotH, lobe;
    vec3 c, h;
    if (point)
        lobe = facet_disk_point_lobe(s, v, NdotV, disk, irradiance, c, h, VdotH);
    else
        lobe = facet_disk_lobe(s, v, NdotV, disk, irradiance, c, h, VdotH);
    vec3 F, kd;
    facet_fresnel(s, VdotH, F, kd);
    diffuse = kd * s.albedo * (irradiance / PI) * disk.radiance;
#ifdef FACET_TRANSMISSION
    diffuse *= 1.0 - s.transmission;
#endif
    specular = F * lobe * disk.radiance;
#ifdef FACET_ANISOTROPY
    // KHR_materials_anisotropy: the closed form above (isotropic) times the ratio of the
    // stretched lobe to the round one at the cap's centre, both widened by the cap's radius
    // (its slope variance added to each width's square): the point ratio for small caps,
    // 1 where the cap is wider than either lobe.
    if (s.anisotropy > 0.0) {
        float alpha = max(s.roughness * s.roughness, MIN_ALPHA), a2 = alpha * alpha;
        float NdotL = max(dot(s.n, c), 1e-4), r2 = disk.sin_radius * disk.sin_radius;
        float at = mix(alpha, 1.0, s.anisotropy * s.anisotropy);
        float stretched = facet_anisotropic_dg(s, v, c, h, NdotV, NdotL, false, sqrt(at * at + r2), sqrt(a2 + r2));
        float round = facet_anisotropic_dg(s, v, c, h, NdotV, NdotL, false, sqrt(a2 + r2), sqrt(a2 + r2));
        specular *= stretched / max(round, 1e-30);
    }
#endif
}

void facet_disk_light(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk, out vec3 diffuse, out vec3 specular) {
    facet_disk_light(s, v, NdotV, disk, false, diffuse, specular);
}

// The light a disk below the surface transmits (FACET_TRANSMISSION, facet/transmission.glsl):
// the closed form of the disk mirrored above the surface with the transmitted lobe, kd(v.h)
// in place of F, times transmission x albedo (the base layer's light, like the diffuse).
// Zero for caps above the surface. Occlusion not applied.
vec3 facet_disk_transmission(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk) {
    FacetDiskLight m = disk;
    m.direction = facet_mirrored(s.n, disk.direction);
    FacetSurface t = s;
    t.roughness = s.transmission_roughness;
    float irradiance;
    vec3 c, h;
    float VdotH;
    float lobe = facet_disk_lobe(t, v, NdotV, m, irradiance, c, h, VdotH);
    vec3 F, kd;
    facet_fresnel(s, VdotH, F, kd);
    return s.transmission * s.albedo * kd * lobe * disk.radiance;
}

// KHR_materials_clearcoat's layer under a disk: `below`, the factor that dims the surface's
// own terms of the disk (facet_disk_light's: 1 - weight Fc(v.h) at the cap's centre), and
// the layer's specular (facet_disk_light's closed form, the layer as the surface). 1 and 0
// without a layer.
void facet_disk_clearcoat(FacetSurface s, vec3 v, FacetDiskLight disk, out float below, out vec3 specular) {
    below = 1.0;
    specular = vec3(0.0);
    if (s.clearcoat <= 0.0) return;
    vec3 h = v + disk.direction;
    h *= inversesqrt(max(dot(h, h), 1e-12));
    below = 1.0 - facet_clearcoat_fresnel(s, clamp(dot(v, h), 0.0, 1.0));
    FacetSurface c = facet_clearcoat_layer(s);
    vec3 none;
    facet_disk_light(c, v, clamp(dot(c.n, v), 0.0, 1.0), disk, none, specular);
    specular *= s.clearcoat;  // facet_disk_light's F is the layer's Fc
}

// The lookups of the prefiltered cube that stand for the specular lobe. One along R at the
// surface's roughness (the split sum as Karis wrote it), or, `fitted`, three fitted to the
// true lobe D V (n.l) (specular_lobes.glsl, scripts/fit_specular_lobes.py): at n.v < 1 the
// lobe leans towards n and stretches in the plane of n and v, which one lookup of a kernel
// symmetric about R cannot follow. The fit's L1 distance to the lobe is 2-10 times smaller
// than one lookup's along R at n.v 0.1-0.9, roughness 0.2-1.
struct FacetSpecularLookups {
    vec3 direction[3];
    float lod[3];
    float weight[3];
};

// The fitted table's two texels at table coordinates x (n.v column) and y (roughness row),
// each in [0, 8], interpolated linearly by the sampler (include/facet/render/specular_lobes.h):
// (t0, t1, t2, w0) and (r0, r1, r2, w1).
void facet_lobe_entries(sampler2D lobe_table, uint brdf, float x, float y, out vec4 directions, out vec4 widths) {
    float v = (float(brdf) * 9.0 + 0.5 + y) / 18.0;
    directions = textureLod(lobe_table, vec2((0.5 + x) / 27.0, v), 0.0);
    widths = textureLod(lobe_table, vec2((9.5 + x) / 27.0, v), 0.0);
}

// The table's column coordinate x at n.v: n.v 0.1 .. 0.9 by 0.1, clamped (the lookups meet at
// R = n as n.v -> 1).
float facet_lobe_column(float NdotV) { return clamp((NdotV - 0.1) * 10.0, 0.0, 8.0); }

// The table's row coordinate y at a roughness: 0.2 .. 1 by 0.1 (below 0.2 the first row).
float facet_lobe_row(float roughness) { return clamp((roughness - 0.2) * 10.0, 0.0, 8.0); }

// The two lookups' texel (t0, t1, r0, r1), the table's third block.
vec4 facet_two_lobe_entry(sampler2D lobe_table, uint brdf, float x, float y) {
    return textureLod(lobe_table, vec2((18.5 + x) / 27.0, (float(brdf) * 9.0 + 0.5 + y) / 18.0), 0.0);
}

// One fitted lookup from its table entry: the axis between n and R at the linear weight t
// (which stands for the fitted angle), at the roughness `width`. Below roughness 0.2 the
// first row's lookups are drawn towards R and their roughness scaled with the surface's,
// so that a mirror reads R at level 0. (A few lookups of negligible weight were fitted
// narrower: none reads below 0.35 r.)
void facet_fitted_lookup(FacetSurface s, vec3 R, float t, float width, float specular_levels, out vec3 direction,
                         out float lod) {
    float below = clamp(s.roughness / 0.2, 0.0, 1.0);
    direction = normalize(mix(s.n, R, mix(1.0, t, below)));
    lod = facet_specular_lod(max(width * below, 0.35 * s.roughness), specular_levels);
}

FacetSpecularLookups facet_specular_lookups(FacetSurface s, vec3 v, float NdotV, float specular_levels,
                                              sampler2D lobe_table, bool fitted) {
    FacetSpecularLookups k;
    // An anisotropic surface's lookups reflect about n at its roughness: about the Khronos
    // sample viewer's bent normal (n bent towards the stretch as the lobe widens) the sun
    // sky's worst group was 16% (glTF) and 13% (thesis) off where along R it is 12% and 6%
    // (3.5% and 6% with the glTF LUT read at facet_anisotropic_view_roughness); at
    // sqrt(alpha_t alpha_b) 21%.
    vec3 R = reflect(-v, s.n);
    float lod = facet_specular_lod(s.roughness, specular_levels);
    for (int i = 0; i < 3; ++i) {
        k.direction[i] = R;
        k.lod[i] = lod;
        k.weight[i] = i == 0 ? 1.0 : 0.0;
    }
    if (!fitted) return k;
    vec4 directions, widths;
    facet_lobe_entries(lobe_table, s.brdf, facet_lobe_column(NdotV), facet_lobe_row(s.roughness), directions, widths);
    vec3 weights = vec3(directions.w, widths.w, 1.0 - directions.w - widths.w);
    for (int i = 0; i < 3; ++i) {
        facet_fitted_lookup(s, R, directions[i], widths[i], specular_levels, k.direction[i], k.lod[i]);
        k.weight[i] = weights[i];
    }
    return k;
}

// Two lookups of equal weight fitted like the three (facet_specular_lookups; one table read
// and one cube read fewer): from roughness kTwoLookupsRoughness (0.6) up they keep the image
// within its targets, below it only where the automatic choice predicts so
// (include/facet/render/specular_lobes.h). The third lookup weighs 0, which the compiler
// folds away.
FacetSpecularLookups facet_two_specular_lookups(FacetSurface s, vec3 v, float NdotV, float specular_levels,
                                                sampler2D lobe_table) {
    vec4 e = facet_two_lobe_entry(lobe_table, s.brdf, facet_lobe_column(NdotV), facet_lobe_row(s.roughness));
    vec3 R = reflect(-v, s.n);
    FacetSpecularLookups k;
    for (int i = 0; i < 2; ++i) {
        facet_fitted_lookup(s, R, e[i], e[2 + i], specular_levels, k.direction[i], k.lod[i]);
        k.weight[i] = 0.5;
    }
    k.direction[2] = R;
    k.lod[2] = 0.0;
    k.weight[2] = 0.0;
    return k;
}

// The specular levels below `first_level_without_lights` still hold the extracted lights:
// a disk's own specular counts only for the share of the lookup read from the levels
// without them (the bake's light extraction split level).
float facet_disk_specular_weight(float roughness, float specular_levels, float first_level_without_lights) {
    return clamp(facet_specular_lod(roughness, specular_levels) - (first_level_without_lights - 1.0), 0.0, 1.0);
}

// The same share for the lookups that shade the surface.
float facet_disk_specular_weight(FacetSpecularLookups k, float first_level_without_lights) {
    float w = 0.0;
    for (int i = 0; i < 3; ++i) w += k.weight[i] * clamp(k.lod[i] - (first_level_without_lights - 1.0), 0.0, 1.0);
    return w;
}

// The environment's contribution, and the two lookups it is made of (for inspection).
struct FacetEnvironmentLight {
    vec3 diffuse;
    vec3 specular;
    vec3 irradiance;   // E / pi along n, times the intensity
    vec3 prefiltered;  // prefiltered radiance along the lookup direction, times the intensity
};

// Split-sum image-based lighting, occlusion applied. `irradiance` is E / pi along n times
// the intensity (the overload below reads it from an irradiance cube, which holds E / pi),
// specular_map the GGX-prefiltered radiance read by the lookups k (facet_specular_lookups:
// one along R, or three fitted to the true lobe), lut facet_brdf_lut's value. multiscatter
// adds Kulla and Conty's multiple-scattering lobe (the LUT's third channel).
FacetEnvironmentLight facet_environment_light(FacetSurface s, vec3 v, float NdotV, vec4 lut, vec3 irradiance,
                                              samplerCube specular_map, float intensity, bool multiscatter,
                                              FacetSpecularLookups k) {
    FacetEnvironmentLight env;
    env.specular = vec3(0.0);
    // The split sum's directional albedo E = F0 A + B (Karis 2013) and the diffuse
    // lobe's weight: the cosine-weighted mean of the model's (1 - F) over the hemisphere,
    // which for Schlick's F depends on n.v alone (exact under uniform light).
    vec3 E, kd;
    facet_lut_albedo(s, NdotV, lut, E, kd);
    env.irradiance = irradiance;
    if (multiscatter) {
        // Kulla and Conty 2017: the multiple-scattering lobe f_ms = F_ms (1 - E(mu_o))
        // (1 - E(mu_i)) / (pi (1 - E_avg)), integrated against the environment with
        // (1 - E(mu_i)) replaced by its cosine-weighted mean 1 - E_avg, is
        // F_ms (1 - E(mu_o)) times the irradiance (exact under uniform light). The
        // diffuse lobe keeps what both specular lobes leave.
        float e_single = lut.x + lut.y;
        vec3 f_avg = s.F0 + (1.0 - s.F0) / 21.0;
        vec3 f_ms = f_avg * f_avg * lut.z / (1.0 - f_avg * (1.0 - lut.z));
        vec3 E_ms = s.specular_weight * f_ms * (1.0 - e_single);
        env.specular += E_ms * env.irradiance * s.occlusion;
        kd = min(kd, (1.0 - E - E_ms) * (1.0 - s.metallic));
    }
    // fitted: the lookups fitted to the true lobe (facet_specular_lookups).
    // Measured against the truth before them (facet-bench accuracy, glTF model, light
    // extraction on): Frostbite's dominant direction (Lagarde and de Rousiers 2014, listing 22)
    // faded in from roughness 0.35 to 0.5 left 5-7% in the worst groups under venice_sunset,
    // royal_esplanade and empty_warehouse_01; Filament's mix(R, n, alpha^2), a lookup pointed
    // at the lobe's centroid, level blending linear in alpha^2, 11 levels instead of 6 and 8
    // filtered importance samples of the true BRDF per pixel were each worse somewhere.
    env.prefiltered = vec3(0.0);
    for (int i = 0; i < 3; ++i)
        if (k.weight[i] > 0.0) env.prefiltered += k.weight[i] * textureLod(specular_map, k.direction[i], k.lod[i]).rgb;
    env.prefiltered *= intensity;
    env.diffuse = kd * s.albedo * env.irradiance * s.occlusion;
#ifdef FACET_TRANSMISSION
    env.diffuse *= 1.0 - s.transmission;  // the rest of the base's light is transmitted (forward.frag)
#endif
    env.specular += env.prefiltered * E * s.occlusion;
    return env;
}

FacetEnvironmentLight facet_environment_light(FacetSurface s, vec3 v, float NdotV, vec4 lut, samplerCube irradiance_map,
                                              samplerCube specular_map, float intensity, bool multiscatter,
                                              FacetSpecularLookups k) {
    return facet_environment_light(s, v, NdotV, lut, texture(irradiance_map, s.n).rgb * intensity, specular_map,
                                   intensity, multiscatter, k);
}

// KHR_materials_clearcoat's layer under the environment, applied to facet_environment_light's
// result `env` for the same surface and its LUT value `lut`: the surface's terms dimmed by
// 1 - weight x the mean of Fc over each lobe (the diffuse lobe's from the LUT's fourth
// channel, the specular lobe's (0.04 A + B) / (A + B) from its split sum), and the layer's
// own split sum added: one lookup along its reflection at its roughness, times 0.04 A + B of
// the LUT (lut_map) at its n.v and roughness. Nothing without a layer.
void facet_environment_clearcoat(FacetSurface s, vec3 v, vec4 lut, sampler2D lut_map, samplerCube specular_map,
                                 float specular_levels, float intensity, inout FacetEnvironmentLight env) {
    if (s.clearcoat <= 0.0) return;
    env.diffuse *= 1.0 - s.clearcoat * (0.04 + 0.96 * lut.w);
    env.specular *= 1.0 - s.clearcoat * (0.04 * lut.x + lut.y) / max(lut.x + lut.y, 1e-6);
    float coat_NdotV = clamp(dot(s.clearcoat_n, v), 0.0, 1.0);
    vec4 coat_lut = facet_brdf_lut(lut_map, coat_NdotV, s.clearcoat_roughness);
    vec3 R = reflect(-v, s.clearcoat_n);
    float lod = facet_specular_lod(s.clearcoat_roughness, specular_levels);
    vec3 prefiltered = textureLod(specular_map, R, lod).rgb * intensity;
    env.specular += s.clearcoat * (0.04 * coat_lut.x + coat_lut.y) * prefiltered * s.occlusion;
}

// The same with the lookups made here (facet_specular_lookups): one along R, or the three
// fitted ones read from lobe_table when `fitted`.
FacetEnvironmentLight facet_environment_light(FacetSurface s, vec3 v, float NdotV, vec4 lut, samplerCube irradiance_map,
                                              samplerCube specular_map, float specular_levels, float intensity,
                                              bool multiscatter, sampler2D lobe_table, bool fitted) {
    return facet_environment_light(s, v, NdotV, lut, irradiance_map, specular_map, intensity, multiscatter,
                                   facet_specular_lookups(s, v, NdotV, specular_levels, lobe_table, fitted));
}

#endif
