#pragma once
// A window's swapchain for the viewer: created for the context's device and queue
// (which must be able to present to the surface), recreated on resize.
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>

namespace facet {

class Context;

class Swapchain {
public:
    // Takes ownership of `surface` (destroyed with the swapchain).
    static Result<std::unique_ptr<Swapchain>> create(Context& context, VkSurfaceKHR surface, uint32_t width,
                                                     uint32_t height);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // For a new window size (after VK_ERROR_OUT_OF_DATE_KHR or a resize).
    Status recreate(uint32_t width, uint32_t height);

    VkSwapchainKHR handle() const { return swapchain_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    const std::vector<VkImage>& images() const { return images_; }

private:
    Swapchain(Context& context, VkSurfaceKHR surface) : context_(context), surface_(surface) {}
    Context& context_;
    VkSurfaceKHR surface_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
};

}  // namespace facet
