// Light extraction on a synthetic sun sky (where the answer is known), on a sky without
// a sun, and on the shared environments (what it finds is printed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <facet/ibl/light_extraction.h>
#include <facet/io/environment_image.h>
#include <facet/reference/ibl_reference.h>
#include "render/lobe_disks.h"

namespace facet {
namespace {

constexpr double pi = 3.14159265358979323846;

DiskLight cap(glm::vec3 direction, double radius_degrees, glm::vec3 radiance) {
    DiskLight d;
    d.direction = glm::normalize(direction);
    d.angular_radius = float(radius_degrees * pi / 180.0);
    d.solid_angle = float(2.0 * pi * (1.0 - std::cos(double(d.angular_radius))));
    d.radiance = radiance;
    d.power_fraction = 0.25;
    return d;
}

// A softbox in two overlapping pieces and a lamp far from it: a smooth lobe keeps all three
// as they are; a rough one merges the pieces into one cap of their power, mean direction and
// spread, never the lamp.
TEST(LobeDisks, RoughLobesMergeCapsTheyCannotTellApart) {
    const double half = 1.5 * pi / 180.0;  // the pieces' centres 3 degrees apart
    const std::vector<DiskLight> disks = {
        cap({-std::sin(half), 0.0, std::cos(half)}, 3.0, {100.0f, 200.0f, 300.0f}),
        cap({0.0, 1.0, 0.0}, 2.0, {50.0f, 50.0f, 50.0f}),
        cap({std::sin(half), 0.0, std::cos(half)}, 3.0, {100.0f, 200.0f, 300.0f}),
    };
    const std::vector<DiskLight> smooth = disks_for_lobe(disks, 0.2f);  // alpha 0.04: 1.1 degrees
    ASSERT_EQ(smooth.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(smooth[i].direction, disks[i].direction);
        EXPECT_EQ(smooth[i].radiance, disks[i].radiance);
        EXPECT_EQ(smooth[i].angular_radius, disks[i].angular_radius);
    }
    const std::vector<DiskLight> rough = disks_for_lobe(disks, 0.6f);  // alpha 0.36: 10.3 degrees
    ASSERT_EQ(rough.size(), 2u);
    // The pieces first (the first of them is disks[0]), then the lamp untouched.
    EXPECT_EQ(rough[1].direction, disks[1].direction);
    EXPECT_EQ(rough[1].radiance, disks[1].radiance);
    const DiskLight& m = rough[0];
    for (int c = 0; c < 3; ++c) {
        const double power = double(disks[0].radiance[c]) * disks[0].solid_angle + double(disks[2].radiance[c]) * disks[2].solid_angle;  // cap() sets 2 pi (1 - cos theta)
        EXPECT_NEAR(double(m.radiance[c]) * m.solid_angle, power, 1e-4 * power) << "channel " << c;
    }
    // Equal power, mirrored about z: the centre is the bisector, and the
    // spread is each piece's 1.5-degree offset squared plus its own theta^2 / 2.
    EXPECT_NEAR(m.direction.x, 0.0, 1e-6);
    EXPECT_NEAR(m.direction.z, 1.0, 1e-6);
    const double theta = 3.0 * pi / 180.0, expected = std::sqrt(2.0 * (half * half + 0.5 * theta * theta));
    EXPECT_NEAR(m.angular_radius, expected, 1e-5);
    EXPECT_NEAR(m.solid_angle, 2.0 * pi * (1.0 - std::cos(expected)), 1e-7);
    EXPECT_NEAR(m.power_fraction, 0.5, 1e-12);
    // The lamp is 90 degrees away: no lobe merges it. Nor a faint speck opposite the pieces,
    // which would hardly move their spread (its light would move 170 degrees).
    EXPECT_EQ(disks_for_lobe(disks, 1.0f).size(), 2u);
    std::vector<DiskLight> speck = disks;
    speck.push_back(cap({0.1, 0.0, -1.0}, 0.5, {1.0f, 1.0f, 1.0f}));
    EXPECT_EQ(disks_for_lobe(speck, 1.0f).size(), 3u);
}

// A lobe shades a cap as a point from an alpha (roughness^2) of kPointCapLobeRatio (3) times
// the cap's angular radius: a 2-degree lamp from roughness 0.324, an 11.5-degree softbox
// (0.2 rad) from 0.775; never for a mirror.
TEST(LobeDisks, CapsAreShadedAsPointsWhereTheLobeIsThreeTimesWider) {
    EXPECT_EQ(kPointCapLobeRatio, 3.0f);
    const DiskLight lamp = cap({0.0, 0.0, 1.0}, 2.0, {1.0f, 1.0f, 1.0f});
    const DiskLight softbox = cap({0.0, 0.0, 1.0}, 0.2 * 180.0 / pi, {1.0f, 1.0f, 1.0f});
    EXPECT_FALSE(disk_is_point_for_lobe(lamp, 0.0f));
    EXPECT_FALSE(disk_is_point_for_lobe(lamp, 0.32f));
    EXPECT_TRUE(disk_is_point_for_lobe(lamp, 0.33f));
    EXPECT_FALSE(disk_is_point_for_lobe(softbox, 0.77f));
    EXPECT_TRUE(disk_is_point_for_lobe(softbox, 0.78f));
    EXPECT_TRUE(disk_is_point_for_lobe(softbox, 1.0f));
}

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

// Luminous power of an equirect map (luminance x texel solid angle), in double.
double power(const std::vector<float>& rgba, uint32_t w, uint32_t h) {
    double sum = 0;
    for (uint32_t y = 0; y < h; ++y) {
        const double omega = (2 * pi / w) * (pi / h) * std::cos(((y + 0.5) / h - 0.5) * pi);
        for (uint32_t x = 0; x < w; ++x) {
            const float* t = &rgba[(size_t(y) * w + x) * 4];
            sum += (0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]) * omega;
        }
    }
    return sum;
}

// A softbox too wide for the lights left (20 degrees across, one light allowed: the region
// pass leaves it in the map) becomes the excess over 100x the median: one disk of the
// excess's power around the softbox's centre with the softbox's own radius (a uniform cap's
// spread), the residual clamped to that level, no power lost or made; a few isolated bright
// texels (each far under 2% of the power) stay in the map.
TEST(LightExtraction, TheExcessOfAWideSoftboxBecomesOneDiskOfItsPowerAndSpread) {
    const double diameter = 20.0, elevation = 25.0, azimuth = -60.0, radiance = 5000;
    test::Equirect sky = test::sun_sky(512, 256, radiance, diameter, elevation, azimuth);
    for (uint32_t x : {40u, 200u, 300u}) sky.rgba[(size_t(200) * sky.w + x) * 4 + 1] = 400.0f;  // isolated, green
    LightExtractionSettings one;
    one.max_lights = 1;
    const LightExtraction e = extract_lights(sky.rgba, sky.w, sky.h, one);
    ASSERT_EQ(e.lights.size(), 1u);
    EXPECT_FALSE(e.notes.empty()) << "the region pass names the softbox it leaves";
    const DiskLight& box = e.lights[0];
    const double el = elevation * pi / 180, az = azimuth * pi / 180;
    const glm::dvec3 want(std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az));
    EXPECT_GT(glm::dot(glm::dvec3(box.direction), want), std::cos(0.2 * pi / 180)) << "within 0.2 degree";
    EXPECT_NEAR(box.angular_radius * 180 / pi, diameter / 2, 0.2) << "the cap's spread is the softbox's";
    std::vector<float> sorted;
    for (size_t i = 0; i < sky.rgba.size(); i += 4) sorted.push_back(0.2126f * sky.rgba[i] + 0.7152f * sky.rgba[i + 1] + 0.0722f * sky.rgba[i + 2]);
    std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
    const double level = 100.0 * sorted[sorted.size() / 2];
    double brightest = 0;  // but for the isolated texels
    for (size_t i = 0; i < e.residual.size(); i += 4)
        if (e.residual[i + 1] != 400.0f) brightest = std::max(brightest, 0.2126 * e.residual[i] + 0.7152 * e.residual[i + 1] + 0.0722 * e.residual[i + 2]);
    EXPECT_NEAR(brightest, level, 1e-3 * level) << "the residual stops at 100x the median";
    const double disk_power = double(0.2126f * box.radiance.x + 0.7152f * box.radiance.y + 0.0722f * box.radiance.z) *
                              box.solid_angle;
    const double whole = power(sky.rgba, sky.w, sky.h);
    EXPECT_NEAR(power(e.residual, sky.w, sky.h) + disk_power, whole, 1e-5 * whole) << "power kept";
    EXPECT_NEAR(disk_power / whole, box.power_fraction, 1e-5);
    for (uint32_t x : {40u, 200u, 300u}) EXPECT_EQ(e.residual[(size_t(200) * sky.w + x) * 4 + 1], 400.0f);
    // Off, the softbox stays in the map.
    one.max_residual_range = 0;
    EXPECT_TRUE(extract_lights(sky.rgba, sky.w, sky.h, one).lights.empty());
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
