#pragma once
// The Vulkan 1.3 device Facet runs on: its own headless one (a discrete GPU when there
// is one, else lavapipe), or one a host engine owns and hands in.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>

namespace facet {

class Allocator;

struct ContextOptions {
    // Khronos validation layer + debug-utils messenger. Default: on in Debug builds or
    // when FACET_VALIDATION=1, off otherwise (FACET_VALIDATION=0 forces off).
    bool validation = default_validation();
    // GPU-assisted synchronization validation (only with validation).
    bool sync_validation = true;
    // Device by name substring or index; empty: FACET_DEVICE, else a discrete GPU,
    // else the first CPU device (lavapipe).
    std::string device;
    std::string app_name = "facet";
    // More extensions, e.g. a window system's surface extensions (instance) and
    // VK_KHR_swapchain (device); a missing one is an error naming it.
    std::vector<std::string> instance_extensions;
    std::vector<std::string> device_extensions;

    static bool default_validation();
};

// Vulkan objects owned by a host engine. Facet creates and destroys only its own
// objects on them. The device must have Vulkan 1.3 with synchronization2 and
// dynamic rendering enabled, and VK_KHR_push_descriptor.
struct HostVulkan {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    // True when the host enabled VK_EXT_debug_utils on the instance (object names).
    bool debug_utils = false;
};

// Thread safety: a Context may be used from several threads at once for creating and
// destroying resources, samplers and pipelines (Image, Buffer, Pipeline, ProgramCache
// per thread), allocating device memory and submitting (submit_and_wait, GraphRun,
// uploads and readbacks), which serialise on the one queue. Objects built on it (a
// RenderGraph, GraphRun, ProgramCache, ShaderCompiler, RenderSession) belong to one
// thread at a time. Several contexts may live in one process; fault injection and the
// process-wide validation count are shared by them.
class Context {
public:
    static Result<std::unique_ptr<Context>> create(const ContextOptions& options = {});
    static Result<std::unique_ptr<Context>> adopt(const HostVulkan& host,
                                                  const ContextOptions& options = {});
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
    // throws VulkanError(VK_ERROR_DEVICE_LOST); destroying objects stays valid.
    bool device_lost() const { return device_lost_.load(); }

    // Debug name for any Vulkan object (no-op without VK_EXT_debug_utils).
    void set_name(VkObjectType type, uint64_t handle, const std::string& name) const;
    template <class T>
    void set_name(T handle, VkObjectType type, const std::string& name) const {
        set_name(type, reinterpret_cast<uint64_t>(handle), name);
    }

    // Records with `record` into a one-time command buffer, submits, waits.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record);
    // Submits an already recorded command buffer and waits for it.
    void submit_and_wait(VkCommandBuffer cmd);

    PFN_vkCmdPushDescriptorSetKHR cmd_push_descriptor_set = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT cmd_begin_label = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT cmd_end_label = nullptr;

private:
    Context() = default;
    void finish_setup();
    void submit_locked(VkCommandBuffer cmd);
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
    VkPhysicalDeviceProperties properties_{};
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
    std::unique_ptr<Allocator> allocator_;
    std::atomic<uint32_t> validation_messages_{0};
    std::atomic<bool> device_lost_{false};
    std::mutex submit_mutex_;  // one-shot pool and fence are shared
};

}  // namespace facet
