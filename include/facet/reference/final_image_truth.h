#pragma once
// The final image's truth for both BRDF models (design.md "BRDF models"): each model's
// BRDF times n.l for one light direction, and the outgoing radiance of a surface point
// under an environment as the double-precision sum over every texel. Written from the
// equations (glTF 2.0 appendix B with KHR_materials_specular's weight; the thesis'
// Cook-Torrance), independently of the shaders.
#include <vector>

#include <facet/core/brdf_model.h>
#include <facet/reference/ibl_reference.h>

namespace facet::test {

struct TruthMaterial {
    Vec3 albedo{1, 1, 1};          // glTF baseColor (linear)
    double metallic = 0, roughness = 0.5;  // perceptual roughness: alpha = roughness^2
    double dielectric_f0 = 0.04;   // ior 1.5
    double specular_weight = 1;    // KHR_materials_specular's factor (dielectric part only)
    Vec3 specular_color{1, 1, 1};  // its colour: the dielectric F0 is min(dielectric_f0 x colour, 1)
    // KHR_materials_clearcoat: a layer of weight `clearcoat` with its own perceptual
    // roughness and unit normal (zero: the surface's normal).
    double clearcoat = 0, clearcoat_roughness = 0;
    Vec3 clearcoat_normal{0, 0, 0};
    // KHR_materials_iridescence: a thin film of weight `iridescence`, index iridescence_ior
    // and thickness in nanometres over the surface (under a clear coat, whose index 1.5 is
    // then the film's outside).
    double iridescence = 0, iridescence_ior = 1.3, iridescence_thickness = 0;
    // KHR_materials_anisotropy: the lobe stretched along anisotropy_t (its part in the
    // surface's plane, normalised), strength `anisotropy`.
    double anisotropy = 0;
    Vec3 anisotropy_t{1, 0, 0};
    // KHR_materials_sheen: a layer of colour sheen_color (black: none) and roughness
    // sheen_roughness over the material (under a clear coat).
    Vec3 sheen_color{0, 0, 0};
    double sheen_roughness = 0;
    // KHR_materials_transmission: the part of the dielectric's diffuse (0..1) given to a
    // thin-walled specular transmission (the light goes through the surface unbent).
    double transmission = 0;
};

// KHR_materials_sheen's lobe (sheenColor 1): the "Charlie" D (Conty Estevez and Kulla 2017,
// alpha = max(r^2, 1e-6)) times the extension's visibility with the paper's fitted Lambda,
// 1 / ((1 + Lambda(n.v) + Lambda(n.l)) 4 n.v n.l), for cosines in (0, 1].
double sheen_dv(double n_h, double n_v, double n_l, double roughness);
// Its directional albedo E(n.v, r): the integral of sheen_dv (n.l) over the hemisphere, by
// the midpoint rule over half vectors (512 x 128, in a variable that follows D), tabulated
// per roughness at 257 nodes in sqrt(n.v) (computed once per roughness; thread-safe).
double sheen_albedo(double n_v, double roughness);

// The extension's F_iridescence (Belcour and Barla 2017 as KHR_materials_iridescence defines
// it): the reflectance of a film of index film_ior and thickness_nm between a medium of
// index outside_ior and a base of normal-incidence reflectance base_f0 (per channel, its
// index (1 + sqrt F0) / (1 - sqrt F0)), light at cos1 to the microfacet; Schlick's F at both
// interfaces, two orders of interference integrated against Gaussian fits of the CIE 1931
// matching functions, linear Rec. 709.
Vec3 thin_film_fresnel(double outside_ior, double film_ior, double cos1, double thickness_nm, const Vec3& base_f0);

// f(l, v) |n.l| for unit n, v (towards the eye) and l (towards the light); zero when l is
// below the surface, unless the material transmits. `punctual` picks the thesis' k =
// (r+1)^2/8 instead of the environment's r^2/2 (the glTF model has no such switch).
//  gltf:   D GGX (alpha = max(r^2, 1e-4)), V height-correlated Smith,
//          dielectric = (1 - w max(Fd)) albedo/pi + w Fd D V, Fd = Schlick(F0, v.h) per
//          channel, F0 = min(dielectric_f0 x specular_color, 1) (KHR_materials_specular),
//          metal = Schlick(albedo, v.h) D V, f = mix(dielectric, metal, metallic).
//  thesis: F0 = mix(that F0, albedo, metallic), F = w' Schlick(F0, v.h) with
//          w' = mix(specular_weight, 1, metallic), kd = (1 - F)(1 - metallic),
//          f = kd albedo/pi + F D G / (4 n.l n.v), G Smith with Schlick-GGX.
//  iridescence (both models): each Schlick F above (glTF: Fd and the metal's; thesis: F)
//          mixed with thin_film_fresnel(outside, ior, v.h, thickness, its F0) by the weight.
//  anisotropy: D anisotropic GGX, alpha_t = alpha + (1 - alpha) s^2 along t, alpha_b = alpha
//          along b = n x t: 1 / (pi at ab ((t.h/at)^2 + (b.h/ab)^2 + (n.h)^2)^2); glTF's V the
//          anisotropic height-correlated Smith, 0.5 / (n.l |(at t.v, ab b.v, n.v)| + n.v |(at t.l,
//          ab b.l, n.l)|); the thesis keeps its isotropic G.
//  sheen (both models, KHR_materials_sheen's layering): f_sheen (n.l) + f (n.l) s with
//          f_sheen = sheenColor sheen_dv and the albedo scaling s = min(1 - max3(sheenColor)
//          min(E(n.v), 1), 1 - max3(sheenColor) min(E(n.l), 1)), E = sheen_albedo (taken at
//          most 1: the fitted Lambda's lobe exceeds 1 at grazing angles for small roughness);
//  transmission T (both models, KHR_materials_transmission, thin-walled): above the surface
//          the diffuse term times (1 - T); below it (n.l < 0) the specular lobe mirrored through
//          the surface, l' = l - 2 (n.l) n, h = normalize(v + l'): (1 - metallic) T albedo kd_T
//          DV(n.h, n.v, n.l') |n.l|, kd_T = 1 - w max(Fd) (glTF) or 1 - F (thesis) at v.h (what
//          the diffuse gets), DV = D V (glTF) or D G / (4 n.l' n.v) (thesis) at the roughness
//          r_T = r clamp(2 ior - 2, 0, 1), ior = (1 + sqrt F0) / (1 - sqrt F0) of dielectric_f0
//          (the Khronos sample viewer's; alpha_T = max(r_T^2, 1e-4)); anisotropy and iridescence
//          as the reflection's for l'; a sheen scales it by 1 - max3(sheenColor) min(E(n.v), 1)
//          and adds nothing below; zero where T = 0;
//  clearcoat (both models, the extension's layering): f (1 - c Fc(v.h)) (n.l) + c Fc(v.h)
//          D V of the model's specular lobe at the layer's roughness (n_c.l), Fc =
//          Schlick(0.04, v.h) (h of l', transmitted), zero where l is below both n and the
//          layer's normal n_c and the material transmits nothing.
Vec3 brdf_cos(BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v, const Vec3& l,
              bool punctual = false);

// A prepared environment: every texel's centre direction and radiance x solid angle
// (texels of zero radiance left out). Build once per environment.
struct TexelLights {
    std::vector<Vec3> dir, power;
};
TexelLights texel_lights(const Equirect& env);

// Outgoing radiance at a point with unit normal n seen along unit v (towards the eye):
// the sum of brdf_cos x power over every texel above the surface (every texel where the
// material transmits).
Vec3 environment_truth(const TexelLights& t, BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v);

}  // namespace facet::test
