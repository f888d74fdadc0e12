// facet-viewer: the thesis' sample program on Vulkan. A GLFW window shows the forward
// PBR frame of a model under an environment; WASD + mouse fly the camera (Tab: orbit
// around the target instead), R frames the model again, F12 saves a screenshot. Scripted
// use (CI, tests): --frames N renders N frames and exits, --screenshot FILE saves the
// last one. The swapchain image is imported into each frame's render graph; the display
// image is copied into it by a transfer pass.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

#include "cli.h"
#include "gpu/context.h"
#include "gpu/transfer.h"
#include "graph/compiled_graph.h"
#include "graph/graph_run.h"
#include "io/image_io.h"
#include "render/camera.h"
#include "render_job.h"
#include "render_options.h"
#include "swapchain.h"

namespace {

using namespace facet;

constexpr const char* program = "facet-viewer";

struct Options {
    RenderJob job;
    int frames = 0;  // 0: until the window closes
    std::string screenshot, device;
};

std::optional<Options> parse(int argc, char** argv) {
    cli::Parser p(program, "[--model PATH|builtin:NAME] [--env PATH|builtin:NAME|none] [options]",
                  "Shows a glTF model or a built-in scene under an environment with the forward PBR pass.\n"
                  "Keys: WASD move, mouse (left button) look, Tab fly/orbit, R reset the camera, F12 screenshot,\n"
                  "Esc quit. --frames N renders N frames and exits (with --screenshot FILE: the last one).");
    add_render_options(p);
    p.option("--frames", "N", "render N frames, then exit (default: until the window closes)")
        .option("--screenshot", "FILE", "save the last frame as FILE (.png tone-mapped, .exr linear)")
        .option("--device", "NAME|INDEX", "Vulkan device (default: FACET_DEVICE, a GPU, else lavapipe)");
    cli::Parsed a = p.parse(argc, argv);
    if (p.answered_help_or_version(a, FACET_VERSION)) return std::nullopt;
    if (!a.positional.empty()) throw std::invalid_argument("unexpected argument '" + a.positional[0] + "'");
    Options o;
    o.job.frame.width = 960;
    o.job.frame.height = 540;
    parse_render_options(a, o.job);
    if (a.has("--frames")) o.frames = cli::parse_int(a.get("--frames"), "--frames", 1, 1000000);
    o.screenshot = a.get("--screenshot");
    if (!o.screenshot.empty() && o.screenshot.size() < 5)
        throw std::invalid_argument("--screenshot: expected a .png or .exr file name");
    o.device = a.get("--device");
    return o;
}

// Fly camera (yaw/pitch around the position) or orbit camera (around the target).
struct CameraControl {
    CameraView view, home;
    bool orbit = false;
    double last_x = 0, last_y = 0;
    bool dragging = false;

    void update(GLFWwindow* window, double seconds) {
        glm::vec3 forward = glm::normalize(view.target - view.position);
        const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
        const float speed = 0.5f * glm::length(home.target - home.position) * float(seconds);
        glm::vec3 move(0.0f);
        if (glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS) move += forward;
        if (glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS) move -= forward;
        if (glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS) move += right;
        if (glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS) move -= right;
        view.position += move * speed;
        if (!orbit) view.target += move * speed;
        double x, y;
        glfwGetCursorPos(window, &x, &y);
        const bool pressed = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        if (pressed && dragging) {
            const float yaw = float(x - last_x) * -0.005f, pitch = float(y - last_y) * -0.005f;
            const glm::vec3 pivot = orbit ? view.target : view.position;
            glm::vec3 arm = orbit ? view.position - view.target : view.target - view.position;
            const glm::mat4 turn = glm::rotate(glm::rotate(glm::mat4(1.0f), yaw, glm::vec3(0, 1, 0)), pitch, right);
            arm = glm::vec3(turn * glm::vec4(arm, 0.0f));
            if (std::abs(glm::normalize(arm).y) < 0.99f) {
                if (orbit) view.position = pivot + arm;
                else view.target = pivot + arm;
            }
        }
        dragging = pressed;
        last_x = x;
        last_y = y;
    }
};

CameraControl* control_of(GLFWwindow* w) { return static_cast<CameraControl*>(glfwGetWindowUserPointer(w)); }

struct FrameSync {
    VkDevice device;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkSemaphore acquired = VK_NULL_HANDLE, rendered = VK_NULL_HANDLE;
    VkFence done = VK_NULL_HANDLE;
    explicit FrameSync(Context& c) : device(c.device()) {
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = c.queue_family();
        vk_check(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        vk_check(vkAllocateCommandBuffers(device, &alloc, &cmd), "vkAllocateCommandBuffers");
        VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        vk_check(vkCreateSemaphore(device, &semaphore, nullptr, &acquired), "vkCreateSemaphore");
        vk_check(vkCreateSemaphore(device, &semaphore, nullptr, &rendered), "vkCreateSemaphore");
        VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vk_check(vkCreateFence(device, &fence, nullptr, &done), "vkCreateFence");
    }
    ~FrameSync() {
        vkDestroyFence(device, done, nullptr);
        vkDestroySemaphore(device, rendered, nullptr);
        vkDestroySemaphore(device, acquired, nullptr);
        vkDestroyCommandPool(device, pool, nullptr);
    }
};

Status save(const std::string& path, uint32_t w, uint32_t h, const std::vector<std::byte>& ldr,
            const std::vector<float>& hdr, float exposure) {
    if (path.size() > 4 && path.substr(path.size() - 4) == ".exr") {
        std::vector<float> exposed = hdr;
        for (size_t i = 0; i < exposed.size(); ++i)
            if (i % 4 != 3) exposed[i] *= exposure;
        return write_hdr_image(path, w, h, exposed);
    }
    std::vector<uint8_t> bytes(ldr.size());
    std::memcpy(bytes.data(), ldr.data(), ldr.size());
    return write_ldr_image(path, w, h, bytes);
}

int run(const Options& o) {
    if (!glfwInit()) throw std::runtime_error("cannot open a window (GLFW could not start; is DISPLAY set?)");
    struct GlfwGuard {
        ~GlfwGuard() { glfwTerminate(); }
    } glfw_guard;
    if (!glfwVulkanSupported()) throw std::runtime_error("GLFW finds no Vulkan loader");
    uint32_t count = 0;
    const char** required = glfwGetRequiredInstanceExtensions(&count);
    ContextOptions options;
    options.device = o.device;
    options.app_name = program;
    for (uint32_t i = 0; i < count; ++i) options.instance_extensions.push_back(required[i]);
    options.device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    auto created = Context::create(options);
    if (!created) throw std::runtime_error("cannot start Vulkan: " + created.error().message);
    Context& context = *created.value();

    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    GLFWwindow* window = glfwCreateWindow(int(o.job.frame.width), int(o.job.frame.height), program, nullptr, nullptr);
    if (!window) throw std::runtime_error("cannot open a window");
    struct WindowGuard {
        GLFWwindow* w;
        ~WindowGuard() { glfwDestroyWindow(w); }
    } window_guard{window};
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    if (VkResult r = glfwCreateWindowSurface(context.instance(), window, nullptr, &surface); r != VK_SUCCESS)
        throw std::runtime_error(std::string("cannot create a Vulkan surface: ") + vk_result_name(r));
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    auto swapchain = Swapchain::create(context, surface, uint32_t(fb_w), uint32_t(fb_h));
    if (!swapchain) throw std::runtime_error(swapchain.error().message);

    auto log = [](const std::string& line) { std::fprintf(stderr, "%s: %s\n", program, line.c_str()); };
    RenderJob job = o.job;
    job.frame.width = (*swapchain)->extent().width;
    job.frame.height = (*swapchain)->extent().height;
    auto session = RenderSession::create(context, job, log);
    if (!session) throw std::runtime_error(session.error().message);
    CameraControl control;
    control.view = control.home = (*session)->camera();
    glfwSetWindowUserPointer(window, &control);
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
        if (action != GLFW_PRESS) return;
        CameraControl* c = control_of(w);
        if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
        if (key == GLFW_KEY_TAB) c->orbit = !c->orbit;
        if (key == GLFW_KEY_R) c->view = c->home;
    });

    FrameSync sync(context);
    int frame = 0;
    double last = glfwGetTime();
    bool screenshot_key = false;
    while (!glfwWindowShouldClose(window) && (o.frames == 0 || frame < o.frames)) {
        glfwPollEvents();
        const double now = glfwGetTime();
        control.update(window, now - last);
        last = now;
        screenshot_key = screenshot_key || glfwGetKey(window, GLFW_KEY_F12) == GLFW_PRESS;
        glfwGetFramebufferSize(window, &fb_w, &fb_h);
        if (fb_w == 0 || fb_h == 0) continue;  // minimised
        uint32_t index = 0;
        VkResult acquired = vkAcquireNextImageKHR(context.device(), (*swapchain)->handle(), UINT64_MAX, sync.acquired,
                                                  VK_NULL_HANDLE, &index);
        const VkExtent2D extent = (*swapchain)->extent();
        if (acquired == VK_ERROR_OUT_OF_DATE_KHR || uint32_t(fb_w) != extent.width || uint32_t(fb_h) != extent.height) {
            // A resize: the swapchain (and any image acquired from it) is replaced.
            vkDeviceWaitIdle(context.device());
            if (Status st = (*swapchain)->recreate(uint32_t(fb_w), uint32_t(fb_h)); !st)
                throw std::runtime_error(st.error().message);
            vkDestroySemaphore(context.device(), sync.acquired, nullptr);
            VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
            vk_check(vkCreateSemaphore(context.device(), &semaphore, nullptr, &sync.acquired), "vkCreateSemaphore");
            continue;
        }
        if (acquired != VK_SUCCESS && acquired != VK_SUBOPTIMAL_KHR)
            throw std::runtime_error(std::string("vkAcquireNextImageKHR: ") + vk_result_name(acquired));

        FrameSettings& settings = (*session)->frame_settings();
        settings.camera = control.view;
        settings.width = extent.width;
        settings.height = extent.height;
        RenderGraph graph;
        auto images = (*session)->add_frame_passes(graph);
        if (!images) throw std::runtime_error(images.error().message);
        ImageDesc swap_desc;
        swap_desc.format = (*swapchain)->format();
        swap_desc.width = extent.width;
        swap_desc.height = extent.height;
        // The semaphore wait covers every stage, so the graph may start from any of them.
        ImageHandle target = graph.import_image(
            "swapchain image", {(*swapchain)->images()[index], swap_desc,
                                {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE},
                                {VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                 VK_ACCESS_2_NONE}});
        const ImageHandle ldr = images->ldr;
        graph.add_transfer_pass("copy to the window", [&](PassBuilder& b) {
            b.copy_from(ldr);
            target = b.copy_to(target);
        }, [ldr, target, extent](PassContext& pc) {
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            blit.srcOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
            blit.dstSubresource = blit.srcSubresource;
            blit.dstOffsets[1] = blit.srcOffsets[1];
            vkCmdBlitImage(pc.cmd(), pc.image(ldr), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pc.image(target),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        });
        const bool last_frame = o.frames != 0 && frame + 1 == o.frames;
        const bool capture = (last_frame && !o.screenshot.empty()) || screenshot_key;
        const ResourceState readable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                     VK_ACCESS_2_TRANSFER_READ_BIT};
        if (capture) {
            graph.export_image(ldr, readable);
            graph.export_image(images->hdr, readable);
        }
        CompiledGraph compiled = graph.compile();
        GraphRun run(context, compiled);
        vk_check(vkResetCommandBuffer(sync.cmd, 0), "vkResetCommandBuffer");
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vk_check(vkBeginCommandBuffer(sync.cmd, &begin), "vkBeginCommandBuffer");
        run.record(sync.cmd);
        vk_check(vkEndCommandBuffer(sync.cmd), "vkEndCommandBuffer");
        VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        wait.semaphore = sync.acquired;
        wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        signal.semaphore = sync.rendered;
        signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        VkCommandBufferSubmitInfo buffer{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        buffer.commandBuffer = sync.cmd;
        VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        submit.waitSemaphoreInfoCount = 1;
        submit.pWaitSemaphoreInfos = &wait;
        submit.commandBufferInfoCount = 1;
        submit.pCommandBufferInfos = &buffer;
        submit.signalSemaphoreInfoCount = 1;
        submit.pSignalSemaphoreInfos = &signal;
        vk_check(vkQueueSubmit2(context.queue(), 1, &submit, sync.done), "vkQueueSubmit2");
        VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        present.waitSemaphoreCount = 1;
        present.pWaitSemaphores = &sync.rendered;
        present.swapchainCount = 1;
        const VkSwapchainKHR handle = (*swapchain)->handle();
        present.pSwapchains = &handle;
        present.pImageIndices = &index;
        const VkResult presented = vkQueuePresentKHR(context.queue(), &present);
        // One frame in flight: the graph's resources live until its work is done.
        vk_check(vkWaitForFences(context.device(), 1, &sync.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        vk_check(vkResetFences(context.device(), 1, &sync.done), "vkResetFences");
        if (presented != VK_SUCCESS && presented != VK_SUBOPTIMAL_KHR && presented != VK_ERROR_OUT_OF_DATE_KHR)
            throw std::runtime_error(std::string("vkQueuePresentKHR: ") + vk_result_name(presented));
        if (capture) {
            const std::string path = !o.screenshot.empty() && last_frame ? o.screenshot
                                                                        : "facet-viewer-" + std::to_string(frame) + ".png";
            auto ldr_bytes = read_image(context, *run.transient_image(ldr), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            auto hdr_bytes = read_image(context, *run.transient_image(images->hdr), 0, 0,
                                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            std::vector<float> hdr(hdr_bytes.size() / 4);
            std::memcpy(hdr.data(), hdr_bytes.data(), hdr.size() * 4);
            if (Status st = save(path, extent.width, extent.height, ldr_bytes, hdr, settings.display.exposure); !st)
                throw std::runtime_error(st.error().message);
            log("saved " + path);
            screenshot_key = false;
        }
        ++frame;
    }
    vkDeviceWaitIdle(context.device());
    swapchain->reset();
    log("rendered " + std::to_string(frame) + " frames");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return facet::cli::run_program(program, [&] { return parse(argc, argv); }, run);
}
