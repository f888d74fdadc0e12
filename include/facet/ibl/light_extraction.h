#pragma once
// Light extraction: compact, very bright regions of an environment (a sun, lamps) are
// taken out of the map (their texels filled with the surrounding sky) and returned as
// disk lights of the same solid angle and power, to be shaded with the full BRDF, while
// the remaining smooth map goes through the split sum. This cuts the split sum's error
// where it is worst: rough surfaces under a sun (its n = v = R assumption). What stays over
// max_residual_range times the median after that (a studio's softboxes, too wide for the
// lights left, and their halo) becomes the remaining lights as caps of its power and spread.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace facet {

struct DiskLight {
    glm::vec3 direction{0.0f, 1.0f, 0.0f};  // towards the light (unit)
    float angular_radius = 0.0f;            // radians: the region's solid angle, or the excess's spread
    glm::vec3 radiance{0.0f};               // uniform over the cap: power / solid angle
    float solid_angle = 0.0f;               // steradians
    uint32_t texels = 0;
    double power_fraction = 0;              // of the whole environment's luminous power
};

struct LightExtractionSettings {
    // A texel is part of a light when its luminance exceeds both ratios.
    double min_ratio_to_median = 50.0;
    double min_ratio_to_peak = 0.02;
    double max_solid_angle = 0.01;        // steradians of one light (a cap of about 3.2 degrees radius)
    double max_region_solid_angle = 0.3; // wider regions are split into lights of max_solid_angle each, up to this
    double min_power_fraction = 0.02;     // smaller lights stay in the map
    uint32_t max_lights = 8;
    // After the regions: where the map's peak is still over this many times its median (a
    // studio's softboxes and their halo, spread over more than one region), the luminance
    // above that level, wherever it lies, becomes the lights still free: pieces of at least
    // max_solid_angle, each a disk of the piece's power, centroid and angular spread (the
    // residual keeps the texels' colour, clamped to the level). 0 turns this off.
    double max_residual_range = 100.0;
};

struct LightExtraction {
    std::vector<DiskLight> lights;
    std::vector<float> residual;  // the map without them (RGBA, same size)
    double extracted_power_fraction = 0;
    std::vector<std::string> notes;  // regions left in the map, and why
};

// `rgba`: width x height texels, row 0 = top (+Y), the design's equirect mapping.
LightExtraction extract_lights(std::span<const float> rgba, uint32_t width, uint32_t height,
                               const LightExtractionSettings& settings = {});

}  // namespace facet
