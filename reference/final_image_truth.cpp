#include <facet/reference/final_image_truth.h>

#include <algorithm>
#include <cmath>

namespace facet::test {
namespace {

constexpr double pi = 3.14159265358979323846;

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Trowbridge-Reitz / GGX (Walter et al. 2007): alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
double ggx_d(double n_h, double a2) {
    const double q = n_h * n_h * (a2 - 1) + 1;
    return a2 / (pi * q * q);
}

// glTF appendix B's V = G / (4 n.l n.v) with the height-correlated Smith G.
double visibility_height_correlated(double n_l, double n_v, double a2) {
    const double gl = n_v * std::sqrt(n_l * n_l * (1 - a2) + a2);
    const double gv = n_l * std::sqrt(n_v * n_v * (1 - a2) + a2);
    return 0.5 / std::max(gl + gv, 1e-300);
}

// Schlick-GGX's one-direction factor x / (x (1 - k) + k).
double schlick_g1(double x, double k) { return x / (x * (1 - k) + k); }

// The layer's normal: its own, or the surface's.
const Vec3& coat_normal(const TruthMaterial& m, const Vec3& n) {
    const Vec3& c = m.clearcoat_normal;
    return c[0] == 0 && c[1] == 0 && c[2] == 0 ? n : c;
}

Vec3 layer_brdf_cos(BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v, const Vec3& l,
                    bool punctual);

}  // namespace

Vec3 brdf_cos(BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v, const Vec3& l, bool punctual) {
    const Vec3 below = layer_brdf_cos(model, m, n, v, l, punctual);
    if (m.clearcoat <= 0) return below;
    Vec3 h{v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    const double h_len = std::sqrt(dot(h, h));
    if (h_len < 1e-12) return below;
    const double v_h = std::clamp(dot(v, h) / h_len, 0.0, 1.0), s1 = 1 - v_h;
    const double coat = m.clearcoat * (0.04 + 0.96 * s1 * s1 * s1 * s1 * s1);
    // The layer: a dielectric of F0 0.04 with no diffuse lobe; its F is Fc, so its
    // brdf_cos times the weight is c Fc D V (n_c.l).
    TruthMaterial layer;
    layer.albedo = {0, 0, 0};
    layer.roughness = m.clearcoat_roughness;
    const Vec3 top = layer_brdf_cos(model, layer, coat_normal(m, n), v, l, punctual);
    Vec3 f;
    for (size_t c = 0; c < 3; ++c) f[c] = (1 - coat) * below[c] + m.clearcoat * top[c];
    return f;
}

namespace {

Vec3 layer_brdf_cos(BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v, const Vec3& l,
                    bool punctual) {
    const double n_l = dot(n, l);
    if (n_l <= 0) return {0, 0, 0};
    // Grazing views: clamped away from 0 so that the thesis' 1 / (4 n.l n.v) stays finite
    // (its G carries n.v, so the product tends to a finite value).
    const double n_v = std::max(dot(n, v), 1e-9);
    Vec3 h{v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    const double h_len = std::sqrt(dot(h, h));
    if (h_len < 1e-12) return {0, 0, 0};  // l opposite v: no microfacet reflects it
    for (double& c : h) c /= h_len;
    const double n_h = std::clamp(dot(n, h), 0.0, 1.0), v_h = std::clamp(dot(v, h), 0.0, 1.0);
    const double alpha = std::max(m.roughness * m.roughness, 1e-4), a2 = alpha * alpha;
    const double D = ggx_d(n_h, a2);
    const double s1 = 1 - v_h, schlick = s1 * s1 * s1 * s1 * s1;
    Vec3 f;
    if (model == BrdfModel::gltf) {
        const double DV = D * visibility_height_correlated(n_l, n_v, a2);
        Vec3 Fd;
        for (size_t c = 0; c < 3; ++c) {
            const double f0 = std::min(m.dielectric_f0 * m.specular_color[c], 1.0);
            Fd[c] = f0 + (1 - f0) * schlick;
        }
        const double Fd_max = std::max({Fd[0], Fd[1], Fd[2]});
        for (size_t c = 0; c < 3; ++c) {
            const double dielectric =
                (1 - m.specular_weight * Fd_max) * m.albedo[c] / pi + m.specular_weight * Fd[c] * DV;
            const double metal = (m.albedo[c] + (1 - m.albedo[c]) * schlick) * DV;
            f[c] = (1 - m.metallic) * dielectric + m.metallic * metal;
        }
    } else {
        const double r = m.roughness;
        const double k = punctual ? (r + 1) * (r + 1) / 8 : r * r / 2;
        const double G = schlick_g1(n_v, k) * schlick_g1(n_l, k);
        const double spec = D * G / (4 * n_l * n_v);
        const double w = m.specular_weight * (1 - m.metallic) + m.metallic;
        for (size_t c = 0; c < 3; ++c) {
            const double f0 =
                std::min(m.dielectric_f0 * m.specular_color[c], 1.0) * (1 - m.metallic) + m.albedo[c] * m.metallic;
            const double F = w * (f0 + (1 - f0) * schlick);
            f[c] = (1 - F) * (1 - m.metallic) * m.albedo[c] / pi + F * spec;
        }
    }
    return {f[0] * n_l, f[1] * n_l, f[2] * n_l};
}

}  // namespace

TexelLights texel_lights(const Equirect& env) {
    TexelLights t;
    t.dir.reserve(size_t(env.w) * env.h);
    t.power.reserve(size_t(env.w) * env.h);
    for (uint32_t y = 0; y < env.h; ++y) {
        const double dw = equirect_texel_solid_angle(y, env.w, env.h);
        for (uint32_t x = 0; x < env.w; ++x) {
            const float* L = env.at(x, y);
            if (L[0] == 0 && L[1] == 0 && L[2] == 0) continue;
            t.dir.push_back(equirect_direction((x + 0.5) / env.w, (y + 0.5) / env.h));
            t.power.push_back({L[0] * dw, L[1] * dw, L[2] * dw});
        }
    }
    return t;
}

Vec3 environment_truth(const TexelLights& t, BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v) {
    Vec3 sum{0, 0, 0};
    for (size_t i = 0; i < t.dir.size(); ++i) {
        // Below the horizon (of the surface and of its clear coat): brdf_cos is 0.
        if (dot(n, t.dir[i]) <= 0 && (m.clearcoat <= 0 || dot(coat_normal(m, n), t.dir[i]) <= 0)) continue;
        const Vec3 f = brdf_cos(model, m, n, v, t.dir[i]);
        for (size_t c = 0; c < 3; ++c) sum[c] += f[c] * t.power[i][c];
    }
    return sum;
}

}  // namespace facet::test
