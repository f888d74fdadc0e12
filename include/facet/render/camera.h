#pragma once
// Camera placement and projection: a look-at view (right-handed, +Y up, looking down
// -Z in view space, as glTF) and a reversed-Z perspective for Vulkan's clip space
// (y down, depth 1 at the near plane, 0 at infinity).
#include <glm/glm.hpp>

#include <facet/scene/scene.h>

namespace facet {

struct CameraView {
    glm::vec3 position{0.0f, 0.0f, 3.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov = 0.7853981633974483f;  // radians
    float znear = 0.05f;

    glm::mat4 view() const;
    // Infinite far plane, reversed Z.
    glm::mat4 projection(float aspect) const;
};

// Orbit placement around `target`: theta is the azimuth from +Z towards +X, phi the
// elevation above the horizontal plane (both degrees), radius in metres.
CameraView orbit_camera(glm::vec3 target, float theta_deg, float phi_deg, float radius, float yfov);

// Frames the bounds: looks at their centre from the +Z side, from the distance where
// the box's front face fills the narrower field of view with a 10% margin.
CameraView frame_bounds(glm::vec3 bounds_min, glm::vec3 bounds_max, float yfov, float aspect);

}  // namespace facet
