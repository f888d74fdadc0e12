#include "support/render_truth.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace facet::test {
namespace {

constexpr double pi = 3.14159265358979323846;

struct Texel {
    Vec3 dir;
    Vec3 radiance_solid_angle;  // L * dw
};

// Every texel of the environment, each split into s x s sub-directions (the radiance is
// constant over a texel) so that narrow lobes are resolved.
std::vector<Texel> texels(const test::Equirect& e, uint32_t s) {
    std::vector<Texel> out;
    out.reserve(size_t(e.w) * e.h * s * s);
    for (uint32_t y = 0; y < e.h; ++y) {
        const double dw = test::equirect_texel_solid_angle(y, e.w, e.h) / (s * s);
        for (uint32_t x = 0; x < e.w; ++x) {
            const float* l = e.at(x, y);
            for (uint32_t j = 0; j < s; ++j)
                for (uint32_t i = 0; i < s; ++i) {
                    // Sub-texels of equal solid angle would need sin-spaced rows; at the
                    // latitudes that matter the difference is far below the bounds.
                    const Vec3 d = test::equirect_direction((x + (i + 0.5) / s) / e.w, (y + (j + 0.5) / s) / e.h);
                    out.push_back({d, {l[0] * dw, l[1] * dw, l[2] * dw}});
                }
        }
    }
    return out;
}

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 normalized(const Vec3& a) {
    const double l = std::sqrt(dot(a, a));
    return {a[0] / l, a[1] / l, a[2] / l};
}

struct Material {
    double roughness, metallic;
    Vec3 albedo;
};

// Outgoing radiance towards v: sum over texels of f(v, l) L(l) (n.l) dw.
Vec3 reflected(const std::vector<Texel>& env, const Vec3& n, const Vec3& v, const Material& m) {
    const double alpha = std::max(m.roughness * m.roughness, 1e-4), a2 = alpha * alpha;
    const double k = m.roughness * m.roughness / 2.0;
    const double nv = std::max(dot(n, v), 0.0);
    const double gv = nv / (nv * (1 - k) + k);
    Vec3 f0, sum{0, 0, 0};
    for (int c = 0; c < 3; ++c) f0[c] = 0.04 * (1 - m.metallic) + m.albedo[c] * m.metallic;
    for (const Texel& t : env) {
        const double nl = dot(n, t.dir);
        if (nl <= 0) continue;
        const Vec3 h = normalized({v[0] + t.dir[0], v[1] + t.dir[1], v[2] + t.dir[2]});
        const double nh = std::max(dot(n, h), 0.0), hv = std::max(dot(h, v), 0.0);
        const double q = nh * nh * (a2 - 1) + 1;
        const double D = a2 / (pi * q * q);
        const double G = gv * nl / (nl * (1 - k) + k);
        const double fresnel_weight = std::pow(1 - hv, 5);
        for (int c = 0; c < 3; ++c) {
            const double F = f0[c] + (1 - f0[c]) * fresnel_weight;
            const double f = (1 - F) * (1 - m.metallic) * m.albedo[c] / pi + D * F * G / std::max(4 * nl * nv, 1e-12);
            sum[c] += f * t.radiance_solid_angle[c] * nl;
        }
    }
    return sum;
}

// Radiance of the environment towards d, bilinear between texel centres (u wraps), or
// the texel's own value (the reference renderer's piecewise-constant environment).
Vec3 sample_bilinear(const test::Equirect& e, const Vec3& d, bool nearest = false) {
    const double u = std::atan2(d[2], d[0]) / (2 * pi) + 0.5, v_image = 0.5 - std::asin(std::clamp(d[1], -1.0, 1.0)) / pi;
    if (nearest) {
        const uint32_t x = std::min(uint32_t(u * e.w), e.w - 1), y = std::min(uint32_t(v_image * e.h), e.h - 1);
        return {e.at(x, y)[0], e.at(x, y)[1], e.at(x, y)[2]};
    }
    const double x = u * e.w - 0.5, y = std::clamp(v_image * e.h - 0.5, 0.0, e.h - 1.0);
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    Vec3 out{0, 0, 0};
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const uint32_t xx = uint32_t((x0 + i + int(e.w)) % int(e.w)), yy = uint32_t(std::min(y0 + j, int(e.h) - 1));
            const double w = (i ? fx : 1 - fx) * (j ? fy : 1 - fy);
            for (int c = 0; c < 3; ++c) out[size_t(c)] += w * e.at(xx, yy)[c];
        }
    return out;
}

// Roughness 0: every microfacet is n, so the specular part is the mirror image
// F(n.v) L(R) and the diffuse part has kd = (1 - F(n.v))(1 - metalness).
Vec3 reflected_mirror(const test::Equirect& e, const std::vector<Texel>& env, const Vec3& n, const Vec3& v,
                      const Material& m, bool nearest = false) {
    const double nv = std::max(dot(n, v), 0.0);
    Vec3 irradiance{0, 0, 0};
    for (const Texel& t : env) {
        const double nl = dot(n, t.dir);
        if (nl > 0)
            for (int c = 0; c < 3; ++c) irradiance[size_t(c)] += t.radiance_solid_angle[size_t(c)] * nl;
    }
    const Vec3 r{2 * nv * n[0] - v[0], 2 * nv * n[1] - v[1], 2 * nv * n[2] - v[2]};
    const Vec3 mirror = sample_bilinear(e, normalized(r), nearest);
    Vec3 out;
    for (int c = 0; c < 3; ++c) {
        const double f0 = 0.04 * (1 - m.metallic) + m.albedo[size_t(c)] * m.metallic;
        const double F = f0 + (1 - f0) * std::pow(1 - nv, 5);
        out[size_t(c)] = (1 - F) * (1 - m.metallic) * m.albedo[size_t(c)] / pi * irradiance[size_t(c)] +
                         F * mirror[size_t(c)];
    }
    return out;
}


// Sphere of a world position: the grid of builtin:spheres (7 x 7, 2.5 m apart).
int sphere_of(const float* p) {
    const int col = int(std::lround(p[0] / 2.5 + 3)), row = int(std::lround(p[1] / 2.5 + 3));
    return row * 7 + col;
}

}  // namespace

std::vector<SphereSample> sphere_samples(const std::vector<float>& normals, const std::vector<float>& positions,
                                         uint32_t W, uint32_t H, uint32_t per_sphere_count) {
    std::vector<std::vector<uint32_t>> per_sphere(49);
    for (uint32_t y = 1; y + 1 < H; ++y)
        for (uint32_t x = 1; x + 1 < W; ++x) {
            const size_t i = size_t(y) * W + x;
            if (normals[i * 4 + 3] < 1.0f) continue;
            const int s = sphere_of(&positions[i * 4]);
            bool interior = s >= 0 && s < 49;
            for (int dy = -1; dy <= 1 && interior; ++dy)
                for (int dx = -1; dx <= 1 && interior; ++dx) {
                    const size_t j = size_t(int(y) + dy) * W + size_t(int(x) + dx);
                    interior = normals[j * 4 + 3] == 1.0f && sphere_of(&positions[j * 4]) == s;
                }
            if (interior) per_sphere[size_t(s)].push_back(uint32_t(i));
        }
    std::vector<SphereSample> samples;
    for (int s = 0; s < 49; ++s) {
        const auto& list = per_sphere[size_t(s)];
        if (list.size() < 100) return {};
        for (size_t k = 0; k < per_sphere_count; ++k) samples.push_back({list[k * list.size() / per_sphere_count], s});
    }
    return samples;
}

SpheresTruth spheres_truth(const Equirect& env, const Vec3& eye, const std::vector<float>& normals,
                           const std::vector<float>& positions, const std::vector<SphereSample>& samples) {
    const std::vector<Texel> coarse = texels(env, 1), fine = texels(env, 4);
    SpheresTruth truth{std::vector<Vec3>(samples.size()), std::vector<Vec3>(samples.size())};
    auto work = [&](size_t begin, size_t step) {
        for (size_t k = begin; k < samples.size(); k += step) {
            const size_t i = samples[k].pixel;
            const int col = samples[k].sphere % 7, row = samples[k].sphere / 7;
            const Material m{col / 6.0, row / 6.0, {0.5, 0.0, 0.0}};
            const Vec3 n = normalized({normals[i * 4], normals[i * 4 + 1], normals[i * 4 + 2]});
            const Vec3 p{positions[i * 4], positions[i * 4 + 1], positions[i * 4 + 2]};
            const Vec3 v = normalized({eye[0] - p[0], eye[1] - p[1], eye[2] - p[2]});
            // Roughness 0 is a mirror: no texel sum resolves a delta lobe. Roughness 1/6
            // splits every texel 4 x 4.
            truth.bilinear[k] =
                col == 0 ? reflected_mirror(env, coarse, n, v, m) : reflected(col == 1 ? fine : coarse, n, v, m);
            truth.nearest[k] = col == 0 ? reflected_mirror(env, coarse, n, v, m, true) : truth.bilinear[k];
        }
    };
    std::thread other(work, 1, 2);
    work(0, 2);
    other.join();
    return truth;
}

double relative_rmse(const std::vector<Vec3>& truth, const std::vector<float>& hdr,
                     const std::vector<SphereSample>& samples, const std::function<bool(const SphereSample&)>& keep) {
    double err2 = 0, ref2 = 0;
    for (size_t k = 0; k < samples.size(); ++k) {
        if (!keep(samples[k])) continue;
        for (size_t c = 0; c < 3; ++c) {
            const double d = hdr[samples[k].pixel * 4 + c] - truth[k][c];
            err2 += d * d;
            ref2 += truth[k][c] * truth[k][c];
        }
    }
    return ref2 > 0 ? std::sqrt(err2 / ref2) : 0.0;
}

}  // namespace facet::test
