#version 460
// Cook-Torrance shading, the thesis' reflectance equation: punctual lights with the
// full BRDF, image-based lighting with the split sum, Lambert diffuse with
// kd = (1 - F)(1 - metalness). Variants (defines) carry only the features a material
// uses: HAS_BASE_COLOR_MAP, HAS_METALLIC_ROUGHNESS_MAP, HAS_NORMAL_MAP,
// HAS_OCCLUSION_MAP, HAS_EMISSIVE_MAP, ALPHA_MASK, ALPHA_BLEND, DOUBLE_SIDED, USE_IBL,
// HEIGHT_CORRELATED (glTF's Smith term instead of Schlick-GGX), MULTISCATTER (energy
// compensation), DOMINANT_DIRECTION (bent specular lookup), VIEW (what is written:
// render/views.glsl).
#include "brdf.glsl"
#include "render/forward_interface.glsl"
#include "render/views.glsl"

#ifndef VIEW
#define VIEW VIEW_FINAL
#endif

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
#ifdef HAS_NORMAL_MAP
layout(location = 3) in vec4 in_tangent;
#endif

layout(location = 0) out vec4 out_color;

struct Surface {
    vec3 albedo;
    float alpha;
    float metallic;
    float roughness;
    float occlusion;
    vec3 emissive;
    vec3 F0;
    float specular_weight;  // KHR_materials_specular's factor for the dielectric part
    vec3 n;
};

Surface surface_at(MaterialData m) {
    Surface s;
    vec4 base = m.base_color;
#ifdef HAS_BASE_COLOR_MAP
    base *= texture(base_color_map, in_uv);
#endif
    s.albedo = base.rgb;
    s.alpha = base.a;
    s.metallic = m.factors.x;
    s.roughness = m.factors.y;
#ifdef HAS_METALLIC_ROUGHNESS_MAP
    vec4 mr = texture(metallic_roughness_map, in_uv);
    s.roughness *= mr.g;
    s.metallic *= mr.b;
#endif
    s.metallic = clamp(s.metallic, 0.0, 1.0);
    s.roughness = clamp(s.roughness, 0.0, 1.0);
    s.occlusion = m.extra.z;
#ifdef HAS_OCCLUSION_MAP
    s.occlusion *= 1.0 + m.factors.w * (texture(occlusion_map, in_uv).r - 1.0);
#endif
    s.emissive = m.emissive_f0.rgb;
#ifdef HAS_EMISSIVE_MAP
    s.emissive *= texture(emissive_map, in_uv).rgb;
#endif
    s.F0 = mix(vec3(m.emissive_f0.a), s.albedo, s.metallic);
    s.specular_weight = mix(m.extra.y, 1.0, s.metallic);
    vec3 n = normalize(in_normal);
#ifdef DOUBLE_SIDED
    if (!gl_FrontFacing) n = -n;
#endif
#ifdef HAS_NORMAL_MAP
    // Tangent frame of the glTF specification: bitangent = cross(n, t) * w.
    vec3 t = in_tangent.xyz - n * dot(n, in_tangent.xyz);
    if (dot(t, t) > 1e-12) {
        t = normalize(t);
        vec3 b = cross(n, t) * (in_tangent.w < 0.0 ? -1.0 : 1.0);
        vec3 tn = texture(normal_map, in_uv).xyz * 2.0 - 1.0;
        tn.xy *= m.factors.z;
        n = normalize(mat3(t, b, n) * tn);
    }
#endif
    s.n = n;
    return s;
}

// Incoming radiance scale and direction towards a punctual light (KHR_lights_punctual:
// inverse-square falloff windowed by the range, smooth spot cone).
vec3 light_incidence(Light light, vec3 p, out vec3 l) {
    uint type = uint(light.direction_type.w);
    vec3 radiance = light.color_intensity.rgb * light.color_intensity.a;
    if (type == 0u) {
        l = -normalize(light.direction_type.xyz);
        return radiance;
    }
    vec3 to_light = light.position_range.xyz - p;
    float d2 = max(dot(to_light, to_light), 1e-8);
    l = to_light * inversesqrt(d2);
    float attenuation = 1.0 / d2;
    float range = light.position_range.w;
    if (range > 0.0) {
        float ratio = d2 / (range * range);
        attenuation *= clamp(1.0 - ratio * ratio, 0.0, 1.0);
    }
    if (type == 2u) {
        float cd = dot(normalize(light.direction_type.xyz), -l);
        float cone = clamp(cd * light.cone.x + light.cone.y, 0.0, 1.0);
        attenuation *= cone * cone;
    }
    return radiance * attenuation;
}

// The BRDF's specular term f_s = D F G / (4 n.l n.v), or D F V with the glTF Smith term.
float specular_DG(float NdotV, float NdotL, float NdotH, float roughness) {
    float D = D_GGX(NdotH, roughness);
#ifdef HEIGHT_CORRELATED
    return D * V_SmithGGXCorrelated(NdotV, NdotL, max(roughness * roughness, MIN_ALPHA));
#else
    float G = G_Smith(NdotV, NdotL, k_direct(roughness));
    return D * G / max(4.0 * NdotV * NdotL, 1e-8);
#endif
}

#ifdef USE_IBL
// A bright region taken out of the environment (ibl/light_extraction.h): a cap of
// half-angle theta around c with uniform radiance L, shaded with the full BRDF (the
// environment's, k = r^2/2) by a sum over 32 directions spread evenly over the cap
// (uniform in cos, golden-angle spiral). Lobes much narrower than the cap cannot be
// resolved by 32 directions: there the cap acts as a mirror image, L times the lobe's
// albedo (the LUT's F0 A + B) where R falls inside it, faded over the lobe's width.
void disk_light(Surface s, vec3 v, float NdotV, Light light, vec3 lut, out vec3 diffuse, out vec3 specular) {
    vec3 c = -normalize(light.direction_type.xyz);
    float cos_theta = light.cone.x, theta = light.cone.y;
    vec3 L = light.color_intensity.rgb * light.color_intensity.a;
    vec3 up = abs(c.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 t = normalize(cross(up, c)), b = cross(c, t);
    const uint N = 32u;
    float omega = 2.0 * PI * (1.0 - cos_theta) / float(N);
    float k = k_ibl(s.roughness);
    diffuse = vec3(0.0);
    vec3 sampled = vec3(0.0);
    for (uint i = 0u; i < N; ++i) {
        float z = 1.0 - (float(i) + 0.5) / float(N) * (1.0 - cos_theta);
        float r = sqrt(max(0.0, 1.0 - z * z)), phi = float(i) * 2.39996323;
        vec3 l = t * (r * cos(phi)) + b * (r * sin(phi)) + c * z;
        float NdotL = dot(s.n, l);
        if (NdotL <= 0.0) continue;
        vec3 h = normalize(v + l);
        vec3 F = s.specular_weight * F_Schlick(clamp(dot(h, v), 0.0, 1.0), s.F0);
        diffuse += (1.0 - F) * (1.0 - s.metallic) * s.albedo / PI * NdotL;
        float DG = D_GGX(clamp(dot(s.n, h), 0.0, 1.0), s.roughness) * G_Smith(NdotV, NdotL, k);
        sampled += F * DG / max(4.0 * NdotV * NdotL, 1e-8) * NdotL;
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
#endif

void main() {
    MaterialData m = materials[draw.material];
    Surface s = surface_at(m);
#ifdef ALPHA_MASK
    if (s.alpha < m.extra.x) discard;
#endif
    vec3 v = normalize(frame.camera_position.xyz - in_world);
    vec3 n = s.n;
    float NdotV = clamp(dot(n, v), 0.0, 1.0);

    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
#ifdef USE_IBL
    // Split-sum scale and bias, and the average albedo E_avg (LUT's third channel).
    vec3 lut = texture(brdf_lut, vec2(NdotV, s.roughness)).rgb;
#endif
#if defined(MULTISCATTER) && defined(USE_IBL)
    // Single scattering loses 1 - E(mu) of the energy for F0 = 1 (E = A + B); lights get it
    // back by scaling the lobe by 1 + F0 (1 / E - 1) (Turquin 2019).
    vec3 light_energy = 1.0 + s.F0 * (1.0 / max(lut.x + lut.y, 1e-3) - 1.0);
#else
    vec3 light_energy = vec3(1.0);
#endif
    // The component views show the terms for the first light, or for the mirror
    // direction (h = n) when the scene has no light.
    vec3 view_l = reflect(-v, n);
    float view_k = k_ibl(s.roughness);
    for (uint i = 0u; i < frame.counts.x; ++i) {
        vec3 l;
        vec3 incident = light_incidence(lights[i], in_world, l);
        if (i == 0u) {
            view_l = l;
            view_k = k_direct(s.roughness);
        }
        float NdotL = dot(n, l);
        if (NdotL <= 0.0) continue;
        vec3 h = normalize(v + l);
        vec3 F = s.specular_weight * F_Schlick(clamp(dot(h, v), 0.0, 1.0), s.F0);
        vec3 kd = (1.0 - F) * (1.0 - s.metallic);
        diffuse += kd * s.albedo / PI * incident * NdotL;
        specular += light_energy * F * specular_DG(NdotV, NdotL, clamp(dot(n, h), 0.0, 1.0), s.roughness) * incident *
                    NdotL;
    }
    vec3 irradiance = vec3(0.0), prefiltered = vec3(0.0);
#ifdef USE_IBL
    // Specular levels below frame.ibl.z still hold the extracted lights: the disks' own
    // specular counts only for the share of the lookup read from the levels without them.
    float disk_specular_weight = clamp(s.roughness * frame.ibl.y - (frame.ibl.z - 1.0), 0.0, 1.0);
    for (uint i = 0u; i < frame.counts.y; ++i) {
        vec3 disk_diffuse, disk_specular;
        disk_light(s, v, NdotV, lights[frame.counts.x + i], lut, disk_diffuse, disk_specular);
        diffuse += disk_diffuse * frame.ibl.x * s.occlusion;
        specular += disk_specular * disk_specular_weight * frame.ibl.x * s.occlusion;
    }
    {
        float intensity = frame.ibl.x;
        // The split sum's directional albedo E = F0 A + B (Karis 2013).
        vec3 E = s.specular_weight * (s.F0 * lut.x + lut.y);
        irradiance = texture(irradiance_map, n).rgb * intensity;
#ifdef MULTISCATTER
        // Kulla and Conty 2017: the multiple-scattering lobe f_ms = F_ms (1 - E(mu_o))
        // (1 - E(mu_i)) / (pi (1 - E_avg)), integrated against the environment with
        // (1 - E(mu_i)) replaced by its cosine-weighted mean 1 - E_avg, is
        // F_ms (1 - E(mu_o)) times the irradiance (exact under uniform light).
        float e_single = lut.x + lut.y;
        vec3 f_avg = s.F0 + (1.0 - s.F0) / 21.0;
        vec3 f_ms = f_avg * f_avg * lut.z / (1.0 - f_avg * (1.0 - lut.z));
        vec3 E_ms = s.specular_weight * f_ms * (1.0 - e_single);
        specular += E_ms * irradiance * s.occlusion;
#endif
        // The thesis' kd/ks split with F_SchlickRoughness, capped at 1 - E: at grazing
        // angles on smooth dielectrics E exceeds F_SchlickRoughness by up to ~1%, and
        // diffuse + specular must not reflect more than arrives.
        vec3 F = s.specular_weight * F_SchlickRoughness(NdotV, s.F0, s.roughness);
#ifdef MULTISCATTER
        vec3 kd = min(1.0 - F, 1.0 - E - E_ms) * (1.0 - s.metallic);
#else
        vec3 kd = min(1.0 - F, 1.0 - E) * (1.0 - s.metallic);
#endif
        vec3 lookup = reflect(-v, n);
#ifdef DOMINANT_DIRECTION
        // Rough lobes lean towards n (Lagarde and de Rousiers 2014, "Moving Frostbite to
        // PBR", listing 22, with alpha = roughness^2 as their roughness).
        float alpha = s.roughness * s.roughness;
        float smoothness = clamp(1.0 - alpha, 0.0, 1.0);
        lookup = normalize(mix(n, lookup, smoothness * (sqrt(smoothness) + alpha)));
#endif
        prefiltered = textureLod(specular_map, lookup, s.roughness * frame.ibl.y).rgb * intensity;
        diffuse += kd * s.albedo * irradiance * s.occlusion;
        specular += prefiltered * E * s.occlusion;
    }
#endif

#if VIEW == VIEW_FINAL
    out_color = vec4(diffuse + specular + s.emissive, s.alpha);
#elif VIEW == VIEW_NORMAL
    out_color = vec4(n, 1.0);
#elif VIEW == VIEW_POSITION
    out_color = vec4(in_world, 1.0);
#elif VIEW == VIEW_BASECOLOR
    out_color = vec4(s.albedo, s.alpha);
#elif VIEW == VIEW_METALLIC
    out_color = vec4(vec3(s.metallic), 1.0);
#elif VIEW == VIEW_ROUGHNESS
    out_color = vec4(vec3(s.roughness), 1.0);
#elif VIEW == VIEW_OCCLUSION
    out_color = vec4(vec3(s.occlusion), 1.0);
#elif VIEW == VIEW_EMISSIVE
    out_color = vec4(s.emissive, 1.0);
#elif VIEW == VIEW_DIFFUSE
    out_color = vec4(diffuse, 1.0);
#elif VIEW == VIEW_SPECULAR
    out_color = vec4(specular, 1.0);
#elif VIEW == VIEW_IRRADIANCE
    out_color = vec4(irradiance, 1.0);
#elif VIEW == VIEW_PREFILTERED
    out_color = vec4(prefiltered, 1.0);
#elif VIEW == VIEW_SPECULAR_F0
    out_color = vec4(s.F0, s.specular_weight);
#else
    vec3 h = normalize(v + view_l);
    float NdotL = clamp(dot(n, view_l), 0.0, 1.0);
#if VIEW == VIEW_D
    out_color = vec4(vec3(D_GGX(clamp(dot(n, h), 0.0, 1.0), s.roughness)), 1.0);
#elif VIEW == VIEW_F
    out_color = vec4(s.specular_weight * F_Schlick(clamp(dot(h, v), 0.0, 1.0), s.F0), 1.0);
#elif VIEW == VIEW_G
    out_color = vec4(vec3(G_Smith(NdotV, NdotL, view_k)), 1.0);
#endif
#endif
}
