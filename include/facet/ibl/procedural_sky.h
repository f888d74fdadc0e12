#pragma once
// builtin:sky and builtin:white, generated on the GPU as equirectangular RGBA32F images
// (design.md's mapping). The sky is the HDR case where sampling-based bakes fail: its
// sun's radiance is ~4e4 times the sky's.
#include <array>
#include <cstdint>
#include <string>

#include <facet/core/result.h>
#include <facet/graph/render_graph.h>

namespace facet {

class ProgramCache;

struct ProceduralSky {
    // Direction towards the sun: elevation above the horizon and azimuth measured
    // from +X towards +Z (so azimuth 90 degrees is +Z), in degrees.
    float sun_elevation_deg = 35.0f;
    float sun_azimuth_deg = 60.0f;
    float sun_angular_radius_deg = 0.5f;  // a disk 1 degree across
    std::array<float, 3> sun_radiance{40000.0f, 38000.0f, 34000.0f};
    float sun_glow = 2.0f;  // strength of the forward-scattering halo around the sun
    std::array<float, 3> zenith_radiance{0.25f, 0.45f, 0.95f};
    std::array<float, 3> horizon_radiance{0.9f, 0.95f, 1.05f};
    std::array<float, 3> ground_radiance{0.30f, 0.27f, 0.24f};

    // Uniform radiance 1 in every direction: the white furnace.
    static ProceduralSky white();

    // No light anywhere: every radiance (sun, zenith, horizon, ground) has no positive
    // luminance (the sky's texels are mixes of them with non-negative weights).
    bool black() const;
    // Unit vector towards the sun (world space, +Y up).
    std::array<float, 3> sun_direction() const;
    // Content hash of the parameters (16 hex digits), for bake.json and caches.
    std::string content_hash() const;
};

// Adds the pass that writes `sky` into `target` (RGBA32F, mip 0); returns the new version.
Result<ImageHandle> add_procedural_sky_pass(RenderGraph& graph, ProgramCache& programs, const ProceduralSky& sky,
                                            ImageHandle target);

}  // namespace facet
