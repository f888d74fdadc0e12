#include "swapchain.h"

#include <algorithm>

#include <facet/gpu/context.h>

namespace facet {

Result<std::unique_ptr<Swapchain>> Swapchain::create(Context& context, VkSurfaceKHR surface, uint32_t width,
                                                     uint32_t height) {
    std::unique_ptr<Swapchain> s(new Swapchain(context, surface));
    VkBool32 supported = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(context.physical_device(), context.queue_family(), surface, &supported);
    if (!supported) return Error{context.device_name() + " cannot present to this window"};
    if (Status st = s->recreate(width, height); !st) return st.error();
    return s;
}

Status Swapchain::recreate(uint32_t width, uint32_t height) {
    VkPhysicalDevice gpu = context_.physical_device();
    VkSurfaceCapabilitiesKHR caps;
    if (VkResult r = vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu, surface_, &caps); r != VK_SUCCESS)
        return Error{std::string("vkGetPhysicalDeviceSurfaceCapabilitiesKHR: ") + vk_result_name(r), r};
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface_, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface_, &count, formats.data());
    // UNORM: the tone-mapping pass already encodes sRGB; the copy must not encode again.
    VkSurfaceFormatKHR chosen{VK_FORMAT_UNDEFINED, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR};
    for (const VkSurfaceFormatKHR& f : formats)
        if ((f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
            chosen = f;
    if (chosen.format == VK_FORMAT_UNDEFINED) return Error{"the window offers no 8-bit UNORM swapchain format"};
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if ((caps.supportedUsageFlags & usage) != usage)
        return Error{"the window's swapchain images cannot be copied to and drawn on"};
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {
        extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface_;
    info.minImageCount = std::max(caps.minImageCount, 2u);
    if (caps.maxImageCount) info.minImageCount = std::min(info.minImageCount, caps.maxImageCount);
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = usage;  // the frame is copied in, the panels drawn over it
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    if (VkResult r = vkCreateSwapchainKHR(context_.device(), &info, nullptr, &created); r != VK_SUCCESS)
        return Error{std::string("vkCreateSwapchainKHR: ") + vk_result_name(r), r};
    if (swapchain_) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
    swapchain_ = created;
    format_ = chosen.format;
    extent_ = extent;
    vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, images_.data());
    return Ok{};
}

Swapchain::~Swapchain() {
    if (swapchain_) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
    if (surface_) vkDestroySurfaceKHR(context_.instance(), surface_, nullptr);
}

}  // namespace facet
