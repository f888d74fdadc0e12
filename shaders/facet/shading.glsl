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
    return s;
}

// KHR_materials_specular's specularColorFactor: the dielectric F0 per channel,
// min(F0 x colour, 1) (call after facet_surface).
void facet_surface_specular_color(inout FacetSurface s, vec3 colour) {
    s.dielectric_f0 = min(s.dielectric_f0 * colour, vec3(1.0));
    s.F0 = mix(s.dielectric_f0, s.albedo, s.metallic);
}

float facet_max3(vec3 x) { return max(max(x.r, x.g), x.b); }

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

// The Fresnel term of the specular lobe and the diffuse lobe's weight at v.h.
// glTF: mix(specular x F(0.04), F(baseColor), metallic) and (1 - specular x F(0.04))
// (1 - metallic); thesis: F(F0) (the specular weight scaling it) and (1 - F)(1 - metallic).
void facet_fresnel(FacetSurface s, float VdotH, out vec3 F, out vec3 kd) {
    float x = clamp(1.0 - VdotH, 0.0, 1.0), x2 = x * x, w = x2 * x2 * x;  // (1 - v.h)^5
    if (s.brdf == FACET_BRDF_GLTF) {
        // KHR_materials_specular: F per channel, the diffuse lobe keeps 1 - its largest.
        vec3 Fd = s.specular_factor * (s.dielectric_f0 + (1.0 - s.dielectric_f0) * w);
        F = mix(Fd, s.albedo + (1.0 - s.albedo) * w, s.metallic);
        kd = vec3((1.0 - facet_max3(Fd)) * (1.0 - s.metallic));
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
// A clear coat (facet_surface_clearcoat) dims both by 1 - weight Fc(v.h) and adds its own
// lobe to the specular, with its normal's n.l.
void facet_reflect_light(FacetSurface s, vec3 v, float NdotV, vec3 l, vec3 incident, bool punctual,
                         out vec3 diffuse, out vec3 specular) {
    diffuse = vec3(0.0);
    specular = vec3(0.0);
    float NdotL = dot(s.n, l);
    float coat_NdotL = s.clearcoat > 0.0 ? dot(s.clearcoat_n, l) : 0.0;
    if (NdotL <= 0.0 && coat_NdotL <= 0.0) return;
    vec3 h = normalize(v + l);
    float VdotH = clamp(dot(h, v), 0.0, 1.0);
    if (NdotL > 0.0) {
        vec3 F, kd;
        facet_fresnel(s, VdotH, F, kd);
        diffuse = kd * s.albedo / PI * incident * NdotL;
        specular = F * facet_specular_dg(s, NdotV, NdotL, clamp(dot(s.n, h), 0.0, 1.0), punctual) * incident * NdotL;
    }
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
// Occlusion not applied.
void facet_disk_light(FacetSurface s, vec3 v, float NdotV, FacetDiskLight disk, out vec3 diffuse, out vec3 specular) {
    vec3 c = disk.direction;
    float sin_theta = disk.sin_radius, omega = disk.solid_angle;
    float NdotC = dot(s.n, c);
    // The cap's irradiance: pi sin^2(theta) (n.c) above the horizon (exact); where the
    // horizon cuts it, the cap taken as a flat disk of radius rho = sin theta whose points
    // rise by n.c = e above the horizon at its centre: the integral of the height over the
    // visible segment, e pi rho^2 (segment share) + 2/3 (rho^2 - e^2)^1.5 (within 1-4% of
    // the sum over the cap).
    // Caps under 2 degrees (suns, lamps) are taken as points at the horizon, which then
    // cuts them within their radius alone; where the disk is a constant of the pipeline
    // (the forward pass) this choice costs nothing, and the small cap's shading skips the
    // horizon's arithmetic.
    bool wide = sin_theta > 0.035;
    float cut = clamp(NdotC + sin_theta, 0.0, 2.0 * sin_theta);
    float segment = facet_segment_share(cut * disk.inv_diameter);
    float chord = max(sin_theta * sin_theta - NdotC * NdotC, 0.0);
    float irradiance = NdotC >= sin_theta || !wide
                           ? PI * sin_theta * sin_theta * max(NdotC, 0.0)
                           : max(NdotC * PI * sin_theta * sin_theta * segment + 2.0 / 3.0 * chord * sqrt(chord), 0.0);
    // A cap the horizon cuts: its visible part stands in as the cap between the horizon and
    // the cap's top, carrying the visible segment's solid angle.
    float scale = wide || NdotC > 0.0 ? 1.0 : 0.0, inv_chord2 = disk.inv_chord2;
    if (wide && NdotC < sin_theta) {
        float sin_new = 0.5 * cut, cos_new = sqrt(max(1.0 - sin_new * sin_new, 0.0));
        vec3 across = c - NdotC * s.n;
        c = across * (inversesqrt(max(dot(across, across), 1e-12)) * cos_new) + s.n * sin_new;
        float chord2 = 2.0 * sin_new * sin_new / (1.0 + cos_new);  // 2 - 2 cos, without the cancellation
        inv_chord2 = 1.0 / max(chord2, 1e-12);
        scale = omega * segment * inv_chord2 / PI;  // the segment's solid angle over the new cap's, pi chord2
        omega = PI * chord2;
    }
    // The centre's half vector: the slope of the cap's image, F and the diffuse weight.
    vec3 h = v + c;
    h *= inversesqrt(max(dot(h, h), 1e-12));
    float VdotH = clamp(dot(v, h), 1e-4, 1.0), NdotH = clamp(dot(s.n, h), 1e-4, 1.0);
    float alpha = max(s.roughness * s.roughness, MIN_ALPHA), a2 = alpha * alpha, inv_a2 = 1.0 / a2;
    vec3 R = reflect(-v, s.n);
    float q = 1.0 / (VdotH * NdotH * NdotH * NdotH);
    float r2 = omega / (4.0 * PI) * q;                        // Omega / (4 (v.h) (n.h)^3)
    float centre_d2 = (1.0 - NdotH * NdotH) * VdotH * NdotH * q;  // tan^2 of h's angle from n
    // R's distance from the cap in radii (1 at the edge), and the weight of the near view:
    // the lobe narrower than the cap's image and R not far outside it.
    float reach2 = (2.0 - 2.0 * dot(R, c)) * inv_chord2;
    float outside = max(sqrt(reach2) - 1.0, 0.0);
    float near = r2 / (r2 + a2 + outside * outside * r2);
    float share = facet_ggx_disk_share(mix(centre_d2, r2 * reach2, near) * inv_a2, r2 * inv_a2);
    // G / (4 n.l n.v), the model's visibility, at the centre.
    float NdotL = max(dot(s.n, c), 1e-4);
    float visibility;
    if (s.brdf == FACET_BRDF_GLTF)
        visibility = V_SmithGGXCorrelated(NdotV, NdotL, alpha);
    else
        visibility = G_Smith(NdotV, NdotL, k_ibl(s.roughness)) / max(4.0 * NdotV * NdotL, 1e-8);
    vec3 F, kd;
    facet_fresnel(s, VdotH, F, kd);
    diffuse = kd * s.albedo * (irradiance / PI) * disk.radiance;
    // 4 (v.h) / (n.h) = 4 (v.h)^2 (n.h)^2 q.
    specular = F * (visibility * NdotL * 4.0 * VdotH * VdotH * NdotH * NdotH * q * share * scale) * disk.radiance;
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

// The fitted table's entry nearest to table coordinates x (n.v) and y (roughness), each in
// [0, 8] (include/facet/render/specular_lobes.h: steps + 1 entries per axis, eight halves
// each): (t0, t1, t2, w0) and (r0, r1, r2, w1). One unfiltered fetch.
void facet_lobe_entries(usampler2D lobe_table, uint brdf, float x, float y, out vec4 directions, out vec4 widths) {
    const float per_unit = facet_specular_lobe_table_steps / 8.0;
    ivec2 entry = ivec2(int(x * per_unit + 0.5), int(y * per_unit + 0.5));
    entry.y += int(brdf) * (int(facet_specular_lobe_table_steps) + 1);
    uvec4 texel = texelFetch(lobe_table, entry, 0);
    directions = vec4(unpackHalf2x16(texel.x), unpackHalf2x16(texel.y));
    widths = vec4(unpackHalf2x16(texel.z), unpackHalf2x16(texel.w));
}

FacetSpecularLookups facet_specular_lookups(FacetSurface s, vec3 v, float NdotV, float specular_levels,
                                              usampler2D lobe_table, bool fitted) {
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
    vec4 directions, widths;
    facet_lobe_entries(lobe_table, s.brdf, x, y, directions, widths);
    vec3 weights = vec3(directions.w, widths.w, 1.0 - directions.w - widths.w);
    for (int i = 0; i < 3; ++i) {
        // The axis between n and R (the table's linear weight stands for the fitted angle).
        k.direction[i] = normalize(mix(s.n, R, mix(1.0, directions[i], below)));
        // (A few lookups of negligible weight were fitted narrower: none reads below 0.35 r.)
        k.lod[i] = facet_specular_lod(max(widths[i] * below, 0.35 * s.roughness), specular_levels);
        k.weight[i] = weights[i];
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
                                              bool multiscatter, usampler2D lobe_table, bool fitted) {
    return facet_environment_light(s, v, NdotV, lut, irradiance_map, specular_map, intensity, multiscatter,
                                   facet_specular_lookups(s, v, NdotV, specular_levels, lobe_table, fitted));
}

#endif
