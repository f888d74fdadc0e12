#pragma once
// The viewer's own Vulkan calls (swapchain, UI): a failure ends the program with the
// call's name and the VkResult (run_program prints it and exits 1).
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>

namespace facet {

inline void check_vk(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (" + vk_result_name(result) + ")");
}

}  // namespace facet
