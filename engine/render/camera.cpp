#include <facet/render/camera.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace facet {

glm::vec3 CameraMatrices::position() const { return glm::vec3(glm::inverse(view)[3]); }

glm::mat4 CameraView::view() const { return glm::lookAtRH(position, target, up); }

glm::mat4 CameraView::projection(float aspect) const {
    const float f = 1.0f / std::tan(yfov * 0.5f);
    glm::mat4 p(0.0f);
    p[0][0] = f / aspect;
    p[1][1] = -f;       // Vulkan's clip space has y down
    p[2][3] = -1.0f;    // w = -z_view
    p[3][2] = znear;    // depth = near / -z_view: 1 at the near plane, 0 at infinity
    return p;
}

CameraView orbit_camera(glm::vec3 target, float theta_deg, float phi_deg, float radius, float yfov) {
    const float theta = glm::radians(theta_deg), phi = glm::radians(phi_deg);
    CameraView c;
    c.target = target;
    c.position = target + radius * glm::vec3(std::cos(phi) * std::sin(theta), std::sin(phi),
                                             std::cos(phi) * std::cos(theta));
    c.yfov = yfov;
    c.znear = std::max(1e-3f, radius * 1e-3f);
    if (std::abs(std::cos(phi)) < 1e-4f) c.up = glm::vec3(0.0f, 0.0f, -1.0f);
    return c;
}

CameraView frame_bounds(glm::vec3 bounds_min, glm::vec3 bounds_max, float yfov, float aspect) {
    if (!(bounds_min.x <= bounds_max.x)) bounds_min = bounds_max = glm::vec3(0.0f);
    const glm::vec3 centre = 0.5f * (bounds_min + bounds_max);
    const glm::vec3 half = glm::max(0.5f * (bounds_max - bounds_min), glm::vec3(1e-3f));
    // Seen from +Z, the box's front face must fit both fields of view (with a margin);
    // the front face is half a depth nearer than the centre.
    const float tan_y = std::tan(yfov * 0.5f), tan_x = tan_y * aspect;
    // The box's projected area seen along a unit direction d is proportional to
    // |d.x| hy hz + |d.y| hx hz + |d.z| hx hy. +Z stays the view unless another
    // direction sees clearly more (so that ordinary models keep their framing).
    const float from_z = half.x * half.y, from_x = half.y * half.z;
    const float from_above = 0.70710678f * (half.x * half.z + half.x * half.y);
    if (std::max(from_x, from_above) > 2.0f * from_z) {
        const float radius = glm::length(half);
        const float tan_min = std::min(tan_y, tan_x);
        const float sphere_distance = 1.1f * radius * std::sqrt(1.0f + 1.0f / (tan_min * tan_min));
        const bool side = from_x >= from_above;
        CameraView c = orbit_camera(centre, side ? 90.0f : 0.0f, side ? 0.0f : 45.0f, sphere_distance, yfov);
        c.znear = std::max(1e-3f, (sphere_distance - radius) * 0.25f);
        return c;
    }
    const float distance = 1.1f * std::max(half.y / tan_y, half.x / tan_x) + half.z;
    CameraView c = orbit_camera(centre, 0.0f, 0.0f, distance, yfov);
    c.znear = std::max(1e-3f, (distance - half.z) * 0.25f);
    return c;
}

}  // namespace facet
