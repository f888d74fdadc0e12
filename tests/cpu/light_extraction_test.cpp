// Light extraction on a synthetic sun sky (where the answer is known), on a sky without
// a sun, and on the shared environments (what it finds is printed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <facet/ibl/light_extraction.h>
#include <facet/io/environment_image.h>
#include <facet/reference/ibl_reference.h>

namespace facet {
namespace {

constexpr double pi = 3.14159265358979323846;

TEST(LightExtraction, FindsTheSunWithItsPowerAndDirection) {
    // Sun: 1e5 radiance, 2 degrees across (the synthetic sky of the IBL tests).
    const double diameter = 2.0, elevation = 30.0, azimuth = 40.0, radiance = 1e5;
    const test::Equirect sky = test::sun_sky(512, 256, radiance, diameter, elevation, azimuth);
    const LightExtraction e = extract_lights(sky.rgba, sky.w, sky.h);
    ASSERT_EQ(e.lights.size(), 1u);
    const DiskLight& sun = e.lights[0];
    const double el = elevation * pi / 180, az = azimuth * pi / 180;
    const glm::dvec3 want(std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az));
    EXPECT_GT(glm::dot(glm::dvec3(sun.direction), want), std::cos(0.1 * pi / 180)) << "within 0.1 degree";
    // The disk's power: radiance x solid angle of the true disk, minus the sky under it.
    const double disk = 2 * pi * (1 - std::cos(0.5 * diameter * pi / 180));
    const double power = double(sun.radiance.x) * sun.solid_angle;
    EXPECT_NEAR(power, radiance * disk, 0.02 * radiance * disk);
    EXPECT_GT(sun.power_fraction, 0.9);
    // The residual is the smooth sky: nothing brighter than a few times the sky.
    float brightest = 0;
    for (size_t i = 0; i < e.residual.size(); i += 4) brightest = std::max(brightest, e.residual[i]);
    EXPECT_LT(brightest, 3.0f);
}

TEST(LightExtraction, LeavesASkyWithoutASunAlone) {
    const test::Equirect white = test::uniform_sky(64, 32, 1.0f);
    EXPECT_TRUE(extract_lights(white.rgba, white.w, white.h).lights.empty());
    const test::Equirect dim_sun = test::sun_sky(256, 128, 5.0, 2.0, 30, 0);  // barely brighter than the sky
    EXPECT_TRUE(extract_lights(dim_sun.rgba, dim_sun.w, dim_sun.h).lights.empty());
}

TEST(LightExtraction, SharedEnvironments) {
    for (const char* name : {"venice_sunset_1k", "royal_esplanade_1k", "studio_small_03_1k", "empty_warehouse_01_1k"}) {
        auto env = load_environment(std::string(FACET_SHARED_DATA_DIR "/env/") + name + ".hdr");
        ASSERT_TRUE(env) << env.error().message;
        const LightExtraction e = extract_lights(env->rgba, env->width, env->height);
        std::printf("%-24s %zu light(s), %.1f%% of the power\n", name, e.lights.size(),
                    100 * e.extracted_power_fraction);
        for (const DiskLight& l : e.lights)
            std::printf("    dir (%.3f, %.3f, %.3f), radius %.2f deg, %u texels, radiance %.1f, %.1f%%\n", l.direction.x,
                        l.direction.y, l.direction.z, l.angular_radius * 180 / pi, l.texels, l.radiance.y,
                        100 * l.power_fraction);
        for (const std::string& note : e.notes) std::printf("    note: %s\n", note.c_str());
        for (const DiskLight& l : e.lights) {
            EXPECT_TRUE(std::isfinite(l.radiance.x) && l.radiance.x > 0);
            EXPECT_NEAR(glm::length(l.direction), 1.0f, 1e-5f);
        }
    }
}

}  // namespace
}  // namespace facet
