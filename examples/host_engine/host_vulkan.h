#pragma once
// The host engine's own Vulkan: nothing here is Facet's. An instance (with the Khronos
// validation layer and synchronization validation when asked, every message counted),
// a device created with what facet::device_requirements() asks for, one queue, two
// command buffers and fences (frames in flight), and the frame's images.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/gpu/requirements.h>
#include <facet/gpu/resources.h>

namespace host {

[[noreturn]] inline void fail(const std::string& why) {
    std::fprintf(stderr, "host_engine: %s\n", why.c_str());
    std::exit(1);
}
inline void check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) fail(std::string(what) + " failed (" + std::to_string(int(r)) + ")");
}

struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    facet::ImageDesc desc;
};
struct FrameTargets {
    Image color, depth, hdr, ldr;  // MSAA colour and depth, resolved HDR, display RGBA8
};

struct Vulkan {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer commands[2]{};
    VkFence fences[2]{};
    uint32_t messages = 0;
};

inline VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        ++static_cast<Vulkan*>(user)->messages;
        std::fprintf(stderr, "host_engine: Validation: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

inline Vulkan* create(facet::DeviceRequirements& needs, bool validation) {
    auto* vk = new Vulkan;
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "host_engine";
    app.apiVersion = needs.api_version;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* debug_ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    const VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync;
    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.pNext = &features;
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    messenger.pfnUserCallback = on_message;
    messenger.pUserData = vk;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    if (validation) {
        info.pNext = &messenger;  // also reports what happens while the instance is made and destroyed
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = &layer;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &debug_ext;
    }
    check(vkCreateInstance(&info, nullptr, &vk->instance), "vkCreateInstance");
    if (validation) {
        messenger.pNext = nullptr;
        auto make = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(vk->instance, "vkCreateDebugUtilsMessengerEXT"));
        check(make(vk->instance, &messenger, nullptr, &vk->messenger), "vkCreateDebugUtilsMessengerEXT");
    }
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(vk->instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(vk->instance, &count, devices.data());
    for (VkPhysicalDevice d : devices) {  // the first Vulkan 1.3 device with a graphics + compute queue
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        if (p.apiVersion < needs.api_version) continue;
        uint32_t n = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(d, &n, nullptr);
        std::vector<VkQueueFamilyProperties> families(n);
        vkGetPhysicalDeviceQueueFamilyProperties(d, &n, families.data());
        for (uint32_t i = 0; i < n && !vk->physical_device; ++i)
            if ((families[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
                vk->physical_device = d;
                vk->queue_family = i;
            }
        if (vk->physical_device) break;
    }
    if (!vk->physical_device) fail("no Vulkan 1.3 device with a graphics and compute queue");
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = vk->queue_family;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo device{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device.pNext = needs.chain();  // Facet's features (and the host's own would follow)
    device.queueCreateInfoCount = 1;
    device.pQueueCreateInfos = &queue;
    device.enabledExtensionCount = uint32_t(needs.device_extensions.size());
    device.ppEnabledExtensionNames = needs.device_extensions.data();
    check(vkCreateDevice(vk->physical_device, &device, nullptr, &vk->device), "vkCreateDevice");
    vkGetDeviceQueue(vk->device, vk->queue_family, 0, &vk->queue);
    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = vk->queue_family;
    check(vkCreateCommandPool(vk->device, &pool, nullptr, &vk->pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo buffers{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    buffers.commandPool = vk->pool;
    buffers.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    buffers.commandBufferCount = 2;
    check(vkAllocateCommandBuffers(vk->device, &buffers, vk->commands), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    for (VkFence& f : vk->fences) check(vkCreateFence(vk->device, &fence, nullptr, &f), "vkCreateFence");
    return vk;
}

inline uint32_t memory_type(const Vulkan& vk, uint32_t bits, VkMemoryPropertyFlags want) {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(vk.physical_device, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & want) == want) return i;
    fail("no suitable memory type");
}

inline Image make_image(const Vulkan& vk, VkFormat format, uint32_t w, uint32_t h, VkSampleCountFlagBits samples,
                        VkImageUsageFlags usage) {
    Image image;
    image.desc.format = format;
    image.desc.width = w;
    image.desc.height = h;
    image.desc.samples = samples;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {w, h, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = samples;
    info.usage = usage;
    check(vkCreateImage(vk.device, &info, nullptr, &image.image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(vk.device, image.image, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = memory_type(vk, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkAllocateMemory(vk.device, &alloc, nullptr, &image.memory), "vkAllocateMemory");
    check(vkBindImageMemory(vk.device, image.image, image.memory, 0), "vkBindImageMemory");
    return image;
}

inline FrameTargets create_targets(const Vulkan& vk, uint32_t w, uint32_t h) {
    const auto msaa = VK_SAMPLE_COUNT_4_BIT;
    return {make_image(vk, VK_FORMAT_R16G16B16A16_SFLOAT, w, h, msaa, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT),
            make_image(vk, VK_FORMAT_D32_SFLOAT, w, h, msaa, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT),
            make_image(vk, VK_FORMAT_R16G16B16A16_SFLOAT, w, h, VK_SAMPLE_COUNT_1_BIT,
                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT),
            make_image(vk, VK_FORMAT_R8G8B8A8_UNORM, w, h, VK_SAMPLE_COUNT_1_BIT,
                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT)};
}

inline void destroy_targets(const Vulkan& vk, FrameTargets& t) {
    for (Image* i : {&t.color, &t.depth, &t.hdr, &t.ldr}) {
        vkDestroyImage(vk.device, i->image, nullptr);
        vkFreeMemory(vk.device, i->memory, nullptr);
    }
}

// Waits for the slot's previous frame (the host's fence), then starts its command buffer.
inline void begin_frame(Vulkan& vk, uint32_t slot) {
    check(vkWaitForFences(vk.device, 1, &vk.fences[slot], VK_TRUE, 10'000'000'000ull), "vkWaitForFences");
    check(vkResetFences(vk.device, 1, &vk.fences[slot]), "vkResetFences");
    check(vkResetCommandBuffer(vk.commands[slot], 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(vk.commands[slot], &begin), "vkBeginCommandBuffer");
}

inline void submit_frame(Vulkan& vk, uint32_t slot) {
    check(vkEndCommandBuffer(vk.commands[slot]), "vkEndCommandBuffer");
    VkCommandBufferSubmitInfo cmd{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd.commandBuffer = vk.commands[slot];
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd;
    check(vkQueueSubmit2(vk.queue, 1, &submit, vk.fences[slot]), "vkQueueSubmit2");
}

inline void wait_all(Vulkan& vk) {
    check(vkWaitForFences(vk.device, 2, vk.fences, VK_TRUE, 10'000'000'000ull), "vkWaitForFences");
}

// The RGBA8 image (left in TRANSFER_SRC_OPTIMAL by the frame) into host memory.
inline std::vector<uint8_t> read_back(Vulkan& vk, const Image& image) {
    const VkDeviceSize size = VkDeviceSize(image.desc.width) * image.desc.height * 4;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer buffer;
    check(vkCreateBuffer(vk.device, &info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(vk.device, buffer, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = memory_type(vk, req.memoryTypeBits,
                                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    VkDeviceMemory memory;
    check(vkAllocateMemory(vk.device, &alloc, nullptr, &memory), "vkAllocateMemory");
    check(vkBindBufferMemory(vk.device, buffer, memory, 0), "vkBindBufferMemory");
    begin_frame(vk, 0);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {image.desc.width, image.desc.height, 1};
    vkCmdCopyImageToBuffer(vk.commands[0], image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
    VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    to_host.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    to_host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &to_host;
    vkCmdPipelineBarrier2(vk.commands[0], &dep);
    submit_frame(vk, 0);
    wait_all(vk);
    std::vector<uint8_t> pixels(size);
    void* mapped = nullptr;
    check(vkMapMemory(vk.device, memory, 0, size, 0, &mapped), "vkMapMemory");
    std::memcpy(pixels.data(), mapped, size);
    vkUnmapMemory(vk.device, memory);
    vkDestroyBuffer(vk.device, buffer, nullptr);
    vkFreeMemory(vk.device, memory, nullptr);
    return pixels;
}

// Destroys the host's objects; returns the validation messages seen (object tracking
// reports any object still alive on the device here).
inline uint32_t destroy(Vulkan* vk) {
    vkDeviceWaitIdle(vk->device);  // the host's own device: the host may idle it
    for (VkFence f : vk->fences) vkDestroyFence(vk->device, f, nullptr);
    vkDestroyCommandPool(vk->device, vk->pool, nullptr);
    vkDestroyDevice(vk->device, nullptr);
    if (vk->messenger) {
        auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(vk->instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy_messenger(vk->instance, vk->messenger, nullptr);
    }
    vkDestroyInstance(vk->instance, nullptr);
    const uint32_t messages = vk->messages;
    delete vk;
    return messages;
}

}  // namespace host
