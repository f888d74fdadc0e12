// The engine's equirectangular mapping (engine/io/equirect.h) against the independent
// CPU truth (facet::reference, written from design.md's equations) and against the
// facts design.md states: row 0 looks up, the centre column along +X, u = 0.75 along +Z,
// and the texels of an image cover the sphere (4 pi).
#include <gtest/gtest.h>

#include <cmath>

#include <facet/reference/ibl_reference.h>
#include "io/equirect.h"

namespace facet {
namespace {

void expect_direction(const glm::dvec3& got, const glm::dvec3& want, double tolerance) {
    EXPECT_NEAR(got.x, want.x, tolerance);
    EXPECT_NEAR(got.y, want.y, tolerance);
    EXPECT_NEAR(got.z, want.z, tolerance);
}

TEST(Equirect, DirectionsFollowDesignMd) {
    expect_direction(equirect_direction(0.5, 0.0), {0, 1, 0}, 1e-12);    // top row: +Y
    expect_direction(equirect_direction(0.5, 1.0), {0, -1, 0}, 1e-12);   // bottom row: -Y
    expect_direction(equirect_direction(0.5, 0.5), {1, 0, 0}, 1e-12);    // centre: +X
    expect_direction(equirect_direction(0.75, 0.5), {0, 0, 1}, 1e-12);   // u = 0.75: +Z
    expect_direction(equirect_direction(0.25, 0.5), {0, 0, -1}, 1e-12);
    expect_direction(equirect_direction(0.0, 0.5), {-1, 0, 0}, 1e-12);
}

TEST(Equirect, MatchesTheReferenceAndInvertsItself) {
    for (double u = 0.01; u < 1.0; u += 0.0625)
        for (double v = 0.01; v < 1.0; v += 0.0625) {
            const glm::dvec3 d = equirect_direction(u, v);
            const test::Vec3 r = test::equirect_direction(u, v);
            expect_direction(d, {r[0], r[1], r[2]}, 1e-12);
            EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
            const glm::dvec2 uv = equirect_uv(d);
            EXPECT_NEAR(uv.x, u, 1e-12) << u << ", " << v;
            EXPECT_NEAR(uv.y, v, 1e-12) << u << ", " << v;
        }
    // Texel centres.
    const uint32_t w = 16, h = 8;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const test::Vec3 r = test::equirect_direction((x + 0.5) / w, (y + 0.5) / h);
            expect_direction(equirect_texel_direction(x, y, w, h), {r[0], r[1], r[2]}, 1e-12);
        }
}

TEST(Equirect, TexelSolidAnglesMatchTheReferenceAndCoverTheSphere) {
    const double pi = std::acos(-1.0);
    for (const auto& [w, h] : {std::pair<uint32_t, uint32_t>{4, 2}, {64, 32}, {1000, 500}, {7, 13}}) {
        double sum = 0;
        for (uint32_t y = 0; y < h; ++y) {
            const double omega = equirect_texel_solid_angle(y, w, h);
            EXPECT_NEAR(omega, test::equirect_texel_solid_angle(y, w, h), 1e-15 + 1e-12 * omega) << w << "x" << h;
            EXPECT_GT(omega, 0.0);
            sum += omega * w;
        }
        EXPECT_NEAR(sum, 4 * pi, 1e-12) << w << "x" << h;
    }
}

TEST(Equirect, BandsAddUp) {
    const double pi = std::acos(-1.0);
    const uint32_t h = 37;
    EXPECT_NEAR(equirect_band_solid_angle(0, h, h), 4 * pi, 1e-12);
    EXPECT_NEAR(equirect_band_solid_angle(0, h / 2.0, h), 2 * pi, 1e-12);  // the upper hemisphere
    for (double a = 0; a < h; a += 3.3)
        for (double b = a; b < h; b += 5.1) {
            const double c = std::min(b + 2.7, double(h));
            EXPECT_NEAR(equirect_band_solid_angle(a, b, h) + equirect_band_solid_angle(b, c, h),
                        equirect_band_solid_angle(a, c, h), 1e-12);
        }
    EXPECT_DOUBLE_EQ(equirect_band_solid_angle(5, 6, h) / 11, equirect_texel_solid_angle(5, 11, h));
}

}  // namespace
}  // namespace facet
