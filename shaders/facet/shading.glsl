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
    float dielectric_f0;    // the dielectric part's F0 (0.04 for ior 1.5)
    float specular_factor;  // KHR_materials_specular's factor for the dielectric part (1: none)
    float occlusion;        // ambient occlusion, 0..1: scales environment and disk lights only
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
    s.dielectric_f0 = dielectric_f0;
    s.specular_factor = specular_factor;
    s.occlusion = occlusion;
    return s;
}

// The Fresnel term of the specular lobe and the diffuse lobe's weight at v.h.
// glTF: mix(specular x F(0.04), F(baseColor), metallic) and (1 - specular x F(0.04))
// (1 - metallic); thesis: F(F0) (the specular weight scaling it) and (1 - F)(1 - metallic).
void facet_fresnel(FacetSurface s, float VdotH, out vec3 F, out vec3 kd) {
    float w = pow(clamp(1.0 - VdotH, 0.0, 1.0), 5.0);
    if (s.brdf == FACET_BRDF_GLTF) {
        float Fd = s.specular_factor * (s.dielectric_f0 + (1.0 - s.dielectric_f0) * w);
        F = mix(vec3(Fd), s.albedo + (1.0 - s.albedo) * w, s.metallic);
        kd = vec3((1.0 - Fd) * (1.0 - s.metallic));
    } else {
        F = s.specular_weight * (s.F0 + (1.0 - s.F0) * w);
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

// Radiance `incident` arriving along l (unit, towards the light) reflected towards v:
// diffuse = kd albedo / pi * incident * n.l and specular = F D G / (4 n.l n.v) * incident
// * n.l. Zero when l is below the surface. NdotV = clamp(n.v, 0, 1). `punctual` selects
// the thesis' k for punctual lights (the glTF model has one visibility term).
void facet_reflect_light(FacetSurface s, vec3 v, float NdotV, vec3 l, vec3 incident, bool punctual,
                         out vec3 diffuse, out vec3 specular) {
    diffuse = vec3(0.0);
    specular = vec3(0.0);
    float NdotL = dot(s.n, l);
    if (NdotL <= 0.0) return;
    vec3 h = normalize(v + l);
    vec3 F, kd;
    facet_fresnel(s, clamp(dot(h, v), 0.0, 1.0), F, kd);
    diffuse = kd * s.albedo / PI * incident * NdotL;
    specular = F * facet_specular_dg(s, NdotV, NdotL, clamp(dot(s.n, h), 0.0, 1.0), punctual) * incident * NdotL;
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
        float Ed = s.specular_factor * (s.dielectric_f0 * lut.x + lut.y);
        E = mix(vec3(Ed), s.albedo * lut.x + lut.y, s.metallic);
        float Fd = s.specular_factor * (s.dielectric_f0 + (1.0 - s.dielectric_f0) * lut.w);
        kd = vec3((1.0 - Fd) * (1.0 - s.metallic));
    } else {
        E = s.specular_weight * (s.F0 * lut.x + lut.y);
        kd = (1.0 - s.specular_weight * (s.F0 + (1.0 - s.F0) * lut.w)) * (1.0 - s.metallic);
    }
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
    vec3 radiance;
};

// The cap shaded with the full BRDF (the environment's k for the thesis' model) by a sum
// over N directions spread evenly over it (uniform in cos, golden-angle spiral), N as the
// lobe needs: one (the cap as a point source of its power) where the specular lobe is at
// least four times wider than the cap, alpha >= 4 theta (D's curvature over the cap then
// changes the sum by under 2%; the diffuse part of a cap above the horizon is exact, one
// cut by the horizon needs 8 directions from 0.1 radian on),
// 8 from alpha >= theta on, else 32. Lobes much narrower than the cap cannot be
// resolved by 32 directions: there the cap acts as a mirror image, L times the lobe's
// albedo (the LUT's F0 A + B) where R falls inside it, faded over the lobe's width.
// Occlusion not applied.
void facet_disk_light(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk, vec4 lut, out vec3 diffuse,
                      out vec3 specular) {
    vec3 c = disk.direction;
    float cos_theta = disk.cos_radius, theta = disk.angular_radius;
    vec3 L = disk.radiance;
    diffuse = vec3(0.0);
    specular = vec3(0.0);
    // Wholly below the horizon: nothing arrives.
    if (dot(s.n, c) <= -sin(theta)) return;
    float alpha = max(s.roughness * s.roughness, MIN_ALPHA);
    vec3 R = reflect(-v, s.n);
    float angle = acos(clamp(dot(R, c), -1.0, 1.0));
    // A lobe narrower than a quarter of the cap sees it as a mirror image; one much
    // narrower than the cap's distance from R (eight lobe widths: D down to 1e-4 of its
    // peak) sees nothing of it. Either way the sum serves the diffuse part alone.
    bool mirror_only = alpha <= 0.25 * theta, outside = angle > theta + 8.0 * alpha;
    uint N = alpha >= 4.0 * theta || mirror_only || outside ? 1u : (alpha >= theta ? 8u : 32u);
    // A cap wholly above the horizon: its diffuse part is the exact cosine integral,
    // pi sin^2(theta) (n.c), times the diffuse BRDF at the centre (which varies by under
    // 1% over a cap of 0.2 radian); one cut by the horizon is summed over 8 directions or more.
    float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
    bool above = dot(s.n, c) >= sin_theta;
    if (theta > 0.1 && !above) N = max(N, 8u);
    float omega = 2.0 * PI * (1.0 - cos_theta) / float(N);
    vec3 t = vec3(0.0), b = vec3(0.0);
    if (N > 1u) facet_tangent_frame(c, t, b);
    vec3 sampled = vec3(0.0);
    for (uint i = 0u; i < N; ++i) {
        float z = N == 1u ? 1.0 : 1.0 - (float(i) + 0.5) / float(N) * (1.0 - cos_theta);
        float r = sqrt(max(0.0, 1.0 - z * z)), phi = float(i) * 2.39996323;
        vec3 l = t * (r * cos(phi)) + b * (r * sin(phi)) + c * z;
        vec3 d, sp;
        facet_reflect_light(s, v, NdotV, l, vec3(1.0), false, d, sp);
        diffuse += d;
        sampled += sp;
    }
    if (above) {
        // With one direction the sum already was the centre's; with more, one more evaluation.
        vec3 centre_diffuse = diffuse, unused;
        if (N > 1u) facet_reflect_light(s, v, NdotV, c, vec3(1.0), false, centre_diffuse, unused);
        diffuse = centre_diffuse * (PI * sin_theta * sin_theta);
    } else {
        diffuse *= omega;
    }
    diffuse *= L;
    sampled *= L * omega;
    if (outside && !mirror_only) {
        specular = sampled;  // the one direction's specular: the lobe's far tail
        return;
    }
    float coverage = clamp((theta + alpha - angle) / (2.0 * alpha), 0.0, 1.0);
    vec3 E, kd;
    facet_lut_albedo(s, lut, E, kd);
    vec3 mirror = L * E * coverage;
    // 32 directions are about theta / 3 apart: the sum resolves lobes from alpha = theta / 2
    // on; below theta / 4 the mirror image holds.
    specular = mix(mirror, sampled, clamp((alpha - theta / 4.0) / (theta / 4.0), 0.0, 1.0));
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

// One lookup's entry of the fitted table (include/facet/render/specular_lobes.h: texel
// (lookup * 9 + column, model * 9 + row)), interpolated linearly by the sampler at table
// coordinates x (n.v column) and y (roughness row), each in [0, 8].
vec3 facet_lobe_entry(sampler2D lobe_table, uint brdf, int lookup, float x, float y) {
    vec2 uv = vec2((float(lookup) * 9.0 + 0.5 + x) / 27.0, (float(brdf) * 9.0 + 0.5 + y) / 18.0);
    return textureLod(lobe_table, uv, 0.0).xyz;
}

FacetSpecularLookups facet_specular_lookups(FacetSurface s, vec3 v, float NdotV, float specular_levels,
                                              sampler2D lobe_table, bool fitted) {
    FacetSpecularLookups k;
    vec3 R = reflect(-v, s.n);
    float lod = facet_specular_lod(s.roughness, specular_levels);
    for (int i = 0; i < 3; ++i) {
        k.direction[i] = R;
        k.lod[i] = lod;
        k.weight[i] = i == 0 ? 1.0 : 0.0;
    }
    if (!fitted) return k;
    // Table coordinates: roughness 0.2 .. 1 by 0.1 (below 0.2 the first row, its lookups
    // drawn towards R and its roughness scaled with the surface's, so that a mirror reads R
    // at level 0), n.v 0.1 .. 0.9 by 0.1 (clamped: the lookups meet at R = n as n.v -> 1).
    float x = clamp((NdotV - 0.1) * 10.0, 0.0, 8.0);
    float y = clamp((s.roughness - 0.2) * 10.0, 0.0, 8.0);
    float below = clamp(s.roughness / 0.2, 0.0, 1.0);
    float cos_theta = clamp(dot(s.n, R), -1.0, 1.0);
    float theta = acos(cos_theta), sin_theta = sin(theta);
    for (int i = 0; i < 3; ++i) {
        vec3 e = facet_lobe_entry(lobe_table, s.brdf, i, x, y);
        float fraction = mix(1.0, e.x, below);
        // The axis at `fraction` of the angle from n to R, on their great circle.
        vec3 d = sin_theta > 1e-4 ? (s.n * sin((1.0 - fraction) * theta) + R * sin(fraction * theta)) / sin_theta : R;
        k.direction[i] = normalize(d);
        // (A few lookups of negligible weight were fitted narrower: none reads below 0.35 r.)
        k.lod[i] = facet_specular_lod(max(e.y * below, 0.35 * s.roughness), specular_levels);
        k.weight[i] = e.z;
    }
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

// Split-sum image-based lighting, occlusion applied. irradiance_map holds E / pi,
// specular_map the GGX-prefiltered radiance read by the lookups k (facet_specular_lookups:
// one along R, or three fitted to the true lobe), lut facet_brdf_lut's value. multiscatter
// adds Kulla and Conty's multiple-scattering lobe (the LUT's third channel).
FacetEnvironmentLight facet_environment_light(FacetSurface s, vec3 v, float NdotV, vec4 lut, samplerCube irradiance_map,
                                              samplerCube specular_map, float intensity, bool multiscatter,
                                              FacetSpecularLookups k) {
    FacetEnvironmentLight env;
    env.specular = vec3(0.0);
    // The split sum's directional albedo E = F0 A + B (Karis 2013) and the diffuse
    // lobe's weight: the cosine-weighted mean of the model's (1 - F) over the hemisphere,
    // which for Schlick's F depends on n.v alone (exact under uniform light).
    vec3 E, kd;
    facet_lut_albedo(s, lut, E, kd);
    env.irradiance = texture(irradiance_map, s.n).rgb * intensity;
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
    env.specular += env.prefiltered * E * s.occlusion;
    return env;
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
