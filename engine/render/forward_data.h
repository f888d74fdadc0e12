#pragma once
// The forward pass's per-frame and per-draw data as the shaders read it (std140 /
// std430 layouts of shaders/render/forward_interface.glsl and skybox.comp), shared by
// forward_pass.cpp and forward_renderer.cpp. The lights are render/light_data.h's.
// tests/cpu/gpu_layout_test.cpp compares these layouts with the shaders'.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <facet/core/result.h>
#include <facet/gpu/resources.h>
#include "render/light_data.h"
#include <facet/ibl/light_extraction.h>
#include <facet/scene/scene.h>
#include <facet/shader/compiler.h>
#include "core/guarded.h"

namespace facet::forward {

// The most disks the forward pass shades: render/forward.frag unrolls FACET_DISK(0..15).
inline constexpr uint32_t kMaxForwardDiskLights = 16;

struct FrameData {
    glm::mat4 view_projection;
    glm::vec4 camera_position;
    glm::vec4 ibl;
    glm::uvec4 counts;
};
static_assert(sizeof(FrameData) == 112 && offsetof(FrameData, camera_position) == 64 && offsetof(FrameData, ibl) == 80 &&
                  offsetof(FrameData, counts) == 96,
              "Frame in forward_interface.glsl");

struct SkyConstants {
    glm::mat4 inverse_view_projection;
    float lod;
    float intensity;
};
static_assert(offsetof(SkyConstants, lod) == 64 && offsetof(SkyConstants, intensity) == 68, "Sky in skybox.comp");

// The disks as constants of a pipeline (shaders/render/disk_constants.glsl): DISK_LIGHTS and
// FACET_DISK_LIGHT_i, for the forward pass's and the skybox's (`pass` names it in the error
// for more than kMaxForwardDiskLights).
inline Result<std::vector<ShaderDefine>> disk_light_defines(const std::vector<DiskLight>& disks, const char* pass) {
    if (disks.size() > kMaxForwardDiskLights)
        return Error{std::string(pass) + " shades at most " + std::to_string(kMaxForwardDiskLights) +
                     " disk lights extracted from the environment, not " + std::to_string(disks.size()) +
                     " (LightExtractionSettings::max_lights)"};
    std::vector<ShaderDefine> defines;
    if (disks.empty()) return defines;
    defines.push_back({"DISK_LIGHTS", std::to_string(disks.size())});
    for (size_t i = 0; i < disks.size(); ++i)
        defines.push_back({"FACET_DISK_LIGHT_" + std::to_string(i), packed_light_literal(disk_data(disks[i]))});
    return defines;
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
