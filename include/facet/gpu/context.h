#pragma once
// The Vulkan 1.3 device Facet runs on: its own headless one (a discrete GPU when there
// is one, else lavapipe), or one a host engine owns and hands in.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/gpu/faults.h>

namespace facet {

class Allocator;

struct ContextOptions {
    // Khronos validation layer + debug-utils messenger. Default: on when the library is a
    // Debug build, off otherwise. (The library reads no environment variable; the
    // programs map FACET_VALIDATION onto this.)
    bool validation = default_validation();
    // GPU-assisted synchronization validation (only with validation).
    bool sync_validation = true;
    // Context::create only: the device by index or name substring (an error lists the
    // devices when none matches); empty: a discrete GPU, else integrated, virtual, and
    // last a CPU device (lavapipe).
    std::string device;
    std::string app_name = "facet";
    // Context::create only: more extensions, e.g. a window system's surface extensions
    // (instance) and VK_KHR_swapchain (device); a missing one is an error naming it.
    std::vector<std::string> instance_extensions;
    std::vector<std::string> device_extensions;
    // The longest Facet waits for the GPU to finish one submission, in milliseconds.
    // A wait that runs out returns Error{"timed out after N ms waiting for ...",
    // VK_TIMEOUT} instead of hanging, and the context takes no more work (timed_out()).
    // Generous by default: a large bake on a slow device takes seconds, not a minute.
    uint64_t fence_timeout_ms = 60'000;
    // Testing error paths: arms a fault (facet/gpu/faults.h) when the context is created
    // or adopted. The armed fault is process-wide: it fires in whichever context reaches
    // the site first.
    std::optional<FaultInjection> inject_fault;
    // Context::create only, on a CPU device (lavapipe), where the "GPU" is this process's
    // own threads: raise glibc's malloc trim threshold to 256 MiB and its mmap threshold to
    // 32 MiB (mallopt, process-wide), so that the driver's per-frame allocations (about
    // 30 MiB when it bins a scene of many small triangles) reuse freed memory instead of
    // returning it to the kernel and faulting it in again every frame: builtin:spheres'
    // forward pass at 1280x720 took 112 ms instead of 41 (README, Speed). The price: up
    // to that much freed memory stays resident per malloc arena. False leaves the process's
    // malloc settings alone; Context::adopt never changes them.
    bool keep_freed_memory_on_cpu_device = true;

    static bool default_validation();
};

// Vulkan objects owned by a host engine. Facet creates and destroys only its own
// objects on them, waits only on its own fences (never vkDeviceWaitIdle or
// vkQueueWaitIdle), and submits through `submit` when the host gives one.
// The device must meet device_requirements() (facet/gpu/requirements.h); since Vulkan
// cannot be asked what a VkDevice enabled, the host states it here and Context::adopt
// names every requirement that is missing.
struct HostVulkan {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    // True when the host enabled VK_EXT_debug_utils on the instance (object names).
    bool debug_utils = false;
    // The instance's VkApplicationInfo::apiVersion.
    uint32_t api_version = 0;
    // VkDeviceCreateInfo::ppEnabledExtensionNames.
    std::vector<std::string> device_extensions;
    // VkDeviceCreateInfo::pNext (the chain holding VkPhysicalDeviceFeatures2 and the
    // Vulkan 1.x feature structs) and pEnabledFeatures; read during adopt only.
    const void* enabled_features = nullptr;
    const VkPhysicalDeviceFeatures* enabled_core_features = nullptr;
    // Every submission of Facet's goes through this when set (one VkSubmitInfo2 and the
    // fence Facet then waits on), so the host can hold its own lock on the queue, which
    // Vulkan requires to be externally synchronised. Called from whichever thread
    // submits (Context::submit_and_wait and what uses it), one call at a time per
    // context. Empty: Facet calls vkQueueSubmit2 itself.
    std::function<VkResult(VkQueue, const VkSubmitInfo2&, VkFence)> submit;
};

// Thread safety: a Context may be used from several threads at once for creating and
// destroying resources, samplers and pipelines (Image, Buffer, Pipeline, ProgramCache
// per thread), allocating device memory and submitting (submit_and_wait, GraphRun,
// uploads and readbacks), which serialise on the one queue. Objects built on it (a
// RenderGraph, GraphRun, ProgramCache, ShaderCompiler, RenderSession) belong to one
// thread at a time. Several contexts may live in one process; fault injection and the
// process-wide validation count are shared by them. Destroy a Context (and everything
// built on it) only after every other thread is done with it.
//
// Errors: create and adopt return an Error naming what is wrong. Work submitted on the
// device (submit_and_wait and everything built on it) returns an Error carrying the
// VkResult when the device fails (out of memory, device lost, a wait timed out); so do
// the create() factories of objects built on a Context. No exception crosses the public
// API; UsageError marks programmer misuse (documented where it applies).
class Context {
public:
    // A device of Facet's own: instance (with validation when asked), device, queue.
    static Result<std::unique_ptr<Context>> create(const ContextOptions& options = {});
    // The host's device: checked against device_requirements(); the Error names each
    // requirement the host did not enable. Of `options`, validation, device,
    // instance_extensions and device_extensions do not apply (the host made those choices).
    static Result<std::unique_ptr<Context>> adopt(const HostVulkan& host,
                                                  const ContextOptions& options = {});
    // On an adopted device: destroys Facet's objects only, without waiting for the device
    // (Facet's own submissions have all been waited for). On its own device: waits for
    // the device (unless a wait timed out), then destroys it.
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_device_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    std::string device_name() const { return properties_.deviceName; }
    bool owns_device() const { return owns_device_; }
    bool validation_enabled() const { return messenger_ != VK_NULL_HANDLE; }
    // Nanoseconds per timestamp tick.
    double timestamp_period_ns() const { return properties_.limits.timestampPeriod; }

    Allocator& allocator() { return *allocator_; }

    // Validation messages (warnings and errors) received since creation.
    uint32_t validation_message_count() const { return validation_messages_.load(); }
    // Validation messages received by every context of this process, including those
    // reported while a context was being destroyed (objects left undestroyed).
    static uint32_t process_validation_message_count();
    // True once a submission reported VK_ERROR_DEVICE_LOST: every later submission
    // returns an Error with VK_ERROR_DEVICE_LOST; destroying objects stays valid.
    bool device_lost() const { return device_lost_.load(); }
    // True once a wait for the GPU ran past ContextOptions::fence_timeout_ms: every later
    // submission returns an Error with VK_TIMEOUT at once; destroying objects stays valid.
    bool timed_out() const { return timed_out_.load(); }
    uint64_t fence_timeout_ms() const { return fence_timeout_ms_; }
    // Whether creating this context set the malloc thresholds above
    // (ContextOptions::keep_freed_memory_on_cpu_device on a CPU device, glibc accepting).
    bool keeps_freed_memory() const { return keeps_freed_memory_; }

    // Debug name for any Vulkan object (no-op without VK_EXT_debug_utils).
    void set_name(VkObjectType type, uint64_t handle, const std::string& name) const;
    template <class T>
    void set_name(T handle, VkObjectType type, const std::string& name) const {
        set_name(type, reinterpret_cast<uint64_t>(handle), name);
    }

    // Records with `record` into a one-time command buffer, submits (through
    // HostVulkan::submit when given), waits on Facet's fence for at most
    // fence_timeout_ms. `what` names the work in a timeout's message. Returns an Error on
    // failure (VK_TIMEOUT: "timed out after N ms waiting for <what>"; VK_ERROR_DEVICE_LOST;
    // out of memory), also when `record` itself fails inside the engine (e.g. a view it
    // creates); a UsageError `record` throws passes through.
    Status submit_and_wait(const std::function<void(VkCommandBuffer)>& record,
                           const char* what = "a one-shot submission");
    // Submits an already recorded command buffer and waits for it, as above.
    Status submit_and_wait(VkCommandBuffer cmd, const char* what = "a submitted command buffer");

    // For a program that submits or presents on queue() itself while Facet may submit
    // from another thread (a viewer baking on a worker): Vulkan requires host access to a
    // queue to be externally synchronised, and this is the lock Facet's own submissions
    // hold around vkQueueSubmit2 (only around the call: their fence waits run unlocked, so
    // a long bake pass on another thread does not block the holder). Hold it for each
    // vkQueueSubmit2, vkQueuePresentKHR and vkQueueWaitIdle on queue(), and for
    // vkDeviceWaitIdle. Not for an adopted device: the host's own submit hook serialises.
    [[nodiscard]] std::unique_lock<std::mutex> lock_queue() { return std::unique_lock(queue_mutex_); }

    PFN_vkCmdPushDescriptorSetKHR cmd_push_descriptor_set = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT cmd_begin_label = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT cmd_end_label = nullptr;

private:
    Context() = default;
    void finish_setup();
    // The throwing implementations behind submit_and_wait (which catches).
    void submit_recorded(const std::function<void(VkCommandBuffer)>& record, const char* what);
    void submit_locked(VkCommandBuffer cmd, const char* what);
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    bool owns_device_ = true;
    bool keeps_freed_memory_ = false;
    VkPhysicalDeviceProperties properties_{};
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
    std::unique_ptr<Allocator> allocator_;
    std::atomic<uint32_t> validation_messages_{0};
    std::atomic<bool> device_lost_{false};
    std::atomic<bool> timed_out_{false};
    uint64_t fence_timeout_ms_ = 60'000;
    std::function<VkResult(VkQueue, const VkSubmitInfo2&, VkFence)> submit_hook_;
    std::mutex submit_mutex_;  // one-shot pool and fence are shared (held from recording to the fence)
    std::mutex queue_mutex_;   // the queue itself (held around vkQueueSubmit2 only): lock_queue()
};

}  // namespace facet
