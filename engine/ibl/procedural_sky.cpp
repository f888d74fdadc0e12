#include "ibl/procedural_sky.h"

#include <cmath>

namespace facet {

std::array<float, 3> ProceduralSky::sun_direction() const {
    const double to_rad = 3.14159265358979323846 / 180.0;
    const double el = sun_elevation_deg * to_rad, az = sun_azimuth_deg * to_rad;
    return {float(std::cos(el) * std::cos(az)), float(std::sin(el)), float(std::cos(el) * std::sin(az))};
}

}  // namespace facet
