#include <facet/scene/scene.h>

#include <limits>

#include <glm/common.hpp>

namespace facet {

std::pair<glm::vec3, glm::vec3> Scene::world_bounds() const {
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    for (const Instance& instance : instances) {
        if (instance.primitive >= primitives.size()) continue;
        const Primitive& primitive = primitives[instance.primitive];
        // A rotated box's extent is set by its corners, so transform all eight.
        for (int corner = 0; corner < 8; ++corner) {
            glm::vec3 local((corner & 1) ? primitive.bounds_max.x : primitive.bounds_min.x,
                            (corner & 2) ? primitive.bounds_max.y : primitive.bounds_min.y,
                            (corner & 4) ? primitive.bounds_max.z : primitive.bounds_min.z);
            glm::vec3 world = glm::vec3(instance.world * glm::vec4(local, 1.0f));
            lo = glm::min(lo, world);
            hi = glm::max(hi, world);
        }
    }
    return {lo, hi};
}

}  // namespace facet
