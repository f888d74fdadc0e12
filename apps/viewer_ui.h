#pragma once
// The viewer's Dear ImGui layer (Debian's libimgui-dev, GLFW and Vulkan backends): a
// render pass over the swapchain image (ImGui 1.86 draws inside a VkRenderPass), its
// framebuffers, and a graph pass that draws the panels after the frame has been copied in.
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/graph/render_graph.h>

struct GLFWwindow;

namespace facet {

class Context;
class Swapchain;

class ViewerUi {
public:
    ViewerUi(Context& context, GLFWwindow* window, const Swapchain& swapchain);
    ~ViewerUi();
    ViewerUi(const ViewerUi&) = delete;
    ViewerUi& operator=(const ViewerUi&) = delete;

    // After the swapchain was recreated.
    void rebuild(const Swapchain& swapchain);
    // Starts the ImGui frame; panels are built between this and add_pass.
    void begin_frame();
    // Finishes the ImGui frame and draws it over swapchain image `index`; returns the
    // image's new version.
    ImageHandle add_pass(RenderGraph& graph, ImageHandle target, uint32_t index);
    bool wants_mouse() const;
    bool wants_keyboard() const;

private:
    void destroy_framebuffers();
    Context& context_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
    VkExtent2D extent_{};
};

}  // namespace facet
