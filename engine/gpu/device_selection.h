#pragma once
// Which physical device Facet creates its own context on, and what a device offers.
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/gpu/requirements.h>

namespace facet {

bool has_device_extension(VkPhysicalDevice device, const char* name);

// The requirements `device` cannot meet (unsupported version, feature or extension).
std::vector<std::string> device_lacks(VkPhysicalDevice device, const DeviceRequirements& needs);

// "a, b, c".
std::string join(const std::vector<std::string>& items);

// The selector (index or name substring), else discrete > integrated > virtual > CPU
// (lavapipe), among the devices that meet device_requirements().
Result<VkPhysicalDevice> pick_device(VkInstance instance, const std::string& selector);

std::optional<uint32_t> find_queue_family(VkPhysicalDevice device);

}  // namespace facet
