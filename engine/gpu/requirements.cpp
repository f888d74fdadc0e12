#include <facet/gpu/requirements.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <type_traits>

namespace facet {

namespace {

// The feature structs hold nothing but VkBool32 members after their header, so each is
// compared as an array of flags; a name is looked up by the member's offset.
template <class S>
constexpr size_t first_flag_offset() {
    if constexpr (std::is_same_v<S, VkPhysicalDeviceFeatures>) return 0;
    else return offsetof(S, pNext) + sizeof(void*);
}

template <class S>
constexpr size_t flag_count() {
    return (sizeof(S) - first_flag_offset<S>()) / sizeof(VkBool32);
}

template <class S>
VkBool32* flags(S& s) {
    return reinterpret_cast<VkBool32*>(reinterpret_cast<unsigned char*>(&s) + first_flag_offset<S>());
}
template <class S>
const VkBool32* flags(const S& s) {
    return reinterpret_cast<const VkBool32*>(reinterpret_cast<const unsigned char*>(&s) + first_flag_offset<S>());
}

struct FlagName {
    size_t offset;
    const char* name;
};

#define FACET_FLAG(S, member) FlagName{offsetof(S, member), #member}

// The members Facet requires or may plausibly require; others are named by position.
constexpr FlagName core_names[] = {
    FACET_FLAG(VkPhysicalDeviceFeatures, robustBufferAccess),
    FACET_FLAG(VkPhysicalDeviceFeatures, geometryShader),
    FACET_FLAG(VkPhysicalDeviceFeatures, independentBlend),
    FACET_FLAG(VkPhysicalDeviceFeatures, multiDrawIndirect),
    FACET_FLAG(VkPhysicalDeviceFeatures, depthClamp),
    FACET_FLAG(VkPhysicalDeviceFeatures, fillModeNonSolid),
    FACET_FLAG(VkPhysicalDeviceFeatures, wideLines),
    FACET_FLAG(VkPhysicalDeviceFeatures, samplerAnisotropy),
    FACET_FLAG(VkPhysicalDeviceFeatures, textureCompressionBC),
    FACET_FLAG(VkPhysicalDeviceFeatures, pipelineStatisticsQuery),
    FACET_FLAG(VkPhysicalDeviceFeatures, fragmentStoresAndAtomics),
    FACET_FLAG(VkPhysicalDeviceFeatures, shaderStorageImageExtendedFormats),
    FACET_FLAG(VkPhysicalDeviceFeatures, shaderStorageImageReadWithoutFormat),
    FACET_FLAG(VkPhysicalDeviceFeatures, shaderStorageImageWriteWithoutFormat),
    FACET_FLAG(VkPhysicalDeviceFeatures, shaderFloat64),
    FACET_FLAG(VkPhysicalDeviceFeatures, shaderInt64),
    FACET_FLAG(VkPhysicalDeviceFeatures, shaderInt16),
};
constexpr FlagName vulkan12_names[] = {
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, shaderFloat16),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, shaderInt8),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, descriptorIndexing),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, runtimeDescriptorArray),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, scalarBlockLayout),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, uniformBufferStandardLayout),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, hostQueryReset),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, timelineSemaphore),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, bufferDeviceAddress),
    FACET_FLAG(VkPhysicalDeviceVulkan12Features, vulkanMemoryModel),
};
constexpr FlagName vulkan13_names[] = {
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, robustImageAccess),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, inlineUniformBlock),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, pipelineCreationCacheControl),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, privateData),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, shaderDemoteToHelperInvocation),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, shaderTerminateInvocation),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, subgroupSizeControl),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, computeFullSubgroups),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, synchronization2),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, shaderZeroInitializeWorkgroupMemory),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, dynamicRendering),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, shaderIntegerDotProduct),
    FACET_FLAG(VkPhysicalDeviceVulkan13Features, maintenance4),
};
#undef FACET_FLAG

template <class S, size_t N>
std::string flag_name(const FlagName (&names)[N], size_t index) {
    const size_t offset = first_flag_offset<S>() + index * sizeof(VkBool32);
    for (const FlagName& n : names)
        if (n.offset == offset) return n.name;
    std::string text = "#";
    text += std::to_string(index);
    return text;
}

// Everything a creator enabled, gathered from the chain into one struct per version.
struct Enabled {
    VkPhysicalDeviceFeatures core{};
    VkPhysicalDeviceVulkan12Features vulkan12{};
    VkPhysicalDeviceVulkan13Features vulkan13{};
};

template <class S>
void merge(S& into, const S& from) {
    VkBool32* to = flags(into);
    const VkBool32* f = flags(from);
    for (size_t i = 0; i < flag_count<S>(); ++i) to[i] = to[i] || f[i];
}

Enabled gather(const EnabledDevice& device) {
    Enabled e;
    if (device.core_features) merge(e.core, *device.core_features);
    for (auto* s = static_cast<const VkBaseInStructure*>(device.features); s; s = s->pNext) {
        switch (s->sType) {
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2:
                merge(e.core, reinterpret_cast<const VkPhysicalDeviceFeatures2*>(s)->features);
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES:
                merge(e.vulkan12, *reinterpret_cast<const VkPhysicalDeviceVulkan12Features*>(s));
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES:
                merge(e.vulkan13, *reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(s));
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
                e.vulkan13.synchronization2 |=
                    reinterpret_cast<const VkPhysicalDeviceSynchronization2Features*>(s)->synchronization2;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
                e.vulkan13.dynamicRendering |=
                    reinterpret_cast<const VkPhysicalDeviceDynamicRenderingFeatures*>(s)->dynamicRendering;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES:
                e.vulkan13.maintenance4 |= reinterpret_cast<const VkPhysicalDeviceMaintenance4Features*>(s)->maintenance4;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_HOST_QUERY_RESET_FEATURES:
                e.vulkan12.hostQueryReset |=
                    reinterpret_cast<const VkPhysicalDeviceHostQueryResetFeatures*>(s)->hostQueryReset;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES:
                e.vulkan12.timelineSemaphore |=
                    reinterpret_cast<const VkPhysicalDeviceTimelineSemaphoreFeatures*>(s)->timelineSemaphore;
                break;
            default: break;
        }
    }
    return e;
}

template <class S, size_t N>
void list_missing(const S& needed, const S& enabled, const FlagName (&names)[N], const char* structure,
                  std::vector<std::string>& out) {
    const VkBool32* need = flags(needed);
    const VkBool32* have = flags(enabled);
    for (size_t i = 0; i < flag_count<S>(); ++i)
        if (need[i] && !have[i]) {
            std::string text = "feature ";
            text += flag_name<S>(names, i);
            text += " (";
            text += structure;
            text += ")";
            out.push_back(std::move(text));
        }
}

std::string version_text(uint32_t version) {
    std::string text = std::to_string(VK_API_VERSION_MAJOR(version));
    text += ".";
    text += std::to_string(VK_API_VERSION_MINOR(version));
    return text;
}

}  // namespace

VkPhysicalDeviceFeatures2* DeviceRequirements::chain(void* host_next) {
    features.pNext = &vulkan12;
    vulkan12.pNext = &vulkan13;
    vulkan13.pNext = host_next;
    return &features;
}

void DeviceRequirements::add_supported_optional_features(VkPhysicalDevice physical_device) {
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physical_device, &supported);
    VkPhysicalDeviceFeatures& f = features.features;
    f.shaderStorageImageWriteWithoutFormat |= supported.shaderStorageImageWriteWithoutFormat;
    f.shaderStorageImageReadWithoutFormat |= supported.shaderStorageImageReadWithoutFormat;
    f.samplerAnisotropy |= supported.samplerAnisotropy;
    f.shaderFloat64 |= supported.shaderFloat64;
}

DeviceRequirements device_requirements() {
    DeviceRequirements needs;
    needs.api_version = VK_API_VERSION_1_3;
    needs.device_extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    // Every barrier is a VkDependencyInfo (vkCmdPipelineBarrier2), every raster pass
    // vkCmdBeginRendering.
    needs.vulkan13.synchronization2 = VK_TRUE;
    needs.vulkan13.dynamicRendering = VK_TRUE;
    return needs;
}

std::vector<std::string> unmet_device_requirements(const DeviceRequirements& needs, const EnabledDevice& device) {
    std::vector<std::string> missing;
    if (device.api_version < needs.api_version)
        missing.push_back("Vulkan " + version_text(needs.api_version) + " (the instance asks for " +
                          (device.api_version ? version_text(device.api_version) : std::string("no version")) + ")");
    if (device.physical_device) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(device.physical_device, &p);
        if (p.apiVersion < needs.api_version)
            missing.push_back("Vulkan " + version_text(needs.api_version) + " (the device supports " +
                              version_text(p.apiVersion) + ")");
    }
    const Enabled enabled = gather(device);
    list_missing(needs.features.features, enabled.core, core_names, "VkPhysicalDeviceFeatures", missing);
    list_missing(needs.vulkan12, enabled.vulkan12, vulkan12_names, "VkPhysicalDeviceVulkan12Features", missing);
    list_missing(needs.vulkan13, enabled.vulkan13, vulkan13_names, "VkPhysicalDeviceVulkan13Features", missing);
    for (const char* extension : needs.device_extensions)
        if (std::find(device.extensions.begin(), device.extensions.end(), extension) == device.extensions.end())
            missing.push_back(std::string("extension ") + extension);
    return missing;
}

}  // namespace facet
