// The forward pass's image against ground truth (support/render_truth.h): builtin:spheres
// under real and synthetic environments with a sun, the normal and position views, each
// sampled pixel compared with the brute-force integral of the same BRDF over every
// environment texel in double precision. What remains is the split sum's own error
// (prefiltering with n = v = R, the F0 split of the LUT), reported per roughness and
// metalness and bounded; then what cuts it (the dominant direction, light extraction),
// and the engine's reference mode (Monte Carlo, MIS) against the same sums.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <facet/io/environment_image.h>
#include <facet/io/image_io.h>
#include <facet/render/render_job.h>
#include "support/gpu_test.h"
#include "support/render_truth.h"

namespace facet {
namespace {

using test::SphereSample;
using test::Vec3;

auto column = [](int col) { return [col](const SphereSample& s) { return s.sphere % 7 == col; }; };
auto column_row = [](int col, int row) {
    return [col, row](const SphereSample& s) { return s.sphere % 7 == col && s.sphere / 7 == row; };
};

// An environment written to a temporary .exr for the renderer (removed with the object).
struct EnvironmentFile {
    test::Equirect env;
    std::string path;
    explicit EnvironmentFile(test::Equirect e, const char* name)
        : env(std::move(e)),
          path((std::filesystem::temp_directory_path() / (std::string("facet_truth_") + name + "_" +
                                                          std::to_string(::getpid()) + ".exr")).string()) {
        EXPECT_TRUE(write_hdr_image(path, env.w, env.h, env.rgba));
    }
    ~EnvironmentFile() { std::filesystem::remove(path); }
};

test::Equirect shared_environment(const char* name, uint32_t downsample) {
    auto loaded = load_environment(std::string(FACET_SHARED_DATA_DIR "/env/") + name);
    EXPECT_TRUE(loaded) << loaded.error().message;
    if (!loaded) return {};
    return test::downsample(test::Equirect{loaded->width, loaded->height, loaded->rgba}, downsample);
}

// Renders builtin:spheres (280 x 280, normal and position views) with the job's options.
struct Rendered {
    std::unique_ptr<RenderSession> session;
    RenderedImages images;
};

Rendered render_spheres(const std::string& env_path, const std::function<void(RenderJob&)>& configure = {}) {
    RenderJob job;
    job.programs = &test::gpu_programs();  // the suite's pipelines, each built once
    job.model = "builtin:spheres";
    job.env = env_path;
    job.frame.width = job.frame.height = 280;
    job.frame.skybox = false;
    job.frame.views = {View::normal, View::position};
    job.frame.brdf = BrdfModel::thesis;  // support/render_truth.h's model
    job.shading = ShadingMethod::split_sum;  // the configurations add to it
    if (configure) configure(job);
    Rendered r;
    auto session = RenderSession::create(test::gpu(), job);
    EXPECT_TRUE(session) << session.error().message;
    if (!session) return r;
    r.session = std::move(*session);
    auto images = r.session->render_frame();
    EXPECT_TRUE(images) << images.error().message;
    if (images) r.images = std::move(*images);
    return r;
}

struct Truth {
    std::vector<SphereSample> samples;
    test::SpheresTruth values;
};

Truth truth_for(const Rendered& r, const test::Equirect& env) {
    Truth t;
    const auto& normals = r.images.views.at(0).second;
    const auto& positions = r.images.views.at(1).second;
    t.samples = test::sphere_samples(normals, positions, r.images.width, r.images.height);
    EXPECT_EQ(t.samples.size(), 49u * 24u) << "every sphere needs 100 interior pixels";
    const glm::vec3 e = r.session->camera().position;
    t.values = test::spheres_truth(env, {e.x, e.y, e.z}, normals, positions, t.samples);
    return t;
}

double worst_relative(const Truth& t, const std::vector<float>& hdr, int col) {
    double mean = 0, worst = 0;
    int count = 0;
    for (size_t k = 0; k < t.samples.size(); ++k)
        if (t.samples[k].sphere % 7 == col)
            mean += t.values.bilinear[k][0] + t.values.bilinear[k][1] + t.values.bilinear[k][2], ++count;
    mean /= 3 * count;
    for (size_t k = 0; k < t.samples.size(); ++k)
        for (size_t c = 0; c < 3 && t.samples[k].sphere % 7 == col; ++c) {
            const double got = hdr[t.samples[k].pixel * 4 + c], want = t.values.bilinear[k][c];
            EXPECT_TRUE(std::isfinite(got));
            if (want > 0.05 * mean) worst = std::max(worst, std::abs(got - want) / want);
        }
    return worst;
}

TEST(RenderGroundTruth, SplitSumDominantDirectionAndReferenceUnderASunset) {
    Context& context = test::gpu();
    const uint32_t messages = context.validation_message_count();
    // venice_sunset: a low sun and a bright sunset sky, downsampled 4x; the render and the
    // truth use the same downsampled file.
    EnvironmentFile file(shared_environment("venice_sunset_1k.hdr", 4), "venice");
    Rendered mirror = render_spheres(file.path);
    Rendered dominant = render_spheres(file.path, [](RenderJob& j) { j.frame.dominant_direction = true; });
    ASSERT_FALSE(mirror.images.hdr.empty());
    ASSERT_FALSE(dominant.images.hdr.empty());
    const Truth t = truth_for(mirror, file.env);
    ASSERT_FALSE(t.samples.empty());
    const auto& truth = t.values.bilinear;

    // Bounds: the measured split-sum error on this machine times about 1.5 (see the
    // README's accuracy table); roughness 0 compares with the bilinear mirror image.
    const double bound[7] = {0.03, 0.03, 0.04, 0.065, 0.1, 0.1, 0.1};
    std::printf("lookup    roughness  relRMSE   max rel*  dielectric  metal   (* pixels over 5%% of the mean)\n");
    for (const auto& [name, r] : {std::pair<const char*, const Rendered*>{"mirror", &mirror}, {"dominant", &dominant}})
        for (int col = 0; col < 7; ++col) {
            const double e = test::relative_rmse(truth, r->images.hdr, t.samples, column(col));
            std::printf("%-9s %9.3f  %7.4f   %7.4f   %7.4f   %7.4f\n", name, col / 6.0, e,
                        worst_relative(t, r->images.hdr, col),
                        test::relative_rmse(truth, r->images.hdr, t.samples, column_row(col, 0)),
                        test::relative_rmse(truth, r->images.hdr, t.samples, column_row(col, 6)));
            EXPECT_LT(e, bound[col]) << name << " roughness " << col / 6.0;
        }
    // Where the split sum is worst, rough metals, the dominant direction halves the error.
    for (int col : {5, 6})
        EXPECT_LT(test::relative_rmse(truth, dominant.images.hdr, t.samples, column_row(col, 6)),
                  0.5 * test::relative_rmse(truth, mirror.images.hdr, t.samples, column_row(col, 6)))
            << col;

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
        auto reference = mirror.session->render_reference(settings, {}, &stats);
        ASSERT_TRUE(reference) << reference.error().message;
        EXPECT_EQ(stats.samples, sample_counts[i]);
        for (int col = 0; col < 7; ++col) {
            const double e = test::relative_rmse(t.values.nearest, reference->hdr, t.samples, column(col));
            std::printf("%13u  %9.3f  %7.4f\n", sample_counts[i], col / 6.0, e);
            // At 1024 samples what is left is noise of about 2-3% (a sun 1e3 times the sky).
            if (i == 1) EXPECT_LT(e, 0.05) << "reference, roughness " << col / 6.0;
        }
        total_error[i] = test::relative_rmse(t.values.nearest, reference->hdr, t.samples, [](auto&) { return true; });
    }
    std::printf("reference: relRMSE %.4f at 64 spp, %.4f at 1024 spp\n", total_error[0], total_error[1]);
    EXPECT_LT(total_error[1], total_error[0] / 3.0);
    EXPECT_EQ(context.validation_message_count(), messages);
}

}  // namespace
}  // namespace facet

namespace facet {
namespace {

// Light extraction against the truth of the original environment (sun included): the
// split sum alone, then with suns and lamps shaded as disk lights and the rest through the
// fitted lookups (the default's lights+dominant), per roughness and metalness, on every
// environment here with a sun or lamps.
TEST(RenderGroundTruth, LightExtractionCutsTheSplitSumErrorUnderASun) {
    Context& context = test::gpu();
    const uint32_t messages = context.validation_message_count();
    struct Case {
        const char* name;
        test::Equirect env;
        int lights;      // expected number of extracted lights (-1: any)
        double improve;  // rough metals' error at most this fraction of the split sum's (0: no bound)
    };
    // Synthetic: a sun of 2e4 radiance 2 degrees across over a sky of about 1. Studio: its
    // softboxes (70% of the power) are wider than one light: split into 5 disks, and what
    // stays over 100x the median (their halo, light_extraction.h) into the 3 left.
    const Case cases[] = {{"sun sky", test::sun_sky(256, 128, 2e4, 2.0, 35.0, 60.0), 1, 0.05},
                          {"royal_esplanade", shared_environment("royal_esplanade_1k.hdr", 4), 3, 0.1},
                          {"venice_sunset", shared_environment("venice_sunset_1k.hdr", 4), 1, 0.5},
                          {"studio", shared_environment("studio_small_03_1k.hdr", 4), 8, 0.15},
                          {"warehouse", shared_environment("empty_warehouse_01_1k.hdr", 4), -1, 0.35}};
    std::printf("environment      roughness  dielectric before/after   metal before/after\n");
    for (const Case& c : cases) {
        EnvironmentFile file(c.env, c.name[0] == 's' && c.name[1] == 'u' ? "sunsky" : c.name);
        Rendered before = render_spheres(file.path);
        Rendered after = render_spheres(file.path, [](RenderJob& j) {
            j.extract_lights = true;
            j.frame.dominant_direction = true;
        });
        ASSERT_FALSE(before.images.hdr.empty());
        ASSERT_FALSE(after.images.hdr.empty());
        const Truth t = truth_for(before, file.env);
        ASSERT_FALSE(t.samples.empty());
        const auto& truth = t.values.bilinear;
        const size_t lights = after.session->frame().environment_lights.size();
        double before_rough = 0, after_rough = 0;
        for (int col = 0; col < 7; ++col) {
            double e[4];
            for (int row : {0, 6}) {
                e[row ? 2 : 0] = test::relative_rmse(truth, before.images.hdr, t.samples, column_row(col, row));
                e[row ? 3 : 1] = test::relative_rmse(truth, after.images.hdr, t.samples, column_row(col, row));
            }
            std::printf("%-16s %9.3f  %7.4f / %7.4f        %7.4f / %7.4f\n", c.name, col / 6.0, e[0], e[1], e[2], e[3]);
            if (col >= 4) before_rough += e[2], after_rough += e[3];
            // Nowhere much worse than the split sum alone.
            EXPECT_LT(e[1], std::max(1.5 * e[0], 0.02)) << c.name << " dielectric, roughness " << col / 6.0;
            // Except metals of roughness 1/6 under the warehouse's windows (measured 0.29 against
            // 0.16) and the studio's softboxes (0.24 against 0.047): from roughness 0 to 0.2 the
            // map's level 1 no longer holds the lights, and the disks stand for the window panes
            // and the softboxes' halo as round caps of uniform radiance, which a lobe of alpha
            // 0.028 resolves (bake_rules.h, light_split_level: the price of the 0.2-0.4 groups;
            // the halo kept in level 1 measured 8.4% against 3.2% in the studio's worst group).
            const std::string name = c.name;
            const bool resolved_caps = col == 1 && (name == "warehouse" || name == "studio");
            if (resolved_caps) EXPECT_LT(e[3], 0.3) << c.name << " metal, roughness " << col / 6.0;
            else EXPECT_LT(e[3], std::max(1.5 * e[2], 0.02)) << c.name << " metal, roughness " << col / 6.0;
        }
        std::printf("%-16s %zu light(s); rough metals (roughness >= 2/3): %.4f -> %.4f\n", c.name, lights,
                    before_rough / 3, after_rough / 3);
        if (c.lights >= 0) EXPECT_EQ(lights, size_t(c.lights)) << c.name;
        // Where the lights carry much of the power, rough metals improve several times
        // (measured with the fitted lookups: sun sky 27% -> 0.2%, royal_esplanade 39% -> 1.5%,
        // studio 112% -> 3.4% (8.6% before the excess pass), warehouse 14% -> 2.5%; venice's sun holds only 2% of its power,
        // the fitted lookups alone take it from 14% to 4.2%).
        if (c.improve > 0) EXPECT_LT(after_rough, c.improve * before_rough) << c.name << ": rough metals";
    }
    EXPECT_EQ(context.validation_message_count(), messages);
}

}  // namespace
}  // namespace facet
