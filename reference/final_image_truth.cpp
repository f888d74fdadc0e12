#include <facet/reference/final_image_truth.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

namespace facet::test {
namespace {

constexpr double pi = 3.14159265358979323846;

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Trowbridge-Reitz / GGX (Walter et al. 2007): alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2),
// the bracket summed as (1 - (n.h)^2) + (n.h)^2 alpha^2: at alpha's floor (alpha^2 1e-8)
// a2 - 1 + 1 would lose 8 of its digits.
double ggx_d(double n_h, double a2) {
    const double q = (1 - n_h * n_h) + n_h * n_h * a2;
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

// Which of the base's specular lobes layer_brdf_cos evaluates: the reflection, or
// KHR_materials_transmission's thin-walled transmission for l mirrored through the surface.
enum class Lobe { reflection, transmission };

Vec3 layer_brdf_cos(BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v, const Vec3& l,
                    bool punctual, Lobe lobe = Lobe::reflection);

// Schlick's F for a normal-incidence reflectance r0 at cos theta.
double schlick(double r0, double cos_theta) {
    const double s = 1 - std::clamp(cos_theta, 0.0, 1.0);
    return r0 + (1 - r0) * s * s * s * s * s;
}

// Normal-incidence reflectance between indices a and b, ((a - b) / (a + b))^2.
double f0_between(double a, double b) {
    const double r = (a - b) / (a + b);
    return r * r;
}

// thin_film_fresnel in two steps, so that the glTF model's two Fresnel terms (the
// dielectric's and the metal's, over different bases at the same v.h) share what depends
// on the film and the angle alone: Snell's law, the first interface and the Gaussians'
// decay, and each interference term's cosine where the two bases shift its phase alike.
// The sum is the same expression, term for term, as one thin_film_fresnel call.
class ThinFilm {
public:
    ThinFilm(double outside_ior, double film_ior, double cos1, double thickness_nm) {
        // Below 30 nm the film's index tends to the outside's, smoothly (Hermite smoothstep).
        const double t = std::clamp(thickness_nm / 30.0, 0.0, 1.0);
        film_ = outside_ior + (film_ior - outside_ior) * t * t * (3 - 2 * t);
        // Snell's law into the film.
        const double sin2_sq = (outside_ior / film_) * (outside_ior / film_) * (1 - cos1 * cos1);
        total_reflection_ = sin2_sq >= 1;
        if (total_reflection_) return;
        cos2_ = std::sqrt(1 - sin2_sq);
        R12_ = schlick(f0_between(film_, outside_ior), cos1);
        T121_ = 1 - R12_;
        // Reflection off a denser medium shifts the phase by pi (phi21 = pi - phi12).
        phi21_ = film_ < outside_ior ? 0.0 : pi;
        // Optical path difference of one round trip through the film, in nm.
        const double opd = 2 * film_ * thickness_nm * cos2_;
        for (int order = 1; order <= 2; ++order) {
            const double phase = 2 * pi * order * opd * 1e-9;
            phase_[order - 1] = phase;
            for (size_t k = 0; k < 3; ++k) decay_[order - 1][k] = std::exp(-phase * phase * variance[k]);
            decay_[order - 1][3] = std::exp(-second_x_variance * phase * phase);
        }
    }

    // The film's reflectance over a base of normal-incidence reflectance base_f0.
    Vec3 reflectance(const Vec3& base_f0) {
        if (total_reflection_) return {1, 1, 1};
        Vec3 out{};
        Vec3 R23{};
        bool shifted[3];  // the base's index below the film's: a further pi
        for (size_t c = 0; c < 3; ++c) {
            const double s = std::sqrt(std::clamp(base_f0[c], 0.0, 0.9999));
            const double base_ior = (1 + s) / (1 - s);
            R23[c] = schlick(f0_between(base_ior, film_), cos2_);
            shifted[c] = base_ior < film_;
        }
        // Per order m: cos(m (2 pi opd / lambda) + m phi) integrated against each matching
        // function. The extension's definition pairs the three channels' phase shifts with X, Y
        // and Z in that order (they differ only where the base's index is below the film's in
        // some channels and not others), and so does this.
        Vec3 sensitivity[2];
        for (int order = 1; order <= 2; ++order) {
            double xyz[3];
            for (size_t k = 0; k < 3; ++k)
                xyz[k] = amplitude[k] * std::sqrt(2 * pi * variance[k]) * cosine(order, k, shifted[k]) *
                         decay_[order - 1][k];
            xyz[0] += second_x_amplitude * std::sqrt(2 * pi * second_x_variance) * cosine(order, 3, shifted[0]) *
                      decay_[order - 1][3];
            for (double& x : xyz) x /= 1.0685e-7;
            for (size_t c = 0; c < 3; ++c)
                sensitivity[order - 1][c] = to_rgb[c][0] * xyz[0] + to_rgb[c][1] * xyz[1] + to_rgb[c][2] * xyz[2];
        }
        for (size_t c = 0; c < 3; ++c) {
            const double R123 = std::clamp(R12_ * R23[c], 1e-5, 0.9999), r123 = std::sqrt(R123);
            const double Rs = T121_ * T121_ * R23[c] / (1 - R123);
            double I = R12_ + Rs, Cm = Rs - T121_;
            for (int order = 1; order <= 2; ++order) {
                Cm *= r123;
                I += Cm * 2 * sensitivity[order - 1][c];
            }
            out[c] = std::max(I, 0.0);
        }
        return out;
    }

private:
    // The CIE 1931 matching functions as Gaussians (three for XYZ and a second lobe of X),
    // each Fourier-transformed: amplitude, centre and variance in the frequency domain.
    static constexpr double amplitude[3] = {5.4856e-13, 4.4201e-13, 5.2481e-13};
    static constexpr double centre[4] = {1.6810e+06, 1.7953e+06, 2.2084e+06, 2.2399e+06};
    static constexpr double variance[3] = {4.3278e+09, 9.3046e+09, 6.6121e+09};
    static constexpr double second_x_amplitude = 9.7470e-14, second_x_variance = 4.5282e+09;
    // Rec. 709 from XYZ (rows).
    static constexpr double to_rgb[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                            {-0.9692660, 1.8760108, 0.0415560},
                                            {0.0556434, -0.2040259, 1.0572252}};

    // cos(centre phase + m phase shift) of Gaussian `lobe` (3: X's second), computed once
    // per order, lobe and shift.
    double cosine(int order, size_t lobe, bool shifted) {
        double& memo = cosines_[order - 1][lobe][shifted];
        if (!known_[order - 1][lobe][shifted]) {
            const double phase_shift = phi21_ + (shifted ? pi : 0.0);
            memo = std::cos(centre[lobe] * phase_[order - 1] + order * phase_shift);
            known_[order - 1][lobe][shifted] = true;
        }
        return memo;
    }

    bool total_reflection_ = false;
    double film_ = 0, cos2_ = 0, R12_ = 0, T121_ = 0, phi21_ = 0;
    double phase_[2] = {};
    double decay_[2][4] = {};  // exp(-phase^2 variance) per order and lobe
    double cosines_[2][4][2] = {};
    bool known_[2][4][2] = {};
};

}  // namespace

Vec3 thin_film_fresnel(double outside_ior, double film_ior, double cos1, double thickness_nm, const Vec3& base_f0) {
    return ThinFilm(outside_ior, film_ior, cos1, thickness_nm).reflectance(base_f0);
}



namespace {

// Conty Estevez and Kulla's fit of the sheen's Lambda (KHR_materials_sheen's lambdaSheen):
// l(x) = a / (1 + b x^c) + d x + e, its coefficients interpolated by (1 - alpha)^2 between
// the paper's two fits; Lambda = exp(l(cos)) below cos 0.5, exp(2 l(0.5) - l(1 - cos)) above.
double sheen_l(double x, double alpha) {
    const double t = (1 - alpha) * (1 - alpha);
    const double a = 21.5473 + (25.3245 - 21.5473) * t, b = 3.82987 + (3.32435 - 3.82987) * t;
    const double c = 0.19823 + (0.16801 - 0.19823) * t, d = -1.97760 + (-1.27393 + 1.97760) * t;
    const double e = -4.32054 + (-4.85967 + 4.32054) * t;
    return a / (1 + b * std::pow(x, c)) + d * x + e;
}

double sheen_lambda(double cos_theta, double alpha) {
    return cos_theta < 0.5 ? std::exp(sheen_l(cos_theta, alpha))
                           : std::exp(2 * sheen_l(0.5, alpha) - sheen_l(1 - cos_theta, alpha));
}

double sheen_alpha(double roughness) { return std::max(roughness * roughness, 1e-6); }

// E(mu) by quadrature over h: with w = sin(theta_h)^(1/alpha + 2), D (n.h) dh = dw dphi / (2 pi),
// and dl = 4 (v.h) dh, so E = mean over (w, phi) of sheen_dv (n.l) 4 (v.h) / (D (n.h)) =
// (v.h) / ((1 + Lambda(n.v) + Lambda(n.l)) (n.v) (n.h)) where l = reflect(-v, h) is above.
double sheen_albedo_integral(double mu, double roughness) {
    const double alpha = sheen_alpha(roughness), k = 1 / alpha + 2;
    const double vx = std::sqrt(std::max(1 - mu * mu, 0.0)), lv = sheen_lambda(mu, alpha);
    constexpr int nw = 512, nphi = 128;
    // cos(phi) of each column, the same for every row and every node.
    static const std::array<double, nphi> cos_phi = [] {
        std::array<double, nphi> c{};
        for (int j = 0; j < nphi; ++j) {
            const double phi = (j + 0.5) / nphi * pi;  // the integrand is symmetric about the plane of n and v
            c[size_t(j)] = std::cos(phi);
        }
        return c;
    }();
    double total = 0;
    for (int i = 0; i < nw; ++i) {
        const double u = std::pow((i + 0.5) / nw, 1 / k), n_h = std::sqrt(std::max(1 - u * u, 0.0));
        for (int j = 0; j < nphi; ++j) {
            const double v_h = vx * u * cos_phi[size_t(j)] + mu * n_h, n_l = 2 * v_h * n_h - mu;
            if (v_h <= 0 || n_l <= 0) continue;
            total += v_h / ((1 + lv + sheen_lambda(n_l, alpha)) * mu * n_h);
        }
    }
    return total / (double(nw) * nphi);
}

constexpr int kSheenNodes = 257;  // in sqrt(n.v), node 0 at n.v 1e-6

std::shared_ptr<const std::vector<double>> sheen_albedo_table(double roughness) {
    static std::mutex mutex;
    static std::map<double, std::shared_ptr<const std::vector<double>>> tables;
    std::lock_guard<std::mutex> lock(mutex);
    auto& table = tables[roughness];
    if (!table) {
        auto nodes = std::make_shared<std::vector<double>>(kSheenNodes);
        for (int i = 0; i < kSheenNodes; ++i) {
            const double x = double(i) / (kSheenNodes - 1);
            (*nodes)[size_t(i)] = sheen_albedo_integral(std::max(x * x, 1e-6), roughness);
        }
        table = nodes;
    }
    return table;
}

}  // namespace

double sheen_dv(double n_h, double n_v, double n_l, double roughness) {
    const double alpha = sheen_alpha(roughness), inv = 1 / alpha;
    const double sin2h = std::max(1 - n_h * n_h, 0.0);
    const double D = (2 + inv) * std::pow(sin2h, 0.5 * inv) / (2 * pi);
    const double V = 1 / ((1 + sheen_lambda(n_v, alpha) + sheen_lambda(n_l, alpha)) * 4 * n_v * n_l);
    return D * V;
}

double sheen_albedo(double n_v, double roughness) {
    // The last table used by this thread, so that a sum over texels takes no lock.
    thread_local double last_roughness = -1;
    thread_local std::shared_ptr<const std::vector<double>> last;
    if (!last || last_roughness != roughness) {
        last = sheen_albedo_table(roughness);
        last_roughness = roughness;
    }
    const double x = std::sqrt(std::clamp(n_v, 0.0, 1.0)) * (kSheenNodes - 1);
    const int i = std::min(int(x), kSheenNodes - 2);
    const double f = x - i;
    return (*last)[size_t(i)] * (1 - f) + (*last)[size_t(i) + 1] * f;
}

Vec3 brdf_cos(BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v, const Vec3& l, bool punctual) {
    const double sheen_max = std::max({m.sheen_color[0], m.sheen_color[1], m.sheen_color[2]});
    const double n_l = dot(n, l);
    // The half vector the clear coat's Fresnel dims the base by: of l, or of l mirrored
    // through the surface where the base transmits.
    Vec3 base_l = l;
    Vec3 below{0, 0, 0};
    if (n_l > 0) {
        below = layer_brdf_cos(model, m, n, v, l, punctual);
    } else if (n_l < 0 && m.transmission > 0) {
        // KHR_materials_transmission, thin-walled: the specular lobe mirrored through the surface.
        for (size_t c = 0; c < 3; ++c) base_l[c] = l[c] - 2 * n_l * n[c];
        below = layer_brdf_cos(model, m, n, v, base_l, punctual, Lobe::transmission);
        if (sheen_max > 0) {
            // The sheen's albedo scaling on the view side only; its lobe adds nothing below.
            const double e = sheen_albedo(std::max(dot(n, v), 1e-9), m.sheen_roughness);
            const double scaling = 1 - sheen_max * std::min(e, 1.0);
            for (double& c : below) c *= scaling;
        }
    }
    if (sheen_max > 0 && n_l > 0) {
        // KHR_materials_sheen: the material below scaled by the albedo scaling, the sheen's lobe added.
        const double n_v = std::max(dot(n, v), 1e-9);
        const double scaling = std::min(1 - sheen_max * std::min(sheen_albedo(n_v, m.sheen_roughness), 1.0),
                                        1 - sheen_max * std::min(sheen_albedo(n_l, m.sheen_roughness), 1.0));
        Vec3 h{v[0] + l[0], v[1] + l[1], v[2] + l[2]};
        const double h_len = std::sqrt(dot(h, h));
        const double lobe = h_len < 1e-12 ? 0.0 : sheen_dv(std::clamp(dot(n, h) / h_len, 0.0, 1.0), n_v, n_l,
                                                           m.sheen_roughness) * n_l;
        for (size_t c = 0; c < 3; ++c) below[c] = below[c] * scaling + m.sheen_color[c] * lobe;
    }
    if (m.clearcoat <= 0) return below;
    Vec3 h{v[0] + base_l[0], v[1] + base_l[1], v[2] + base_l[2]};
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

// The transmission lobe's perceptual roughness (the Khronos glTF sample viewer's scaling):
// r clamp(2 ior - 2, 0, 1), ior = (1 + sqrt F0) / (1 - sqrt F0) of dielectric_f0, so r at
// ior 1.5 and a mirror-sharp lobe as ior -> 1. Written 4 sqrt F0 / (1 - sqrt F0) (= 2 ior - 2),
// finite for F0 = 1.
double transmission_roughness(const TruthMaterial& m) {
    const double s = std::sqrt(std::clamp(m.dielectric_f0, 0.0, 1.0));
    return m.roughness * std::clamp(4 * s / std::max(1 - s, 1e-300), 0.0, 1.0);
}

Vec3 layer_brdf_cos(BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v, const Vec3& l,
                    bool punctual, Lobe lobe) {
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
    const bool transmitted = lobe == Lobe::transmission;
    const double roughness = transmitted ? transmission_roughness(m) : m.roughness;
    const double alpha = std::max(roughness * roughness, 1e-4), a2 = alpha * alpha;
    double D = ggx_d(n_h, a2);
    // KHR_materials_anisotropy: the stretched lobe and (glTF) its visibility.
    double at = alpha, ab = alpha;
    Vec3 t{0, 0, 0}, b{0, 0, 0};
    if (m.anisotropy > 0) {
        const double tn = dot(m.anisotropy_t, n);
        t = {m.anisotropy_t[0] - tn * n[0], m.anisotropy_t[1] - tn * n[1], m.anisotropy_t[2] - tn * n[2]};
        const double t_len = std::sqrt(dot(t, t));
        for (double& c : t) c /= t_len;
        b = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
        at = alpha + (1 - alpha) * m.anisotropy * m.anisotropy;
        const double x = dot(t, h) / at, y = dot(b, h) / ab, q = x * x + y * y + n_h * n_h;
        D = 1 / (pi * at * ab * q * q);
    }
    const double s1 = 1 - v_h, schlick = s1 * s1 * s1 * s1 * s1;
    const double outside = m.clearcoat > 0 ? 1.5 : 1.0;  // what lies over a thin film
    Vec3 f;
    if (model == BrdfModel::gltf) {
        double DV = D * visibility_height_correlated(n_l, n_v, a2);
        if (m.anisotropy > 0) {
            auto length3 = [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z); };
            const double gv = n_l * length3(at * dot(t, v), ab * dot(b, v), n_v);
            const double gl = n_v * length3(at * dot(t, l), ab * dot(b, l), n_l);
            DV = D * 0.5 / std::max(gv + gl, 1e-300);
        }
        Vec3 Fd, Fm, f0s;
        for (size_t c = 0; c < 3; ++c) {
            f0s[c] = std::min(m.dielectric_f0 * m.specular_color[c], 1.0);
            Fd[c] = f0s[c] + (1 - f0s[c]) * schlick;
            Fm[c] = m.albedo[c] + (1 - m.albedo[c]) * schlick;
        }
        if (m.iridescence > 0) {
            // KHR_materials_iridescence: each Fresnel term mixed with the film's over the same base.
            ThinFilm film(outside, m.iridescence_ior, v_h, m.iridescence_thickness);
            const Vec3 film_d = film.reflectance(f0s);
            const Vec3 film_m = film.reflectance(m.albedo);
            for (size_t c = 0; c < 3; ++c) {
                Fd[c] += m.iridescence * (film_d[c] - Fd[c]);
                Fm[c] += m.iridescence * (film_m[c] - Fm[c]);
            }
        }
        // The dielectric's diffuse and transmission both take what its specular leaves.
        const double kd = 1 - m.specular_weight * std::max({Fd[0], Fd[1], Fd[2]});
        for (size_t c = 0; c < 3; ++c) {
            if (transmitted) {
                f[c] = (1 - m.metallic) * m.transmission * m.albedo[c] * kd * DV;
                continue;
            }
            const double dielectric =
                (1 - m.transmission) * kd * m.albedo[c] / pi + m.specular_weight * Fd[c] * DV;
            const double metal = Fm[c] * DV;
            f[c] = (1 - m.metallic) * dielectric + m.metallic * metal;
        }
    } else {
        const double r = roughness;
        const double k = punctual ? (r + 1) * (r + 1) / 8 : r * r / 2;
        const double G = schlick_g1(n_v, k) * schlick_g1(n_l, k);
        const double spec = D * G / (4 * n_l * n_v);
        const double w = m.specular_weight * (1 - m.metallic) + m.metallic;
        Vec3 f0s;
        for (size_t c = 0; c < 3; ++c)
            f0s[c] = std::min(m.dielectric_f0 * m.specular_color[c], 1.0) * (1 - m.metallic) + m.albedo[c] * m.metallic;
        const Vec3 film = m.iridescence > 0
                              ? thin_film_fresnel(outside, m.iridescence_ior, v_h, m.iridescence_thickness, f0s)
                              : Vec3{0, 0, 0};
        for (size_t c = 0; c < 3; ++c) {
            const double schlick_f = f0s[c] + (1 - f0s[c]) * schlick;
            const double F = w * (schlick_f + m.iridescence * (film[c] - schlick_f));
            const double kd = (1 - F) * (1 - m.metallic);
            f[c] = transmitted ? m.transmission * m.albedo[c] * kd * spec
                               : (1 - m.transmission) * kd * m.albedo[c] / pi + F * spec;
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

namespace {

// environment_truth for a material with no layer and no extension (every pixel of
// builtin:spheres, the accuracy benchmark's scene): layer_brdf_cos's reflection, term by term
// the same expressions, with what depends only on the material, n and v worked out once
// instead of at every texel (the truths of the test suite spent most of their time there).
// final_image_truth_test holds it to brdf_cos.
Vec3 plain_environment_truth(const TexelLights& t, BrdfModel model, const TruthMaterial& m, const Vec3& n,
                             const Vec3& v) {
    const double n_v = std::max(dot(n, v), 1e-9);
    const double alpha = std::max(m.roughness * m.roughness, 1e-4), a2 = alpha * alpha;
    const bool gltf = model == BrdfModel::gltf;
    // glTF: f = A kd + (w Fd (1 - metallic) + Fm metallic) D V per channel, Fd and Fm Schlick's
    // of f0s and albedo, kd = 1 - w max(Fd) (Fd's largest channel is its largest F0's).
    // Thesis: f = kd albedo / pi + F spec, F = w' Schlick(F0), kd = (1 - F)(1 - metallic).
    Vec3 f0s, diffuse;
    double f0_max = 0;
    const double w = gltf ? m.specular_weight : m.specular_weight * (1 - m.metallic) + m.metallic;
    for (size_t c = 0; c < 3; ++c) {
        f0s[c] = std::min(m.dielectric_f0 * m.specular_color[c], 1.0);
        if (!gltf) f0s[c] = f0s[c] * (1 - m.metallic) + m.albedo[c] * m.metallic;
        f0_max = std::max(f0_max, f0s[c]);
        diffuse[c] = m.albedo[c] / pi;
    }
    const double k = m.roughness * m.roughness / 2;  // the thesis' environment k
    const double g1_v = schlick_g1(n_v, k);
    Vec3 sum{0, 0, 0};
    for (size_t i = 0; i < t.dir.size(); ++i) {
        const Vec3& l = t.dir[i];
        const double n_l = dot(n, l);
        if (n_l <= 0) continue;
        const Vec3 h{v[0] + l[0], v[1] + l[1], v[2] + l[2]};  // not normalised: the cosines divide by its length
        const double h_len = std::sqrt(dot(h, h));
        if (h_len < 1e-12) continue;
        const double n_h = std::clamp(dot(n, h) / h_len, 0.0, 1.0), v_h = std::clamp(dot(v, h) / h_len, 0.0, 1.0);
        const double D = ggx_d(n_h, a2);
        const double s1 = 1 - v_h, schlick = s1 * s1 * s1 * s1 * s1;
        Vec3 f;
        if (gltf) {
            const double DV = D * visibility_height_correlated(n_l, n_v, a2);
            const double kd = 1 - w * (f0_max + (1 - f0_max) * schlick);
            for (size_t c = 0; c < 3; ++c) {
                const double Fd = f0s[c] + (1 - f0s[c]) * schlick;
                const double Fm = m.albedo[c] + (1 - m.albedo[c]) * schlick;
                f[c] = (1 - m.metallic) * (kd * diffuse[c] + w * Fd * DV) + m.metallic * (Fm * DV);
            }
        } else {
            const double spec = D * (g1_v * schlick_g1(n_l, k)) / (4 * n_l * n_v);
            for (size_t c = 0; c < 3; ++c) {
                const double F = w * (f0s[c] + (1 - f0s[c]) * schlick);
                f[c] = (1 - F) * (1 - m.metallic) * diffuse[c] + F * spec;
            }
        }
        for (size_t c = 0; c < 3; ++c) sum[c] += f[c] * n_l * t.power[i][c];
    }
    return sum;
}

}  // namespace

Vec3 environment_truth(const TexelLights& t, BrdfModel model, const TruthMaterial& m, const Vec3& n, const Vec3& v) {
    const bool plain = m.clearcoat <= 0 && m.iridescence <= 0 && m.anisotropy <= 0 && m.transmission <= 0 &&
                       std::max({m.sheen_color[0], m.sheen_color[1], m.sheen_color[2]}) <= 0;
    if (plain) return plain_environment_truth(t, model, m, n, v);
    Vec3 sum{0, 0, 0};
    for (size_t i = 0; i < t.dir.size(); ++i) {
        // Below the horizon (of the surface and of its clear coat) of a material that
        // transmits nothing: brdf_cos is 0.
        if (m.transmission <= 0 && dot(n, t.dir[i]) <= 0 &&
            (m.clearcoat <= 0 || dot(coat_normal(m, n), t.dir[i]) <= 0))
            continue;
        const Vec3 f = brdf_cos(model, m, n, v, t.dir[i]);
        for (size_t c = 0; c < 3; ++c) sum[c] += f[c] * t.power[i][c];
    }
    return sum;
}

}  // namespace facet::test
