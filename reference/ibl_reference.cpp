#include <facet/reference/ibl_reference.h>

#include <algorithm>
#include <cmath>

namespace facet::test {

namespace {
constexpr double pi = 3.14159265358979323846;
}

Vec3 equirect_direction(double u, double v_image) {
    const double phi = (u - 0.5) * 2 * pi, theta = (0.5 - v_image) * pi;
    return {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
}

double equirect_texel_solid_angle(uint32_t y, uint32_t w, uint32_t h) {
    const double t0 = pi * (0.5 - double(y) / h), t1 = pi * (0.5 - double(y + 1) / h);
    return (2 * pi / w) * (std::sin(t0) - std::sin(t1));
}

void select_cube_face(const Vec3& d, uint32_t& face, double& s, double& t) {
    const double ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
    double sc, tc, ma;
    if (ax >= ay && ax >= az) {
        face = d[0] >= 0 ? 0 : 1;
        sc = d[0] >= 0 ? -d[2] : d[2];
        tc = -d[1];
        ma = ax;
    } else if (ay >= az) {
        face = d[1] >= 0 ? 2 : 3;
        sc = d[0];
        tc = d[1] >= 0 ? d[2] : -d[2];
        ma = ay;
    } else {
        face = d[2] >= 0 ? 4 : 5;
        sc = d[2] >= 0 ? d[0] : -d[0];
        tc = -d[1];
        ma = az;
    }
    s = 0.5 * (sc / ma + 1);
    t = 0.5 * (tc / ma + 1);
}

Vec3 cube_texel_direction(uint32_t face, uint32_t x, uint32_t y, uint32_t n) {
    // Solve the selection table for d with |major| = 1.
    const double sc = 2.0 * (x + 0.5) / n - 1, tc = 2.0 * (y + 0.5) / n - 1;
    Vec3 d;
    switch (face) {
        case 0: d = {1, -tc, -sc}; break;
        case 1: d = {-1, -tc, sc}; break;
        case 2: d = {sc, 1, tc}; break;
        case 3: d = {sc, -1, -tc}; break;
        case 4: d = {sc, -tc, 1}; break;
        default: d = {-sc, -tc, -1}; break;
    }
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return {d[0] / len, d[1] / len, d[2] / len};
}

Equirect sun_sky(uint32_t w, uint32_t h, double sun_radiance, double sun_diameter_deg, double elevation_deg,
                 double azimuth_deg) {
    const double el = elevation_deg * pi / 180, az = azimuth_deg * pi / 180;
    const Vec3 sun{std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az)};
    const double cos_radius = std::cos(0.5 * sun_diameter_deg * pi / 180);
    Equirect e{w, h, std::vector<float>(size_t(w) * h * 4)};
    const int ss = 8;
    // equirect_direction of every sub-sample, from its column's and its row's angles, each
    // computed once (the same expressions, so the same directions): an 8192-wide sky has
    // 134 million sub-samples.
    std::vector<double> cos_phi(size_t(w) * ss), sin_phi(size_t(w) * ss);
    for (uint32_t x = 0; x < w; ++x)
        for (int i = 0; i < ss; ++i) {
            const double phi = ((x + (i + 0.5) / ss) / w - 0.5) * 2 * pi;
            cos_phi[size_t(x) * ss + size_t(i)] = std::cos(phi);
            sin_phi[size_t(x) * ss + size_t(i)] = std::sin(phi);
        }
    for (uint32_t y = 0; y < h; ++y) {
        double cos_theta[ss], sin_theta[ss];
        for (int j = 0; j < ss; ++j) {
            const double theta = (0.5 - (y + (j + 0.5) / ss) / h) * pi;
            cos_theta[j] = std::cos(theta);
            sin_theta[j] = std::sin(theta);
        }
        for (uint32_t x = 0; x < w; ++x) {
            Vec3 sum{0, 0, 0};
            for (int j = 0; j < ss; ++j)
                for (int i = 0; i < ss; ++i) {
                    const size_t column = size_t(x) * ss + size_t(i);
                    const Vec3 d{cos_theta[j] * cos_phi[column], sin_theta[j], cos_theta[j] * sin_phi[column]};
                    Vec3 L;
                    if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] >= cos_radius)
                        L = {sun_radiance, sun_radiance * 0.95, sun_radiance * 0.85};
                    else if (d[1] < 0)
                        L = {0.3, 0.28, 0.25};
                    else
                        L = {0.4 + 0.6 * (1 - d[1]), 0.6 + 0.5 * (1 - d[1]), 1.0 + 0.2 * (1 - d[1])};
                    for (int c = 0; c < 3; ++c) sum[c] += L[c];
                }
            float* t = &e.rgba[(size_t(y) * w + x) * 4];
            for (int c = 0; c < 3; ++c) t[c] = float(sum[c] / (ss * ss));
            t[3] = 1;
        }
    }
    return e;
}

Equirect uniform_sky(uint32_t w, uint32_t h, float radiance) {
    Equirect e{w, h, std::vector<float>(size_t(w) * h * 4, radiance)};
    for (size_t i = 3; i < e.rgba.size(); i += 4) e.rgba[i] = 1;
    return e;
}

Equirect downsample(const Equirect& e, uint32_t f) {
    Equirect d{e.w / f, e.h / f, std::vector<float>(size_t(e.w / f) * (e.h / f) * 4)};
    for (uint32_t y = 0; y < d.h; ++y)
        for (uint32_t x = 0; x < d.w; ++x)
            for (int c = 0; c < 4; ++c) {
                double sum = 0, weight = 0;
                for (uint32_t j = 0; j < f; ++j) {
                    // Rows nearer the poles cover less solid angle: weight by it.
                    const double w_row = equirect_texel_solid_angle(y * f + j, e.w, e.h);
                    for (uint32_t i = 0; i < f; ++i) {
                        sum += w_row * e.at(x * f + i, y * f + j)[c];
                        weight += w_row;
                    }
                }
                d.rgba[(size_t(y) * d.w + x) * 4 + c] = float(sum / weight);
            }
    return d;
}

Vec3 irradiance_over_pi(const Equirect& e, const Vec3& n) {
    // Every row shares its columns' angles: their cosines and sines once, not per texel.
    std::vector<double> cos_phi(e.w), sin_phi(e.w);
    for (uint32_t x = 0; x < e.w; ++x) {
        const double phi = ((x + 0.5) / e.w - 0.5) * 2 * pi;
        cos_phi[x] = std::cos(phi);
        sin_phi[x] = std::sin(phi);
    }
    Vec3 sum{0, 0, 0};
    for (uint32_t y = 0; y < e.h; ++y) {
        const double dw = equirect_texel_solid_angle(y, e.w, e.h);
        const double theta = pi * (0.5 - (y + 0.5) / e.h), ct = std::cos(theta), st = std::sin(theta);
        for (uint32_t x = 0; x < e.w; ++x) {
            const double c = n[0] * ct * cos_phi[x] + n[1] * st + n[2] * ct * sin_phi[x];
            if (c <= 0) continue;
            const float* t = e.at(x, y);
            for (int k = 0; k < 3; ++k) sum[k] += t[k] * c * dw;
        }
    }
    return {sum[0] / pi, sum[1] / pi, sum[2] / pi};
}

double luminance(const Vec3& rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }
double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

TexelTable::TexelTable(const Equirect& e) {
        for (uint32_t y = 0; y < e.h; ++y)
            for (uint32_t x = 0; x < e.w; ++x) {
                direction.push_back(equirect_direction((x + 0.5) / e.w, (y + 0.5) / e.h));
                solid_angle.push_back(equirect_texel_solid_angle(y, e.w, e.h));
                const float* L = e.at(x, y);
                radiance.push_back({L[0], L[1], L[2]});
            }
}

Vec3 prefiltered(const TexelTable& t, const Vec3& n, double roughness) {
    const double alpha = std::max(roughness * roughness, 1e-4), a2 = alpha * alpha;
    Vec3 sum{0, 0, 0};
    double weight = 0;
    for (size_t i = 0; i < t.direction.size(); ++i) {
        const Vec3& l = t.direction[i];
        const double n_l = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        if (n_l <= 0) continue;
        // n.h for h = normalize(n + l) is sqrt((1 + n.l) / 2), so (n.h)^2 = (1 + n.l) / 2.
        const double t2 = 0.5 * (1 + n_l) * (a2 - 1) + 1;
        const double w = a2 / (pi * t2 * t2) * n_l * t.solid_angle[i];
        for (int c = 0; c < 3; ++c) sum[c] += w * t.radiance[i][c];
        weight += w;
    }
    return {sum[0] / weight, sum[1] / weight, sum[2] / weight};
}


// In half-vector space, dl = 4 (v.h) dh, so with f = D G F / (4 n.l n.v):
//   A = integral D(h) G(v,l) (1 - Fc) (v.h) / (n.v) dh over n.l > 0, B likewise with Fc.
// The (theta_h, phi) plane is mapped by u = GGX's CDF in theta_h so the grid follows the
// lobe, and u = 1 - s^2 so the weight's (1 - u)^(-1/2) growth at the horizon is removed.
Ab brdf_lut_reference(double n_v, double roughness, bool height_correlated) {
    const double alpha = std::max(roughness * roughness, 1e-4), a2 = alpha * alpha;
    const double k = roughness * roughness / 2;
    const double vx = std::sqrt(1 - n_v * n_v), vz = n_v;
    const int nu = 1024, nphi = 256;
    double a = 0, b = 0;
    for (int i = 0; i < nu; ++i) {
        const double s = (i + 0.5) / nu, u = 1 - s * s, jacobian = 2 * s;
        const double cos_t = std::sqrt((1 - u) / (1 + (a2 - 1) * u)), sin_t = std::sqrt(1 - cos_t * cos_t);
        for (int j = 0; j < nphi; ++j) {
            const double phi = 2 * pi * (j + 0.5) / nphi;
            const double hx = sin_t * std::cos(phi), hz = cos_t;
            const double v_h = vx * hx + vz * hz;
            const double l_z = 2 * v_h * hz - vz;
            if (l_z <= 0 || v_h <= 0) continue;
            double g_vis;  // G (v.h) / ((n.h) (n.v)), the weight per sample of density D (n.h)
            if (height_correlated) {
                const double vis = 0.5 / (l_z * std::sqrt(n_v * n_v * (1 - a2) + a2) +
                                          n_v * std::sqrt(l_z * l_z * (1 - a2) + a2));
                g_vis = 4 * vis * l_z * v_h / hz;
            } else {
                const double g = (n_v / (n_v * (1 - k) + k)) * (l_z / (l_z * (1 - k) + k));
                g_vis = g * v_h / (hz * n_v);
            }
            const double fc = std::pow(1 - v_h, 5);
            a += (1 - fc) * g_vis * jacobian;
            b += fc * g_vis * jacobian;
        }
    }
    return {a / (nu * nphi), b / (nu * nphi)};
}

}  // namespace facet::test
