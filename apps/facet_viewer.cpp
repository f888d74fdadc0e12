// facet-viewer: the thesis' sample program on Vulkan. A GLFW window shows the forward
// PBR frame of a model under an environment, with Dear ImGui panels for the model, its
// material preset, the environment, the display, the component view and pass times;
// WASD + mouse fly the camera (Tab: orbit around the target instead), R frames the model
// again, F12 saves a screenshot. Scripted use (CI, tests): --script runs commands,
// --frames N / --screenshot FILE are shorthands. The swapchain image is imported into
// each frame's render graph: the display image is copied into it, then the panels drawn.
// Choosing another model, environment, preset or method loads and bakes on a worker
// thread (viewer_loader.h) while the window keeps drawing the current scene; the new one
// is swapped in between frames.
// SIGINT and SIGTERM close the window as Esc does (exit status 128 + the signal).
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <cstdio>
#include <cstring>
#include <optional>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>
#include <glm/gtc/matrix_transform.hpp>

#include "cli.h"
#include "interrupt.h"
#include "facet_viewer_options.h"
#include <facet/gpu/context.h>
#include <facet/gpu/memory.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_executor.h>
#include <facet/graph/graph_run.h>
#include <facet/io/image_io.h>
#include <facet/render/camera.h>
#include <facet/render/render_job.h>
#include "render_options.h"
#include "start_vulkan.h"
#include <facet/render/tonemap.h>
#include <facet/scene/material_presets.h>
#include <facet/shader/program_cache.h>
#include "swapchain.h"
#include "viewer_frame_clock.h"
#include "viewer_loader.h"
#include "viewer_panels.h"
#include "viewer_support.h"
#include "viewer_ui.h"

namespace {

using namespace facet;

constexpr const char* program = "facet-viewer";

using Options = ViewerOptions;

// Modification times of every file under a directory, polled a few times a second.
class ShaderWatch {
public:
    explicit ShaderWatch(std::string dir) : dir_(std::move(dir)) { stamp_ = scan(); }
    bool changed(double now) {
        if (dir_.empty() || now - last_poll_ < 0.25) return false;
        last_poll_ = now;
        const std::string stamp = scan();
        if (stamp == stamp_) return false;
        stamp_ = stamp;
        return true;
    }

private:
    std::string scan() const {
        std::string stamp;
        std::error_code ec;
        for (auto it = std::filesystem::recursive_directory_iterator(dir_, ec);
             !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec))
            if (it->is_regular_file(ec))
                stamp += it->path().string() + "@" +
                         std::to_string(std::filesystem::last_write_time(it->path(), ec).time_since_epoch().count()) + ";";
        return stamp;
    }
    std::string dir_, stamp_;
    double last_poll_ = 0;
};

// Where dropped files go (GLFW's drop callback takes no user data beside the window's).
ViewerControls* dropped_into = nullptr;

// The job for the controls' model, environment, preset and methods.
RenderJob job_for(const RenderJob& base, const ViewerControls& c) {
    RenderJob job = base;
    job.model = c.model;
    job.env = c.env;
    job.preset = c.preset.empty() ? std::nullopt : std::optional<std::string>(c.preset);
    job.ibl.irradiance.method = c.irradiance;
    job.ibl.specular.method = c.specular;
    // A saved bake (--ibl DIR) holds its own environment and methods: choosing others bakes them.
    if (c.env != base.env || c.irradiance != base.ibl.irradiance.method || c.specular != base.ibl.specular.method)
        job.ibl_dir.clear();
    return job;
}

// The panels show what a session holds once it is in use (the material override, if any,
// applied to it again).
void show_session(const RenderSession& session, ViewerControls& c) {
    c.status.clear();
    c.bake_passes = session.bake_timings();
    c.warnings = session.warnings();
    c.shading = session.shading();
    c.lights = session.frame().lights;
    c.material_changed = c.override_material;
}

int run(const Options& o) {
    if (!glfwInit()) throw std::runtime_error("cannot open a window (GLFW could not start; is DISPLAY set?)");
    struct GlfwGuard {
        ~GlfwGuard() { glfwTerminate(); }
    } glfw_guard;
    if (!glfwVulkanSupported()) throw std::runtime_error("GLFW finds no Vulkan loader");
    uint32_t count = 0;
    const char** required = glfwGetRequiredInstanceExtensions(&count);
    ContextOptions options = program_context_options(o.device);
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
    auto created_swapchain = Swapchain::create(context, surface, uint32_t(fb_w), uint32_t(fb_h));
    if (!created_swapchain) throw std::runtime_error(created_swapchain.error().message);
    std::unique_ptr<Swapchain> swapchain = std::move(*created_swapchain);
    // Long work (loading, baking) shows its progress in the title bar as well.
    auto log = [window](const std::string& line) {
        std::fprintf(stderr, "%s: %s\n", program, line.c_str());
        glfwSetWindowTitle(window, (std::string(program) + " - " + line).c_str());
    };

    ViewerControls controls;
    controls.model = o.job.model;
    controls.env = o.job.env;
    controls.preset = o.job.preset.value_or("");
    controls.display = o.job.frame.display;
    controls.skybox = o.job.frame.skybox;
    controls.irradiance = o.job.ibl.irradiance.method;
    controls.specular = o.job.ibl.specular.method;
    dropped_into = &controls;
    RenderJob base = o.job;
    base.frame.width = swapchain->extent().width;
    base.frame.height = swapchain->extent().height;
    // The first session before the window shows anything (there is nothing to draw meanwhile).
    auto first = RenderSession::create(context, job_for(base, controls), log);
    if (!first) throw std::runtime_error(first.error().message);
    std::unique_ptr<RenderSession> session = std::move(*first);
    std::string session_model = controls.model;
    show_session(*session, controls);
    auto show_title = [&] {
        glfwSetWindowTitle(window, (std::string(program) + " - " + controls.model + " under " + controls.env).c_str());
    };
    show_title();
    CameraControl camera;
    camera.view = camera.home = session->camera();
    glfwSetWindowUserPointer(window, &camera);
    auto ui = std::make_unique<ViewerUi>(context, window, *swapchain);
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
        ImGui_ImplGlfw_KeyCallback(w, key, scancode, action, mods);
        if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
        CameraControl* c = control_of(w);
        if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
        if (key == GLFW_KEY_TAB) c->orbit = !c->orbit;
        if (key == GLFW_KEY_R) c->view = c->home;
    });

    // Drag and drop: a glTF file becomes the model, an image the environment.
    glfwSetDropCallback(window, [](GLFWwindow*, int count, const char** paths) {
        for (int i = 0; i < count && dropped_into; ++i) {
            const std::string path = paths[i];
            const std::string ext = path.substr(path.find_last_of('.') + 1);
            if (ext == "gltf" || ext == "glb") dropped_into->model = path;
            else dropped_into->env = path;
            dropped_into->reload = true;
        }
    });
    auto made_nearest = Sampler::create(context, VK_FILTER_NEAREST, false, false, "viewer nearest");
    if (!made_nearest) throw std::runtime_error(made_nearest.error().message);
    const Sampler nearest = std::move(*made_nearest);
    ShaderCompilerOptions compiler_options;
    compiler_options.source_dir = o.job.shader_dir;
    compiler_options.disk_cache_dir = o.job.shader_cache_dir;
    ShaderCompiler compiler(compiler_options);
    ShaderWatch watch(o.job.shader_dir);
    controls.status = o.job.shader_dir.empty() ? "hot reload off (start with --shader-dir shaders)" : "";
    ProgramCache programs(context, compiler);
    FrameSync sync(context);
    // One frame in flight (the fence below); the executor keeps each frame's images for
    // the next, so steady frames create no image and allocate no memory.
    GraphExecutor executor(context, 1);
    // Later loads run here; destroyed (the load in progress stopped) before the context.
    auto loader = std::make_unique<SessionLoader>(context);
    // A load asked for and not yet swapped in (or failed): the script's "wait" and its
    // screenshots wait for it, frames go on.
    auto loading = [&] { return controls.reload || loader->pending(); };
    struct LoadWatch {
        double started = 0;                    // glfwGetTime() of the request
        int frames = 0, frames_in_passes = 0;  // drawn meanwhile; of them, while the bake's passes ran
    } load_watch;
    bool load_failed = false;  // a scripted session then exits with status 1
    size_t step = 0;       // next script command
    int frames_left = 0;   // of the current "frames N"
    std::string screenshot;
    int frame = 0;
    // Device allocations and images made by this thread inside frames after each
    // session's first (graph build to fence; screenshot frames, which export more, aside):
    // zero while the frame keeps its shape (the executor reuses the images), also while a
    // load allocates on its worker.
    uint64_t later_allocations = 0, later_images = 0;
    int session_frame = 0;  // frames drawn with the current session
    FrameClock clock;  // frames per second and the longest frame, logged at the end
    double last = glfwGetTime();
    int exit_status = 0;
    while (!glfwWindowShouldClose(window)) {
        if (int sig = interrupt_signal()) {
            // Between frames: the teardown below runs as after Esc.
            exit_status = report_interrupted(Interrupted{sig}, "closing the window");
            glfwSetWindowShouldClose(window, GLFW_TRUE);
            break;
        }
        // Script: apply commands until one asks for frames.
        const bool scripted = !o.script.empty();
        while (scripted && frames_left == 0 && screenshot.empty() && step < o.script.size()) {
            const std::string& command = o.script[step];
            if (command == "wait" && loading()) break;  // frames go on until the load is done
            // Frames go on until the requested load's bake has run a pass (tests: a choice made mid-bake).
            if (command == "wait bake" && loading()) {
                const SessionLoader::Progress p = loader->progress();
                if (controls.reload || !p.latest || p.passes_done == 0) break;
            }
            ++step;
            const std::string verb = command.substr(0, command.find(' '));
            const std::string arg = command.substr(command.find(' ') + 1);
            log("script: " + command);
            if (verb == "frames") {
                frames_left = std::stoi(arg);
                // "frames N; screenshot FILE" saves the last of those N frames.
                if (step < o.script.size() && o.script[step].rfind("screenshot ", 0) == 0)
                    screenshot = o.script[step++].substr(11);
            }
            else if (verb == "screenshot") screenshot = arg;
            else if (verb == "model") controls.model = arg, controls.reload = true;
            else if (verb == "env") controls.env = arg, controls.reload = true;
            else if (verb == "preset") controls.preset = arg, controls.reload = true;
            else if (verb == "view") controls.view = *parse_view(arg);
            else if (verb == "tonemap") controls.display.tonemap = *parse_tonemap(arg);
            else if (verb == "exposure") controls.display.exposure = float(std::stod(arg));
            else if (verb == "skybox") controls.skybox = arg == "on";
            else if (verb == "material") {
                float v[6] = {1, 1, 1, 0, 0.5f, 1};
                char textures[8] = "on";
                std::sscanf(arg.c_str(), "%f,%f,%f,%f,%f,%f,%7s", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], textures);
                controls.override_material = true;
                controls.albedo = glm::vec3(v[0], v[1], v[2]);
                controls.metallic = v[3];
                controls.roughness = v[4];
                controls.occlusion = v[5];
                const bool on = std::string(textures) != "off";
                controls.albedo_texture = controls.metal_rough_texture = controls.occlusion_texture = on;
                controls.material_changed = true;
            }
            else if (verb == "size") {
                unsigned w = 0, h = 0;
                std::sscanf(arg.c_str(), "%ux%u", &w, &h);
                glfwSetWindowSize(window, int(w), int(h));
            }
        }
        if (scripted && frames_left == 0 && screenshot.empty() && step >= o.script.size()) break;
        glfwPollEvents();
        if (controls.reload) {
            controls.reload = false;
            const std::string what = controls.model + " under " + controls.env;
            const std::string superseded = loader->request(job_for(base, controls), what);
            if (!superseded.empty()) log("cancelling the load of " + superseded + ": superseded by " + what);
            log("loading " + what + " in the background");
            load_watch = LoadWatch{glfwGetTime()};
            clock.start_span();
        }
        for (const std::string& line : loader->take_lines()) log(line);
        if (auto finished = loader->take_finished()) {
            // Between frames, after the last one's fence: nothing still uses the old session.
            char timing[200];
            std::snprintf(timing, sizeof timing,
                          " after %.0f ms: %d frames drawn meanwhile (%d while its bake passes ran), longest frame %.1f ms",
                          1000 * (glfwGetTime() - load_watch.started), load_watch.frames,
                          load_watch.frames_in_passes, clock.span_longest_ms());
            if (finished->session) {
                session = std::move(*finished->session);
                session_frame = 0;
                show_session(*session, controls);
                camera.home = session->camera();
                // The same model keeps the user's view; another is framed.
                if (controls.model != session_model) camera.view = camera.home;
                session_model = controls.model;
                log("swapped in " + finished->what + timing);
                show_title();
            } else {
                controls.status = "error: " + finished->session.error().message + " (the previous scene stays)";
                log(controls.status);
                log("gave up loading " + finished->what + timing);
                load_failed = true;
            }
        }
        if (watch.changed(glfwGetTime())) {
            // Hot reload between frames: nothing recorded is pending after the last fence.
            auto reloaded = session->reload_shaders();
            if (reloaded) reloaded = programs.reload();
            if (reloaded) {
                controls.status = "shaders reloaded (" + std::to_string(*reloaded) + " pipelines rebuilt)";
                log(controls.status);
            } else {
                controls.status = "shader error, the last good pipelines keep running:\n" + reloaded.error().message;
                log(controls.status);
            }
        }
        if (controls.material_changed) {
            controls.material_changed = false;
            // Between frames: the last frame's fence was waited for.
            Status changed = controls.override_material
                                 ? session->override_materials(RenderSession::MaterialFactors{
                                       controls.albedo, controls.metallic, controls.roughness, controls.occlusion,
                                       controls.albedo_texture, controls.metal_rough_texture,
                                       controls.occlusion_texture})
                                 : session->override_materials(std::nullopt);
            if (!changed) {
                controls.status = "materials not changed: " + changed.error().message;
                log(controls.status);
            }
        }
        const double now = glfwGetTime();
        if (!ui->wants_mouse() && !ui->wants_keyboard()) camera.update(window, now - last);
        last = now;
        if (!ui->wants_keyboard() && glfwGetKey(window, GLFW_KEY_F12) == GLFW_PRESS && screenshot.empty())
            screenshot = "facet-viewer-" + std::to_string(frame) + ".png";
        glfwGetFramebufferSize(window, &fb_w, &fb_h);
        if (fb_w == 0 || fb_h == 0) continue;  // minimised
        uint32_t index = 0;
        VkResult acquired = vkAcquireNextImageKHR(context.device(), swapchain->handle(), UINT64_MAX, sync.acquired,
                                                  VK_NULL_HANDLE, &index);
        VkExtent2D extent = swapchain->extent();
        if (acquired == VK_ERROR_OUT_OF_DATE_KHR || uint32_t(fb_w) != extent.width || uint32_t(fb_h) != extent.height) {
            // A resize: the swapchain (and any image acquired from it) is replaced. The
            // queue's lock, since a load may be submitting on its worker.
            {
                auto queue = context.lock_queue();
                check_vk(vkQueueWaitIdle(context.queue()), "vkQueueWaitIdle");
            }
            if (Status st = swapchain->recreate(uint32_t(fb_w), uint32_t(fb_h)); !st)
                throw std::runtime_error(st.error().message);
            ui->rebuild(*swapchain);
            vkDestroySemaphore(context.device(), sync.acquired, nullptr);
            VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
            check_vk(vkCreateSemaphore(context.device(), &semaphore, nullptr, &sync.acquired), "vkCreateSemaphore");
            continue;
        }
        if (acquired != VK_SUCCESS && acquired != VK_SUBOPTIMAL_KHR)
            throw std::runtime_error(std::string("vkAcquireNextImageKHR: ") + vk_result_name(acquired));

        ui->begin_frame();
        controls.loading.reset();
        if (loader->pending()) {
            const SessionLoader::Progress p = loader->progress();
            controls.loading = LoadShown{p.what, p.last_line, p.passes_done, p.passes_total};
        }
        draw_panels(controls);
        FrameSettings& settings = session->frame_settings();
        settings.camera = camera.view;
        settings.width = extent.width;
        settings.height = extent.height;
        settings.display = controls.display;
        settings.skybox = controls.skybox;
        settings.lights = controls.lights;
        settings.views.clear();
        if (controls.view != View::final_color) settings.views = {controls.view};
        const AllocationCounts frame_begin = Allocator::made_on_this_thread();
        RenderGraph graph;
        auto images = session->add_frame_passes(graph);
        if (!images) throw std::runtime_error(images.error().message);
        ImageHandle shown = images->ldr;
        if (controls.view != View::final_color) {
            // A component view, shown through the same display transform.
            ImageDesc desc;
            desc.format = VK_FORMAT_R8G8B8A8_UNORM;
            desc.width = extent.width;
            desc.height = extent.height;
            auto mapped = add_tonemap_pass(graph, programs, nearest, images->views.at(0).second,
                                           graph.create_image("view display", desc), controls.display);
            if (!mapped) throw std::runtime_error(mapped.error().message);
            shown = *mapped;
        }
        ImageDesc swap_desc;
        swap_desc.format = swapchain->format();
        swap_desc.width = extent.width;
        swap_desc.height = extent.height;
        // The semaphore wait covers every stage, so the graph may start from any of them.
        ImageHandle target = graph.import_image(
            "swapchain image", {swapchain->images()[index], swap_desc,
                                {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE},
                                {VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                 VK_ACCESS_2_NONE}});
        graph.add_transfer_pass("copy to the window", [&](PassBuilder& b) {
            b.copy_from(shown);
            target = b.copy_to(target);
        }, [shown, target, extent](PassContext& pc) {
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            blit.srcOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
            blit.dstSubresource = blit.srcSubresource;
            blit.dstOffsets[1] = blit.srcOffsets[1];
            vkCmdBlitImage(pc.cmd(), pc.image(shown), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pc.image(target),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        });
        target = ui->add_pass(graph, target, index);
        // A screenshot shows the scene the script asked for: it waits for a load (frames go on).
        const bool hold_for_screenshot = !screenshot.empty() && frames_left <= 1 && loading();
        const bool capture = !screenshot.empty() && frames_left <= 1 && !hold_for_screenshot;
        const ResourceState readable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                     VK_ACCESS_2_TRANSFER_READ_BIT};
        if (capture) {
            graph.export_image(shown, readable);
            graph.export_image(images->hdr, readable);
        }
        const auto frame_start = std::chrono::steady_clock::now();
        CompiledGraph compiled = graph.compile();
        check_vk(vkResetCommandBuffer(sync.cmd, 0), "vkResetCommandBuffer");
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        check_vk(vkBeginCommandBuffer(sync.cmd, &begin), "vkBeginCommandBuffer");
        auto recorded = executor.record(compiled, sync.cmd);
        if (!recorded) throw std::runtime_error(recorded.error().message);
        GraphRun& run = **recorded;
        check_vk(vkEndCommandBuffer(sync.cmd), "vkEndCommandBuffer");
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
        {
            auto queue = context.lock_queue();  // a load may be submitting on its worker
            check_vk(vkQueueSubmit2(context.queue(), 1, &submit, sync.done), "vkQueueSubmit2");
        }
        VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        present.waitSemaphoreCount = 1;
        present.pWaitSemaphores = &sync.rendered;
        present.swapchainCount = 1;
        const VkSwapchainKHR handle = swapchain->handle();
        present.pSwapchains = &handle;
        present.pImageIndices = &index;
        VkResult presented;
        {
            auto queue = context.lock_queue();
            presented = vkQueuePresentKHR(context.queue(), &present);
        }
        // One frame in flight: the graph's resources live until its work is done.
        check_vk(vkWaitForFences(context.device(), 1, &sync.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        check_vk(vkResetFences(context.device(), 1, &sync.done), "vkResetFences");
        clock.frame_done();
        if (loader->pending()) {
            ++load_watch.frames;
            const SessionLoader::Progress p = loader->progress();
            if (p.passes_done > 0 && p.passes_done < p.passes_total) ++load_watch.frames_in_passes;
        }
        if (presented != VK_SUCCESS && presented != VK_SUBOPTIMAL_KHR && presented != VK_ERROR_OUT_OF_DATE_KHR)
            throw std::runtime_error(std::string("vkQueuePresentKHR: ") + vk_result_name(presented));
        if (session_frame > 0 && !capture) {
            const AllocationCounts frame_end = Allocator::made_on_this_thread();
            later_allocations += frame_end.allocations_made - frame_begin.allocations_made;
            later_images += frame_end.images_bound - frame_begin.images_bound;
        }
        controls.frame_passes = run.timings();
        controls.frame_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame_start).count();
        if (capture) {
            auto ldr_bytes = read_image(context, *run.transient_image(shown), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            auto hdr_bytes = read_image(context, *run.transient_image(images->hdr), 0, 0,
                                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            if (!ldr_bytes) throw std::runtime_error(ldr_bytes.error().message);
            if (!hdr_bytes) throw std::runtime_error(hdr_bytes.error().message);
            std::vector<float> hdr(hdr_bytes->size() / 4);
            std::memcpy(hdr.data(), hdr_bytes->data(), hdr.size() * 4);
            if (Status st = save(screenshot, extent.width, extent.height, *ldr_bytes, hdr, settings.display.exposure); !st)
                throw std::runtime_error(st.error().message);
            log("saved " + screenshot);
            screenshot.clear();
        }
        // Scripts and tests wait for this: every pipeline of the frame is built by now.
        if (frame == 0) log("first frame shown");
        if (frames_left > 0 && !hold_for_screenshot) --frames_left;
        ++frame;
        ++session_frame;
    }
    if (loader->pending()) log("stopping the load of " + loader->progress().what + ": the window closes");
    loader->stop();
    for (const std::string& line : loader->take_lines()) log(line);
    loader.reset();
    vkDeviceWaitIdle(context.device());  // no other thread uses the device now
    executor.release();
    ui.reset();
    swapchain.reset();
    log("rendered " + std::to_string(frame) + " frames (after the first: " + std::to_string(later_allocations) +
        " device allocations, " + std::to_string(later_images) + " images created)");
    log(clock.summary());
    if (!o.script.empty() && load_failed && exit_status == 0) {
        log("a model or environment the script asked for did not load (above): exit status 1");
        exit_status = 1;
    }
    return exit_status;
}

}  // namespace

int main(int argc, char** argv) {
    return facet::run_interruptible(program, [&] { return parse_viewer_options(argc, argv); }, run);
}
