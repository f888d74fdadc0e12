#pragma once
// The equirectangular mapping of docs/design.md ("Coordinates"), the C++ side of
// shaders/ibl/equirect.glsl and written once for the engine: a direction d sits at
// u = atan2(d.z, d.x) / 2pi + 0.5 and v_image = 0.5 - asin(d.y) / pi, so image row 0 looks
// up (+Y), the centre column along +X and u = 0.75 along +Z. Rows are addressed by a row
// coordinate in [0, height] (row y spans [y, y + 1]), so fractional bands (a box filter's
// overlaps) use the same functions as whole texels. tests/gpu/shared_constants_test.cpp
// checks that the GLSL side gives the same values; facet::reference keeps its own,
// independent copy for the tests' truth.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include <facet/core/shared_constants.h>

namespace facet {

// Latitude (radians) at row coordinate `row` of an image `height` rows tall: +pi/2 at the
// top edge, -pi/2 at the bottom edge.
inline double equirect_latitude(double row, uint32_t height) { return (0.5 - row / height) * pi; }

// The unit direction at longitude atan2(d.z, d.x) and latitude asin(d.y) (radians).
inline glm::dvec3 direction_at(double longitude, double latitude) {
    return {std::cos(latitude) * std::cos(longitude), std::sin(latitude), std::cos(latitude) * std::sin(longitude)};
}

// Direction for image coordinates (u, v_image) in [0, 1]^2, v_image = 0 at the top row.
inline glm::dvec3 equirect_direction(double u, double v_image) {
    return direction_at((u - 0.5) * 2 * pi, (0.5 - v_image) * pi);
}

// Image coordinates (u, v_image) of a unit direction: the inverse of equirect_direction.
inline glm::dvec2 equirect_uv(const glm::dvec3& d) {
    return {std::atan2(d.z, d.x) / (2 * pi) + 0.5, 0.5 - std::asin(std::clamp(d.y, -1.0, 1.0)) / pi};
}

// Direction through the centre of texel (x, y) of a width x height image.
inline glm::dvec3 equirect_texel_direction(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
    return equirect_direction((x + 0.5) / width, (y + 0.5) / height);
}

// Solid angle (steradians) of the full-width band between row coordinates
// top_row <= bottom_row: 2 pi (sin latitude_top - sin latitude_bottom).
inline double equirect_band_solid_angle(double top_row, double bottom_row, uint32_t height) {
    return 2 * pi * (std::sin(equirect_latitude(top_row, height)) - std::sin(equirect_latitude(bottom_row, height)));
}

// Solid angle (steradians) of one texel of row y: its band shared by the width's texels.
// The texels of a whole image add up to 4 pi.
inline double equirect_texel_solid_angle(uint32_t y, uint32_t width, uint32_t height) {
    return equirect_band_solid_angle(y, y + 1.0, height) / width;
}

}  // namespace facet
