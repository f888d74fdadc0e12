#pragma once
// Ground truth for rendered images of builtin:spheres: the pixels to compare (interior
// pixels of each sphere, from the normal and position views) and, for each, the
// brute-force integral of the forward pass's BRDF over every environment texel in
// double precision (Cook-Torrance: GGX, Fresnel-Schlick on h.v, Smith/Schlick-GGX with
// k = r^2/2, kd = (1 - F)(1 - metalness), Lambert), written independently of the shaders.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <facet/reference/ibl_reference.h>

namespace facet::test {

struct SphereSample {
    uint32_t pixel;  // y * width + x
    int sphere;      // row * 7 + column of the 7 x 7 grid (row 0 at the bottom: metalness 0)
};

// Up to `per_sphere` interior pixels (all 3x3 neighbours on the same sphere) per sphere of
// the default builtin:spheres grid, spread over each disk. Empty if a sphere has fewer
// than 100 interior pixels.
std::vector<SphereSample> sphere_samples(const std::vector<float>& normals, const std::vector<float>& positions,
                                         uint32_t width, uint32_t height, uint32_t per_sphere = 24);

struct SpheresTruth {
    std::vector<Vec3> bilinear;  // roughness 0: mirror image bilinear between texel centres
    std::vector<Vec3> nearest;   // roughness 0: the texel's own radiance (piecewise constant)
};

// The truth at every sample, for the grid's materials (roughness column / 6, metalness
// row / 6, albedo (0.5, 0, 0)), seen from `eye`. Runs on two threads.
SpheresTruth spheres_truth(const Equirect& env, const Vec3& eye, const std::vector<float>& normals,
                           const std::vector<float>& positions, const std::vector<SphereSample>& samples);

// sqrt(sum (image - truth)^2 / sum truth^2) over the samples `keep` accepts, all channels.
double relative_rmse(const std::vector<Vec3>& truth, const std::vector<float>& hdr,
                     const std::vector<SphereSample>& samples, const std::function<bool(const SphereSample&)>& keep);

}  // namespace facet::test
