#pragma once
// builtin:sky: a procedural sky with a small, very bright sun, generated on the GPU as an
// equirectangular RGBA32F image (design.md's mapping). It is the HDR case where
// sampling-based bakes fail: the sun's radiance is ~4e4 times the sky's.
#include <array>
#include <cstdint>

namespace facet {

struct ProceduralSky {
    // Direction towards the sun: elevation above the horizon and azimuth measured
    // from +X towards +Z (so azimuth 90 degrees is +Z), in degrees.
    float sun_elevation_deg = 35.0f;
    float sun_azimuth_deg = 60.0f;
    float sun_angular_radius_deg = 0.5f;  // a disk 1 degree across
    std::array<float, 3> sun_radiance{40000.0f, 38000.0f, 34000.0f};
    std::array<float, 3> zenith_radiance{0.25f, 0.45f, 0.95f};
    std::array<float, 3> horizon_radiance{0.9f, 0.95f, 1.05f};
    std::array<float, 3> ground_radiance{0.30f, 0.27f, 0.24f};

    // Unit vector towards the sun (world space, +Y up).
    std::array<float, 3> sun_direction() const;
};

}  // namespace facet
