#include "viewer_ui.h"

#include <stdexcept>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <facet/gpu/context.h>
#include <facet/graph/graph_run.h>
#include "check_vk.h"
#include "swapchain.h"

namespace facet {
namespace {

void check_imgui_vk(VkResult r) { check_vk(r, "Dear ImGui's Vulkan backend"); }

}  // namespace

ViewerUi::ViewerUi(Context& context, GLFWwindow* window, const Swapchain& swapchain) : context_(context) {
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}};
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool.maxSets = 16;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = sizes;
    check_vk(vkCreateDescriptorPool(context.device(), &pool, nullptr, &pool_), "vkCreateDescriptorPool");

    // The graph leaves the image in COLOR_ATTACHMENT_OPTIMAL and moves it on afterwards,
    // so the render pass keeps that layout and loads what the frame copied in.
    VkAttachmentDescription color{};
    color.format = swapchain.format();
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &color;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    check_vk(vkCreateRenderPass(context.device(), &info, nullptr, &render_pass_), "vkCreateRenderPass");

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written into the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window, true);
    ImGui_ImplVulkan_InitInfo init{};
    init.Instance = context.instance();
    init.PhysicalDevice = context.physical_device();
    init.Device = context.device();
    init.QueueFamily = context.queue_family();
    init.Queue = context.queue();
    init.DescriptorPool = pool_;
    init.MinImageCount = 2;
    init.ImageCount = uint32_t(swapchain.images().size());
    init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    init.CheckVkResultFn = check_imgui_vk;
    ImGui_ImplVulkan_Init(&init, render_pass_);
    if (Status fonts = context.submit_and_wait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
        !fonts)
        throw std::runtime_error("viewer fonts: " + fonts.error().message);
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    rebuild(swapchain);
}

ViewerUi::~ViewerUi() {
    vkDeviceWaitIdle(context_.device());
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    destroy_framebuffers();
    vkDestroyRenderPass(context_.device(), render_pass_, nullptr);
    vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
}

void ViewerUi::destroy_framebuffers() {
    for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(context_.device(), f, nullptr);
    for (VkImageView v : views_) vkDestroyImageView(context_.device(), v, nullptr);
    framebuffers_.clear();
    views_.clear();
}

void ViewerUi::rebuild(const Swapchain& swapchain) {
    destroy_framebuffers();
    extent_ = swapchain.extent();
    for (VkImage image : swapchain.images()) {
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = swapchain.format();
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView v = VK_NULL_HANDLE;
        check_vk(vkCreateImageView(context_.device(), &view, nullptr, &v), "vkCreateImageView");
        views_.push_back(v);
        VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fb.renderPass = render_pass_;
        fb.attachmentCount = 1;
        fb.pAttachments = &v;
        fb.width = extent_.width;
        fb.height = extent_.height;
        fb.layers = 1;
        VkFramebuffer f = VK_NULL_HANDLE;
        check_vk(vkCreateFramebuffer(context_.device(), &fb, nullptr, &f), "vkCreateFramebuffer");
        framebuffers_.push_back(f);
    }
    ImGui_ImplVulkan_SetMinImageCount(2);
}

void ViewerUi::begin_frame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

bool ViewerUi::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ViewerUi::wants_keyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

ImageHandle ViewerUi::add_pass(RenderGraph& graph, ImageHandle target, uint32_t index) {
    ImGui::Render();
    ImageHandle written;
    graph.add_graphics_pass("ui", [&](PassBuilder& b) { written = b.color_attachment(target); },
                            [this, index](PassContext& pc) {
                                VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
                                begin.renderPass = render_pass_;
                                begin.framebuffer = framebuffers_.at(index);
                                begin.renderArea = {{0, 0}, extent_};
                                vkCmdBeginRenderPass(pc.cmd(), &begin, VK_SUBPASS_CONTENTS_INLINE);
                                ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), pc.cmd());
                                vkCmdEndRenderPass(pc.cmd());
                            });
    return written;
}

}  // namespace facet
