// The forward pass's image against ground truth: builtin:spheres (roughness across,
// metalness down) under a real sunny environment, linear EXR-equivalent readback with
// the normal and position views, every sampled pixel compared with the brute-force
// integral of the same BRDF (Cook-Torrance: GGX, Fresnel-Schlick, Smith/Schlick-GGX
// with k = r^2/2, kd = (1 - F)(1 - metalness), Lambert) over every environment texel,
// in double precision, written here independently of the shaders. What remains is the
// split sum's own error (prefiltering with n = v = R, F0-split LUT), reported per
// roughness and bounded. The engine's own reference mode (Monte Carlo, MIS) is checked
// against the same sums and for convergence.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "io/environment_image.h"
#include "io/image_io.h"
#include "render_job.h"
#include "support/gpu_test.h"
#include "support/ibl_reference.h"

namespace facet {
namespace {

using test::Vec3;
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

TEST(RenderGroundTruth, SpheresUnderASunnyEnvironment) {
    Context& context = test::gpu();
    const uint32_t messages = context.validation_message_count();
    // venice_sunset: a low sun about 1e3 times the sky. Downsampled 4x; the render and
    // the truth use the same downsampled file.
    auto loaded = load_environment(FACET_SHARED_DATA_DIR "/env/venice_sunset_1k.hdr");
    ASSERT_TRUE(loaded) << loaded.error().message;
    test::Equirect full{loaded->width, loaded->height, loaded->rgba};
    const test::Equirect env = test::downsample(full, 4);
    const std::string env_path =
        (std::filesystem::temp_directory_path() / ("facet_truth_env_" + std::to_string(::getpid()) + ".exr")).string();
    ASSERT_TRUE(write_hdr_image(env_path, env.w, env.h, env.rgba));

    RenderJob job;
    job.model = "builtin:spheres";
    job.env = env_path;
    job.frame.width = job.frame.height = 280;
    job.frame.skybox = false;
    job.frame.views = {View::normal, View::position};
    auto session = RenderSession::create(context, job);
    ASSERT_TRUE(session) << session.error().message;
    auto images = (*session)->render_frame();
    ASSERT_TRUE(images) << images.error().message;
    // The same frame with the specular lookup bent towards n (Frostbite's dominant
    // direction); same camera, so the same pixels.
    job.frame.dominant_direction = true;
    auto dominant_session = RenderSession::create(context, job);
    std::filesystem::remove(env_path);
    ASSERT_TRUE(dominant_session) << dominant_session.error().message;
    auto dominant = (*dominant_session)->render_frame();
    ASSERT_TRUE(dominant) << dominant.error().message;
    const Vec3 eye{(*session)->camera().position.x, (*session)->camera().position.y, (*session)->camera().position.z};
    const uint32_t W = images->width, H = images->height;
    const std::vector<float>&normals = images->views[0].second, &positions = images->views[1].second;

    // Sphere of a world position: the grid of builtin:spheres (7 x 7, 2.5 m apart).
    auto sphere_of = [](const float* p) {
        const int col = int(std::lround(p[0] / 2.5 + 3)), row = int(std::lround(p[1] / 2.5 + 3));
        return row * 7 + col;
    };
    struct Sample {
        uint32_t pixel;
        int sphere;
    };
    // Interior pixels only (all 3x3 neighbours on the same sphere), up to 24 per sphere
    // spread over its disk.
    std::vector<std::vector<uint32_t>> per_sphere(49);
    for (uint32_t y = 1; y + 1 < H; ++y)
        for (uint32_t x = 1; x + 1 < W; ++x) {
            const size_t i = size_t(y) * W + x;
            if (normals[i * 4 + 3] < 1.0f || images->hdr[i * 4 + 3] < 1.0f) continue;
            const int s = sphere_of(&positions[i * 4]);
            bool interior = s >= 0 && s < 49;
            for (int dy = -1; dy <= 1 && interior; ++dy)
                for (int dx = -1; dx <= 1 && interior; ++dx) {
                    const size_t j = size_t(int(y) + dy) * W + size_t(int(x) + dx);
                    interior = normals[j * 4 + 3] == 1.0f && sphere_of(&positions[j * 4]) == s;
                }
            if (interior) per_sphere[size_t(s)].push_back(uint32_t(i));
        }
    std::vector<Sample> samples;
    for (int s = 0; s < 49; ++s) {
        const auto& list = per_sphere[size_t(s)];
        ASSERT_GT(list.size(), 100u) << "sphere " << s;
        for (size_t k = 0; k < 24; ++k) samples.push_back({list[k * list.size() / 24], s});
    }

    const std::vector<Texel> coarse = texels(env, 1), fine = texels(env, 4);
    std::vector<Vec3> truth(samples.size()), truth_nearest(samples.size());
    auto work = [&](size_t begin, size_t step) {
        for (size_t k = begin; k < samples.size(); k += step) {
            const size_t i = samples[k].pixel;
            const int col = samples[k].sphere % 7, row = samples[k].sphere / 7;
            const Material m{col / 6.0, row / 6.0, {0.5, 0.0, 0.0}};
            const Vec3 n = normalized({normals[i * 4], normals[i * 4 + 1], normals[i * 4 + 2]});
            const Vec3 p{positions[i * 4], positions[i * 4 + 1], positions[i * 4 + 2]};
            const Vec3 v = normalized({eye[0] - p[0], eye[1] - p[1], eye[2] - p[2]});
            // Roughness 0 is a mirror: no texel sum resolves a delta lobe.
            truth[k] = col == 0 ? reflected_mirror(env, coarse, n, v, m) : reflected(col == 1 ? fine : coarse, n, v, m);
            truth_nearest[k] = col == 0 ? reflected_mirror(env, coarse, n, v, m, true) : truth[k];
        }
    };
    std::thread other(work, 1, 2);
    work(0, 2);
    other.join();

    // Relative RMS error over the samples of one roughness column (row -1: every row).
    auto rel_rmse_against = [&](const std::vector<Vec3>& want, const RenderedImages& image, int col, int row) {
        double err2 = 0, ref2 = 0;
        for (size_t k = 0; k < samples.size(); ++k)
            if (samples[k].sphere % 7 == col && (row < 0 || samples[k].sphere / 7 == row))
                for (size_t c = 0; c < 3; ++c) {
                    const double d = image.hdr[samples[k].pixel * 4 + c] - want[k][c];
                    err2 += d * d;
                    ref2 += want[k][c] * want[k][c];
                }
        return std::sqrt(err2 / ref2);
    };
    auto rel_rmse_of = [&](const RenderedImages& image, int col, int row) {
        return rel_rmse_against(truth, image, col, row);
    };
    auto worst_of = [&](const RenderedImages& image, int col) {
        double mean = 0, worst = 0;
        int count = 0;
        for (size_t k = 0; k < samples.size(); ++k)
            if (samples[k].sphere % 7 == col) mean += truth[k][0] + truth[k][1] + truth[k][2], ++count;
        mean /= 3 * count;
        for (size_t k = 0; k < samples.size(); ++k)
            for (size_t c = 0; c < 3 && samples[k].sphere % 7 == col; ++c) {
                const double got = image.hdr[samples[k].pixel * 4 + c], want = truth[k][c];
                EXPECT_TRUE(std::isfinite(got));
                if (want > 0.05 * mean) worst = std::max(worst, std::abs(got - want) / want);
            }
        return worst;
    };
    // Bounds: the measured split-sum error on this machine times about 1.5 (see the
    // README's accuracy table); roughness 0 compares with the bilinear mirror image.
    const double bound[7] = {0.03, 0.03, 0.04, 0.065, 0.1, 0.1, 0.1};
    std::printf("lookup    roughness  relRMSE   max rel*  dielectric  metal   (* pixels over 5%% of the mean)\n");
    for (const auto& [name, image] : {std::pair<const char*, const RenderedImages*>{"mirror", &*images},
                                      {"dominant", &*dominant}})
        for (int col = 0; col < 7; ++col) {
            const double rel_rmse = rel_rmse_of(*image, col, -1);
            std::printf("%-9s %9.3f  %7.4f   %7.4f   %7.4f   %7.4f\n", name, col / 6.0, rel_rmse, worst_of(*image, col),
                        rel_rmse_of(*image, col, 0), rel_rmse_of(*image, col, 6));
            EXPECT_LT(rel_rmse, bound[col]) << name << " roughness " << col / 6.0;
        }
    // The reference mode (Monte Carlo with MIS over the same texels) agrees with the
    // brute-force sums and converges: 16x the samples, about 4x less error (a bias would
    // hold the ratio down).
    double total_error[2] = {};
    const uint32_t sample_counts[2] = {64, 1024};
    std::printf("reference spp  roughness  relRMSE\n");
    for (int i = 0; i < 2; ++i) {
        ReferenceSettings settings;
        settings.min_samples = settings.max_samples = sample_counts[i];
        settings.noise_target = 0;
        ReferenceStats stats;
        auto reference = (*session)->render_reference(settings, {}, &stats);
        ASSERT_TRUE(reference) << reference.error().message;
        EXPECT_EQ(stats.samples, sample_counts[i]);
        double err2 = 0, ref2 = 0;
        for (int col = 0; col < 7; ++col) {
            const double e = rel_rmse_against(truth_nearest, *reference, col, -1);
            std::printf("%13u  %9.3f  %7.4f\n", sample_counts[i], col / 6.0, e);
            // At 1024 samples what is left is noise of about 2-3% (a sun 1e3 times the sky).
            if (i == 1) EXPECT_LT(e, 0.05) << "reference, roughness " << col / 6.0;
        }
        for (size_t k = 0; k < samples.size(); ++k)
            for (size_t c = 0; c < 3; ++c) {
                const double d = reference->hdr[samples[k].pixel * 4 + c] - truth_nearest[k][c];
                err2 += d * d;
                ref2 += truth_nearest[k][c] * truth_nearest[k][c];
            }
        total_error[i] = std::sqrt(err2 / ref2);
    }
    std::printf("reference: relRMSE %.4f at 64 spp, %.4f at 1024 spp\n", total_error[0], total_error[1]);
    EXPECT_LT(total_error[1], total_error[0] / 3.0);

    // Where the split sum is worst, rough metals, the dominant direction halves the error.
    for (int col : {5, 6}) EXPECT_LT(rel_rmse_of(*dominant, col, 6), 0.5 * rel_rmse_of(*images, col, 6)) << col;
    EXPECT_EQ(context.validation_message_count(), messages);
}

}  // namespace
}  // namespace facet
