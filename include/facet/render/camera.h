#pragma once
// The camera the render passes take is a pair of matrices (an engine's own); CameraView,
// a look-at view (right-handed, +Y up, looking down -Z in view space, as glTF) with a
// reversed-Z perspective for Vulkan's clip space (y down, depth 1 at the near plane, 0
// at infinity), is a helper that produces them.
#include <glm/glm.hpp>

#include <facet/scene/scene.h>

namespace facet {

// World -> view -> Vulkan clip space. The passes test depth GREATER_OR_EQUAL and clear it
// to 0, so `projection` must be reversed Z (near plane at depth 1, far at 0 or infinity).
struct CameraMatrices {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::vec3 position() const;  // the camera's world position (from the inverse view)
};

struct CameraView {
    glm::vec3 position{0.0f, 0.0f, 3.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov = 0.7853981633974483f;  // radians
    float znear = 0.05f;

    glm::mat4 view() const;
    // Infinite far plane, reversed Z.
    glm::mat4 projection(float aspect) const;
    CameraMatrices matrices(float aspect) const { return {view(), projection(aspect)}; }
};

// Orbit placement around `target`: theta is the azimuth from +Z towards +X, phi the
// elevation above the horizontal plane (both degrees), radius in metres.
CameraView orbit_camera(glm::vec3 target, float theta_deg, float phi_deg, float radius, float yfov);

// Frames the bounds: looks at their centre from the +Z side, from the distance where
// the box's front face fills the narrower field of view with a 10% margin. A box that
// +Z sees nearly edge-on (its projected area from +X, or from 45 degrees above, more
// than twice that from +Z: a model lying flat in XZ or YZ) is seen from that direction
// instead, at the distance where its bounding sphere fits with the same margin.
CameraView frame_bounds(glm::vec3 bounds_min, glm::vec3 bounds_max, float yfov, float aspect);

}  // namespace facet
