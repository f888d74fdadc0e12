#pragma once
// Independent CPU references for IBL tests, in double precision: equirect geometry
// (design.md's mapping), the Vulkan cube face table, synthetic skies, brute-force
// integrals over every texel of an environment.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace facet::test {

using Vec3 = std::array<double, 3>;

struct Equirect {
    uint32_t w = 0, h = 0;
    std::vector<float> rgba;
    const float* at(uint32_t x, uint32_t y) const { return &rgba[(size_t(y) * w + x) * 4]; }
};

// Direction of image coordinates (u, v_image) in [0,1]^2, v_image = 0 at the top row.
Vec3 equirect_direction(double u, double v_image);
// Solid angle of any texel of row y.
double equirect_texel_solid_angle(uint32_t y, uint32_t w, uint32_t h);

// The Vulkan specification's cube face selection, forward: face and (s, t) of d.
void select_cube_face(const Vec3& d, uint32_t& face, double& s, double& t);
// Centre direction of texel (x, y) of face `face` of an n x n cube (unit length); checked
// against select_cube_face by the tests.
Vec3 cube_texel_direction(uint32_t face, uint32_t x, uint32_t y, uint32_t n);

// A sky of about 1 (brighter at the horizon) over a ground of 0.3, with a sun disk of
// `sun_radiance` and angular diameter `sun_diameter_deg` at the given elevation/azimuth,
// each texel the 8x8 supersampled mean.
Equirect sun_sky(uint32_t w, uint32_t h, double sun_radiance, double sun_diameter_deg, double elevation_deg,
                 double azimuth_deg);
Equirect uniform_sky(uint32_t w, uint32_t h, float radiance);
// Box-downsamples by an integer factor (the truth then uses the downsampled image too).
Equirect downsample(const Equirect& e, uint32_t factor);

// E(n) / pi = 1/pi * sum over texels of L max(0, n . w) dw: the brute-force truth.
Vec3 irradiance_over_pi(const Equirect& e, const Vec3& n);

// Direction, solid angle and radiance of every texel, computed once per environment.
struct TexelTable {
    std::vector<Vec3> direction;
    std::vector<double> solid_angle;
    std::vector<Vec3> radiance;
    explicit TexelTable(const Equirect& e);
};

// The GGX-prefiltered environment of the split sum (n = v = R):
// P(R) = sum L w dw / sum w dw, w = D(h) (n.l), h = normalize(n + l), over every texel.
Vec3 prefiltered(const TexelTable& t, const Vec3& n, double roughness);

// The split-sum LUT's scale A and bias B at (n.v, roughness) by quadrature over the
// half-vector hemisphere; Schlick-GGX with k = r^2/2, or the height-correlated term.
struct Ab {
    double a, b;
};
Ab brdf_lut_reference(double n_v, double roughness, bool height_correlated);

double luminance(const Vec3& rgb);
double luminance(const float* rgb);

}  // namespace facet::test
