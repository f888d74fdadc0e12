#ifndef FACET_SHADING_GLSL
#define FACET_SHADING_GLSL
// Shading with Facet's baked environment and lights: the functions the forward pass
// (render/forward.frag) shades with, installed (share/facet/shaders/facet/) so that a host
// engine's own material shaders can call them: #include "facet/shading.glsl" with
// share/facet/shaders on the include path. Every function takes its textures and values as
// parameters, never a global binding, so a host passes its own.
//
// The model is the thesis' Cook-Torrance (Junakovic, "Fizikalno temeljen model ostvarivanja
// prikaza", Zagreb 2019): GGX D, Schlick F on h.v, Smith with Schlick-GGX (k = (r+1)^2/8
// for punctual lights, r^2/2 for the environment) or glTF's height-correlated term, Lambert
// diffuse with kd = (1 - F)(1 - metallic). The environment is the split sum (Karis 2013):
// irradiance (E / pi) for the diffuse part, the prefiltered cube at
// lod = roughness x (levels - 1) times the LUT's F0 A + B for the specular part.
// Each composition exists here once: diffuse + specular for a light from one direction
// (facet_reflect_light), for a disk (facet_disk_light), for the environment
// (facet_environment_light).
#include "brdf.glsl"

// What the shading needs of a surface point (facet_surface fills the derived terms).
struct FacetSurface {
    vec3 n;                 // unit shading normal, world space
    vec3 albedo;            // linear base colour
    float metallic;         // 0..1
    float roughness;        // perceptual, 0..1; alpha = roughness^2
    vec3 F0;                // reflectance at normal incidence
    float specular_weight;  // KHR_materials_specular's factor for the dielectric part (1: none)
    float occlusion;        // ambient occlusion, 0..1: scales environment and disk lights only
};

// glTF's metallic-roughness material: F0 = mix(dielectric F0, albedo, metallic); metals
// ignore the dielectric specular factor.
FacetSurface facet_surface(vec3 n, vec3 albedo, float metallic, float roughness, float dielectric_f0,
                           float specular_factor, float occlusion) {
    FacetSurface s;
    s.n = n;
    s.albedo = albedo;
    s.metallic = metallic;
    s.roughness = roughness;
    s.F0 = mix(vec3(dielectric_f0), albedo, metallic);
    s.specular_weight = mix(specular_factor, 1.0, metallic);
    s.occlusion = occlusion;
    return s;
}

// The specular term without F: D G / (4 n.l n.v) with Schlick-GGX of factor k, or D V
// with glTF's height-correlated visibility when height_correlated (k unused).
float facet_specular_dg(float NdotV, float NdotL, float NdotH, float roughness, float k, bool height_correlated) {
    float D = D_GGX(NdotH, roughness);
    if (height_correlated) return D * V_SmithGGXCorrelated(NdotV, NdotL, max(roughness * roughness, MIN_ALPHA));
    float G = G_Smith(NdotV, NdotL, k);
    return D * G / max(4.0 * NdotV * NdotL, 1e-8);
}

// Radiance `incident` arriving along l (unit, towards the light) reflected towards v:
// diffuse = kd albedo / pi * incident * n.l and specular = F D G / (4 n.l n.v) * incident
// * n.l. Zero when l is below the surface. NdotV = clamp(n.v, 0, 1).
void facet_reflect_light(FacetSurface s, vec3 v, float NdotV, vec3 l, vec3 incident, float k, bool height_correlated,
                         out vec3 diffuse, out vec3 specular) {
    diffuse = vec3(0.0);
    specular = vec3(0.0);
    float NdotL = dot(s.n, l);
    if (NdotL <= 0.0) return;
    vec3 h = normalize(v + l);
    vec3 F = s.specular_weight * F_Schlick(clamp(dot(h, v), 0.0, 1.0), s.F0);
    vec3 kd = (1.0 - F) * (1.0 - s.metallic);
    diffuse = kd * s.albedo / PI * incident * NdotL;
    specular = F * facet_specular_dg(NdotV, NdotL, clamp(dot(s.n, h), 0.0, 1.0), s.roughness, k, height_correlated) *
               incident * NdotL;
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

// The split sum's LUT at (n.v, roughness): scale A, bias B, and the average albedo E_avg
// (third channel; multiple scattering).
vec3 facet_brdf_lut(sampler2D lut, float NdotV, float roughness) {
    return texture(lut, vec2(NdotV, roughness)).rgb;
}

// The prefiltered cube holds roughness level / (levels - 1) at each level.
float facet_specular_lod(float roughness, float specular_levels) {
    return roughness * (specular_levels - 1.0);
}

// Multiple scattering for lights: single scattering loses 1 - E(mu) of the energy for
// F0 = 1 (E = A + B); the lobe is scaled by 1 + F0 (1 / E - 1) (Turquin 2019). Multiply a
// light's specular by it.
vec3 facet_multiscatter_light_energy(vec3 F0, vec3 lut) {
    return 1.0 + F0 * (1.0 / max(lut.x + lut.y, 1e-3) - 1.0);
}

// A bright region taken out of the environment before the bake (light extraction): a cap
// of angular radius theta around a direction with uniform radiance inside.
struct FacetDiskLight {
    vec3 direction;        // unit, from the surface towards the cap's centre
    float cos_radius;      // cos theta
    float angular_radius;  // theta, radians
    vec3 radiance;
};

// The cap shaded with the full BRDF (the environment's, k = r^2/2) by a sum over 32
// directions spread evenly over it (uniform in cos, golden-angle spiral). Lobes much
// narrower than the cap cannot be resolved by 32 directions: there the cap acts as a
// mirror image, L times the lobe's albedo (the LUT's F0 A + B) where R falls inside it,
// faded over the lobe's width. Occlusion not applied.
void facet_disk_light(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk, vec3 lut, out vec3 diffuse,
                      out vec3 specular) {
    vec3 c = disk.direction;
    float cos_theta = disk.cos_radius, theta = disk.angular_radius;
    vec3 L = disk.radiance;
    vec3 t, b;
    facet_tangent_frame(c, t, b);
    const uint N = 32u;
    float omega = 2.0 * PI * (1.0 - cos_theta) / float(N);
    float k = k_ibl(s.roughness);
    diffuse = vec3(0.0);
    vec3 sampled = vec3(0.0);
    for (uint i = 0u; i < N; ++i) {
        float z = 1.0 - (float(i) + 0.5) / float(N) * (1.0 - cos_theta);
        float r = sqrt(max(0.0, 1.0 - z * z)), phi = float(i) * 2.39996323;
        vec3 l = t * (r * cos(phi)) + b * (r * sin(phi)) + c * z;
        vec3 d, sp;
        facet_reflect_light(s, v, NdotV, l, vec3(1.0), k, false, d, sp);
        diffuse += d;
        sampled += sp;
    }
    diffuse *= L * omega;
    sampled *= L * omega;
    float alpha = max(s.roughness * s.roughness, MIN_ALPHA);
    vec3 R = reflect(-v, s.n);
    float angle = acos(clamp(dot(R, c), -1.0, 1.0));
    float coverage = clamp((theta + alpha - angle) / (2.0 * alpha), 0.0, 1.0);
    vec3 mirror = L * s.specular_weight * (s.F0 * lut.x + lut.y) * coverage;
    // 32 directions are about theta / 3 apart: the sum resolves lobes from alpha = theta / 2
    // on; below theta / 4 the mirror image holds.
    specular = mix(mirror, sampled, clamp((alpha - theta / 4.0) / (theta / 4.0), 0.0, 1.0));
}

// The specular levels below `first_level_without_lights` still hold the extracted lights:
// a disk's own specular counts only for the share of the lookup read from the levels
// without them (the bake's light extraction split level).
float facet_disk_specular_weight(float roughness, float specular_levels, float first_level_without_lights) {
    return clamp(facet_specular_lod(roughness, specular_levels) - (first_level_without_lights - 1.0), 0.0, 1.0);
}

// The environment's contribution, and the two lookups it is made of (for inspection).
struct FacetEnvironmentLight {
    vec3 diffuse;
    vec3 specular;
    vec3 irradiance;   // E / pi along n, times the intensity
    vec3 prefiltered;  // prefiltered radiance along the lookup direction, times the intensity
};

// Split-sum image-based lighting, occlusion applied. irradiance_map holds E / pi,
// specular_map the GGX-prefiltered radiance with `specular_levels` levels, lut
// facet_brdf_lut's value. multiscatter adds Kulla and Conty's multiple-scattering lobe (the
// LUT's third channel); dominant_direction bends the lookup towards n for rough lobes.
FacetEnvironmentLight facet_environment_light(FacetSurface s, vec3 v, float NdotV, vec3 lut, samplerCube irradiance_map,
                                              samplerCube specular_map, float specular_levels, float intensity,
                                              bool multiscatter, bool dominant_direction) {
    FacetEnvironmentLight env;
    env.specular = vec3(0.0);
    // The split sum's directional albedo E = F0 A + B (Karis 2013).
    vec3 E = s.specular_weight * (s.F0 * lut.x + lut.y);
    env.irradiance = texture(irradiance_map, s.n).rgb * intensity;
    vec3 E_ms = vec3(0.0);
    if (multiscatter) {
        // Kulla and Conty 2017: the multiple-scattering lobe f_ms = F_ms (1 - E(mu_o))
        // (1 - E(mu_i)) / (pi (1 - E_avg)), integrated against the environment with
        // (1 - E(mu_i)) replaced by its cosine-weighted mean 1 - E_avg, is
        // F_ms (1 - E(mu_o)) times the irradiance (exact under uniform light).
        float e_single = lut.x + lut.y;
        vec3 f_avg = s.F0 + (1.0 - s.F0) / 21.0;
        vec3 f_ms = f_avg * f_avg * lut.z / (1.0 - f_avg * (1.0 - lut.z));
        E_ms = s.specular_weight * f_ms * (1.0 - e_single);
        env.specular += E_ms * env.irradiance * s.occlusion;
    }
    // The thesis' kd/ks split with F_SchlickRoughness, capped at 1 - E: at grazing angles
    // on smooth dielectrics E exceeds F_SchlickRoughness by up to ~1%, and diffuse +
    // specular must not reflect more than arrives.
    vec3 F = s.specular_weight * F_SchlickRoughness(NdotV, s.F0, s.roughness);
    vec3 kd = (multiscatter ? min(1.0 - F, 1.0 - E - E_ms) : min(1.0 - F, 1.0 - E)) * (1.0 - s.metallic);
    vec3 lookup = reflect(-v, s.n);
    if (dominant_direction) {
        // Rough lobes lean towards n (Lagarde and de Rousiers 2014, "Moving Frostbite to
        // PBR", listing 22, with alpha = roughness^2 as their roughness).
        float alpha = s.roughness * s.roughness;
        float smoothness = clamp(1.0 - alpha, 0.0, 1.0);
        lookup = normalize(mix(s.n, lookup, smoothness * (sqrt(smoothness) + alpha)));
    }
    env.prefiltered =
        textureLod(specular_map, lookup, facet_specular_lod(s.roughness, specular_levels)).rgb * intensity;
    env.diffuse = kd * s.albedo * env.irradiance * s.occlusion;
    env.specular += env.prefiltered * E * s.occlusion;
    return env;
}

#endif
