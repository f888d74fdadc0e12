#include "gpu/device_selection.h"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace facet {

bool has_device_extension(VkPhysicalDevice device, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

std::vector<std::string> device_lacks(VkPhysicalDevice device, const DeviceRequirements& needs) {
    // What the device supports, stated as if it had all been enabled.
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &features13};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features12};
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    if (properties.apiVersion >= VK_API_VERSION_1_2) vkGetPhysicalDeviceFeatures2(device, &features);
    EnabledDevice offered;
    offered.api_version = needs.api_version;  // the instance is Facet's own, made for it
    offered.physical_device = device;
    for (const VkExtensionProperties& e : extensions) offered.extensions.push_back(e.extensionName);
    offered.features = &features;
    return unmet_device_requirements(needs, offered);
}

std::string join(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
    return text;
}

namespace {

std::string lower(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

int type_rank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

std::string describe_devices(const std::vector<VkPhysicalDevice>& devices) {
    std::string text;
    for (size_t i = 0; i < devices.size(); ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        text += (i ? ", " : "") + std::to_string(i) + ": " + p.deviceName;
    }
    return text.empty() ? "none" : text;
}

}  // namespace

Result<VkPhysicalDevice> pick_device(VkInstance instance, const std::string& selector) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    const DeviceRequirements needs = device_requirements();
    auto usable = [&](VkPhysicalDevice d) { return device_lacks(d, needs).empty(); };
    if (!selector.empty()) {
        VkPhysicalDevice chosen = VK_NULL_HANDLE;
        bool is_index = std::all_of(selector.begin(), selector.end(),
                                    [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
        if (is_index) {
            size_t index = std::stoul(selector);
            if (index < devices.size()) chosen = devices[index];
        } else {
            for (VkPhysicalDevice d : devices) {
                VkPhysicalDeviceProperties p;
                vkGetPhysicalDeviceProperties(d, &p);
                if (lower(p.deviceName).find(lower(selector)) != std::string::npos) {
                    chosen = d;
                    break;
                }
            }
        }
        if (!chosen)
            return Error{"no Vulkan device matches '" + selector + "' (devices: " +
                         describe_devices(devices) + ")"};
        if (std::vector<std::string> lacks = device_lacks(chosen, needs); !lacks.empty())
            return Error{"device '" + selector + "' lacks " + join(lacks)};
        return chosen;
    }
    VkPhysicalDevice best = VK_NULL_HANDLE;
    int best_rank = 1 << 30;
    for (VkPhysicalDevice d : devices) {
        if (!usable(d)) continue;
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        if (type_rank(p.deviceType) < best_rank) {
            best = d;
            best_rank = type_rank(p.deviceType);
        }
    }
    if (!best)
        return Error{"no Vulkan device meets Facet's requirements (Vulkan 1.3, synchronization2, "
                     "dynamicRendering, VK_KHR_push_descriptor; devices: " +
                         describe_devices(devices) + "); install mesa-vulkan-drivers for lavapipe",
                     VK_ERROR_INCOMPATIBLE_DRIVER};
    return best;
}

std::optional<uint32_t> find_queue_family(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need) return i;
    }
    return std::nullopt;
}

}  // namespace facet
