#pragma once
// The engine's internal exception for Vulkan failures deep inside its own calls. Every
// public entry point catches it (guarded(), core/guarded.h) and returns it as an
// Error{message, vk_result}; it is not part of the public API.
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>

namespace facet {

class VulkanError : public std::runtime_error {
public:
    VulkanError(VkResult result, const std::string& what);
    // Carries an Error on unchanged (its message already names the failure).
    explicit VulkanError(const Error& error);
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

// Throws VulkanError naming `what` unless result is VK_SUCCESS.
void vk_check(VkResult result, const char* what);

}  // namespace facet
