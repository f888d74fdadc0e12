#pragma once
// The forward pass's per-frame and per-draw data as the shaders read it (std140 /
// std430 layouts of shaders/render/forward_interface.glsl and skybox.comp), shared by
// forward_pass.cpp and forward_renderer.cpp.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <glm/glm.hpp>

#include <facet/gpu/resources.h>
#include <facet/ibl/light_extraction.h>
#include <facet/scene/scene.h>
#include "core/guarded.h"

namespace facet::forward {

struct FrameData {
    glm::mat4 view_projection;
    glm::vec4 camera_position;
    glm::vec4 ibl;
    glm::uvec4 counts;
};
static_assert(sizeof(FrameData) == 112, "Frame in forward_interface.glsl");

struct LightData {
    glm::vec4 position_range;
    glm::vec4 direction_type;
    glm::vec4 color_intensity;
    glm::vec4 cone;
};
static_assert(sizeof(LightData) == 64, "Light in forward_interface.glsl");

struct DrawConstants {
    uint32_t instance;
    uint32_t material;
};

struct SkyConstants {
    glm::mat4 inverse_view_projection;
    float lod;
    float intensity;
    uint32_t disks;
    float pad;
};

inline LightData disk_data(const DiskLight& d) {
    LightData data{};
    data.direction_type = glm::vec4(-d.direction, 3.0f);  // the direction the light travels
    data.color_intensity = glm::vec4(d.radiance, 1.0f);
    data.cone = glm::vec4(std::cos(d.angular_radius), d.angular_radius, 0.0f, 0.0f);
    return data;
}

inline LightData light_data(const Light& l) {
    LightData d{};
    d.position_range = glm::vec4(l.position, l.range);
    d.direction_type = glm::vec4(glm::normalize(l.direction), float(int(l.type)));
    d.color_intensity = glm::vec4(l.color, l.intensity);
    // KHR_lights_punctual's smooth cone: scale and offset of the cosine.
    const float cos_outer = std::cos(l.outer_cone), cos_inner = std::cos(l.inner_cone);
    const float scale = 1.0f / std::max(cos_inner - cos_outer, 1e-4f);
    d.cone = glm::vec4(scale, -cos_outer * scale, 0.0f, 0.0f);
    return d;
}

// Copies `lights` into a slot's storage buffer, growing it first when it is too small
// (a frame with more lights than any before; steady frames reuse it). At least one
// element is always held, as a zero-sized binding is not allowed.
inline void write_lights(Context& context, Buffer& buffer, const std::vector<LightData>& lights, const char* name) {
    const VkDeviceSize bytes = std::max<size_t>(1, lights.size()) * sizeof(LightData);
    if (!buffer || buffer.size() < bytes)
        buffer = or_throw(Buffer::create(context, std::max<VkDeviceSize>(bytes, buffer.size() * 2),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::upload, name));
    if (!lights.empty()) std::memcpy(buffer.mapped(), lights.data(), lights.size() * sizeof(LightData));
    or_throw(buffer.flush());
}

}  // namespace facet::forward
