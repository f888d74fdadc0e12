#pragma once
// What Facet needs of a Vulkan device, as data a host engine chains into its own
// VkDeviceCreateInfo. The one definition: Context::create enables exactly this (plus the
// optional features below when the device has them) and Context::adopt checks a host's
// device against it.
//
//   facet::DeviceRequirements needs = facet::device_requirements();
//   needs.device_extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);  // the host's own
//   VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
//   info.pNext = needs.chain();  // VkPhysicalDeviceFeatures2 -> Vulkan12 -> Vulkan13
//   info.enabledExtensionCount = uint32_t(needs.device_extensions.size());
//   info.ppEnabledExtensionNames = needs.device_extensions.data();
//
// Thread safety: free functions, no shared state.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace facet {

struct DeviceRequirements {
    // The Vulkan version the instance must be created for (VkApplicationInfo::apiVersion)
    // and the physical device must support.
    uint32_t api_version = VK_API_VERSION_1_3;
    // Device extensions to enable (string literals: they outlive every copy).
    std::vector<const char*> device_extensions;
    // Features to enable: every member set to VK_TRUE. Required ones are set by
    // device_requirements(); add_supported_optional_features() adds the optional ones.
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features vulkan13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};

    // Links features -> vulkan12 -> vulkan13 -> `host_next` (the host's own feature or
    // other structs; nullptr: none) and returns the head, for VkDeviceCreateInfo::pNext.
    // Call it on the object that vkCreateDevice reads, after any copy or move (copies do
    // not re-link); the pointer is valid while this object lives.
    VkPhysicalDeviceFeatures2* chain(void* host_next = nullptr);

    // Also enables the core features Facet uses when a device has them and works
    // without (storage images without a format, anisotropic filtering, 64-bit floats in
    // shaders): those `physical_device` supports. Context::create calls it; a host may.
    void add_supported_optional_features(VkPhysicalDevice physical_device);
};

// Vulkan 1.3; synchronization2 and dynamicRendering (VkPhysicalDeviceVulkan13Features);
// VK_KHR_push_descriptor. No optional feature is set.
DeviceRequirements device_requirements();

// What a device was created with, as its creator states it (Vulkan cannot be asked which
// features a VkDevice has enabled).
struct EnabledDevice {
    uint32_t api_version = 0;                   // the instance's VkApplicationInfo::apiVersion
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;  // for the version it supports
    std::vector<std::string> extensions;        // VkDeviceCreateInfo::ppEnabledExtensionNames
    // VkDeviceCreateInfo::pNext: VkPhysicalDeviceFeatures2, VkPhysicalDeviceVulkan11/12/13
    // Features and the per-feature structs (VkPhysicalDeviceSynchronization2Features,
    // VkPhysicalDeviceDynamicRenderingFeatures, ...), in any order; others are skipped.
    const void* features = nullptr;
    // VkDeviceCreateInfo::pEnabledFeatures, when the core features were given there.
    const VkPhysicalDeviceFeatures* core_features = nullptr;
};

// Each requirement `device` does not meet, named: "Vulkan 1.3 (the instance asks for
// 1.2)", "feature synchronization2 (VkPhysicalDeviceVulkan13Features)", "extension
// VK_KHR_push_descriptor". Empty: the device is fit for Facet.
std::vector<std::string> unmet_device_requirements(const DeviceRequirements& needs, const EnabledDevice& device);

}  // namespace facet
