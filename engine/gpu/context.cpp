#include <facet/gpu/context.h>

#include <dlfcn.h>
#include <link.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <facet/core/log.h>
#include "core/guarded.h"
#include "gpu/device_selection.h"
#include "gpu/fault_injection.h"
#include <facet/gpu/memory.h>
#include <facet/gpu/requirements.h>

namespace facet {

namespace {

constexpr const char* validation_layer = "VK_LAYER_KHRONOS_validation";

std::atomic<uint32_t> g_process_validation_messages{0};

#if defined(__SANITIZE_ADDRESS__)
#define FACET_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FACET_ASAN 1
#endif
#endif

#ifdef FACET_ASAN
// The Vulkan loader unloads the driver and the layers at vkDestroyInstance; LeakSanitizer
// then cannot name the library an allocation came from at exit ("<unknown module>"),
// and its suppressions by library (tests/sanitizers/lsan.supp) stop working. Pinning
// them keeps every leak report attributable. Sanitizer builds only.
void pin_vulkan_libraries() {
    std::vector<std::string> paths;
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void* out) {
            const std::string name = info->dlpi_name ? info->dlpi_name : "";
            if (name.find("vulkan_") != std::string::npos || name.find("VkLayer") != std::string::npos ||
                name.find("libLLVM") != std::string::npos)
                static_cast<std::vector<std::string>*>(out)->push_back(name);
            return 0;
        },
        &paths);
    for (const std::string& path : paths) dlopen(path.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
}
#endif

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool has_instance_extension(const char* layer, const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

}  // namespace

uint32_t Context::process_validation_message_count() { return g_process_validation_messages.load(); }

bool ContextOptions::default_validation() {
#ifdef NDEBUG
    return false;
#else
    return true;
#endif
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::on_debug_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* context = static_cast<Context*>(user);
    const bool is_error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    context->validation_messages_.fetch_add(1);
    g_process_validation_messages.fetch_add(1);
    log(is_error ? LogLevel::error : LogLevel::warning,
        std::string("validation: ") + (data->pMessage ? data->pMessage : "(no message)"));
    return VK_FALSE;
}

// Options every context takes, whoever owns the device.
static void apply_common_options(const ContextOptions& options) {
    if (options.inject_fault) {
        inject_fault(options.inject_fault->site, options.inject_fault->skip);
        log(LogLevel::warning, "fault injection is armed: a Vulkan call will fail on purpose");
    }
}

namespace {

// ContextOptions::keep_freed_memory_on_cpu_device: lavapipe's queue thread allocates its
// binned scene every frame and frees it after; glibc hands a thread arena's free top back
// (MADV_DONTNEED) above the trim threshold, and the next frame faults every page in again.
bool keep_freed_memory() {
#ifdef __GLIBC__
    const bool trim = mallopt(M_TRIM_THRESHOLD, 256 << 20) == 1;
    const bool mmap = mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1;  // glibc's largest on 64-bit
    return trim && mmap;
#else
    return false;
#endif
}

}  // namespace

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
    if (options.fence_timeout_ms == 0) return Error{"ContextOptions::fence_timeout_ms must be at least 1 ms"};
    apply_common_options(options);
    std::unique_ptr<Context> context(new Context());
    Context& c = *context;
    c.fence_timeout_ms_ = options.fence_timeout_ms;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    const bool validation = options.validation;
    if (validation) {
        if (!has_layer(validation_layer))
            return Error{std::string(validation_layer) +
                             " is not installed (Debian package vulkan-validationlayers)",
                         VK_ERROR_LAYER_NOT_PRESENT};
        layers.push_back(validation_layer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    } else if (has_instance_extension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);  // object names for tools
    }
    const bool validation_features =
        validation && options.sync_validation &&
        has_instance_extension(validation_layer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    if (validation_features) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    for (const std::string& e : options.instance_extensions) {
        if (!has_instance_extension(nullptr, e.c_str()))
            return Error{"the Vulkan instance extension " + e + " is not available", VK_ERROR_EXTENSION_NOT_PRESENT};
        extensions.push_back(e.c_str());
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = options.app_name.c_str();
    app.pEngineName = "facet";
    app.apiVersion = device_requirements().api_version;

    const VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;

    VkDebugUtilsMessengerCreateInfoEXT messenger_info{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = &Context::on_debug_message;
    messenger_info.pUserData = &c;
    // Chained into instance creation too, so instance creation itself is validated.
    if (validation_features) messenger_info.pNext = &features;

    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &app;
    instance_info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    instance_info.ppEnabledLayerNames = layers.data();
    instance_info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    instance_info.ppEnabledExtensionNames = extensions.data();
    if (validation) instance_info.pNext = &messenger_info;
    if (VkResult r = vkCreateInstance(&instance_info, nullptr, &c.instance_); r != VK_SUCCESS)
        return Error{std::string("vkCreateInstance failed: ") + vk_result_name(r), r};
#ifdef FACET_ASAN
    pin_vulkan_libraries();
#endif

    if (validation) {
        messenger_info.pNext = nullptr;
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(c.instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (VkResult r = create_messenger(c.instance_, &messenger_info, nullptr, &c.messenger_);
            r != VK_SUCCESS)
            return Error{std::string("cannot create the debug messenger: ") + vk_result_name(r), r};
    }

    auto picked = pick_device(c.instance_, options.device);
    if (!picked) return picked.error();
    c.physical_device_ = picked.value();
    auto family = find_queue_family(c.physical_device_);
    if (!family) return Error{"the device has no graphics+compute queue"};
    c.queue_family_ = *family;

    // Exactly what a host is asked for (device_requirements), plus what the device
    // offers of the optional features.
    DeviceRequirements needs = device_requirements();
    needs.add_supported_optional_features(c.physical_device_);

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = c.queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    std::vector<const char*> device_extensions = needs.device_extensions;
    for (const std::string& e : options.device_extensions) {
        if (!has_device_extension(c.physical_device_, e.c_str()))
            return Error{"the Vulkan device extension " + e + " is not available on " + c.device_name(),
                         VK_ERROR_EXTENSION_NOT_PRESENT};
        device_extensions.push_back(e.c_str());
    }
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.pNext = needs.chain();
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.enabledExtensionCount = static_cast<uint32_t>(device_extensions.size());
    device_info.ppEnabledExtensionNames = device_extensions.data();
    if (VkResult r = vkCreateDevice(c.physical_device_, &device_info, nullptr, &c.device_);
        r != VK_SUCCESS)
        return Error{std::string("vkCreateDevice failed: ") + vk_result_name(r), r};
    vkGetDeviceQueue(c.device_, c.queue_family_, 0, &c.queue_);
    c.owns_device_ = true;
    c.set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(c.instance_, "vkSetDebugUtilsObjectNameEXT"));
    if (std::find_if(extensions.begin(), extensions.end(), [](const char* e) {
            return std::strcmp(e, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) == 0;
        }) == extensions.end())
        c.set_object_name_ = nullptr;
    try {
        c.finish_setup();
    } catch (const VulkanError& e) {
        return Error{e.what(), e.result()};
    }
    if (options.keep_freed_memory_on_cpu_device && c.properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
        c.keeps_freed_memory_ = keep_freed_memory();
    return context;
}

Result<std::unique_ptr<Context>> Context::adopt(const HostVulkan& host, const ContextOptions& options) {
    if (!host.instance || !host.physical_device || !host.device || !host.queue)
        return Error{"HostVulkan: instance, physical device, device and queue are all required"};
    if (options.fence_timeout_ms == 0) return Error{"ContextOptions::fence_timeout_ms must be at least 1 ms"};
    EnabledDevice enabled;
    enabled.api_version = host.api_version;
    enabled.physical_device = host.physical_device;
    enabled.extensions = host.device_extensions;
    enabled.features = host.enabled_features;
    enabled.core_features = host.enabled_core_features;
    if (std::vector<std::string> lacks = unmet_device_requirements(device_requirements(), enabled); !lacks.empty())
        return Error{"the host's device lacks: " + join(lacks) +
                         " (facet::device_requirements() lists what to enable; HostVulkan states what was)",
                     VK_ERROR_FEATURE_NOT_PRESENT};
    apply_common_options(options);
#ifdef FACET_ASAN
    pin_vulkan_libraries();
#endif
    std::unique_ptr<Context> context(new Context());
    Context& c = *context;
    c.instance_ = host.instance;
    c.physical_device_ = host.physical_device;
    c.device_ = host.device;
    c.queue_ = host.queue;
    c.queue_family_ = host.queue_family;
    c.owns_device_ = false;
    c.fence_timeout_ms_ = options.fence_timeout_ms;
    c.submit_hook_ = host.submit;
    if (host.debug_utils)
        c.set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(c.instance_, "vkSetDebugUtilsObjectNameEXT"));
    try {
        c.finish_setup();
    } catch (const VulkanError& e) {
        return Error{e.what(), e.result()};
    }
    if (!c.cmd_push_descriptor_set)
        return Error{"the host's device does not enable VK_KHR_push_descriptor, which Facet needs"};
    return context;
}

void Context::finish_setup() {
    vkGetPhysicalDeviceProperties(physical_device_, &properties_);
    cmd_push_descriptor_set = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
    if (set_object_name_) {
        cmd_begin_label = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
        cmd_end_label = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
    }
    allocator_ = std::make_unique<Allocator>(physical_device_, device_);

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT |
                      VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    vk_check(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_), "vkCreateCommandPool");
    set_name(command_pool_, VK_OBJECT_TYPE_COMMAND_POOL, "facet one-shot commands");
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vk_check(vkCreateFence(device_, &fence_info, nullptr, &fence_), "vkCreateFence");
    set_name(fence_, VK_OBJECT_TYPE_FENCE, "facet submit fence");
    if (owns_device_) {
        set_name(device_, VK_OBJECT_TYPE_DEVICE, "facet device");
        set_name(queue_, VK_OBJECT_TYPE_QUEUE, "facet queue");
    }
}

Context::~Context() {
    // Every submission of Facet's was waited for before submit_and_wait returned, so
    // nothing of Facet's is pending here (a timed-out one aside, which is never waited
    // for again: the GPU did not answer within the limit once already). A host's device
    // and queue are never waited on: the host may be using them. Facet's own device is
    // drained, since a program may have submitted its own work on it (the viewer).
    if (owns_device_ && device_ && !timed_out_) vkDeviceWaitIdle(device_);
    allocator_.reset();
    if (fence_) vkDestroyFence(device_, fence_, nullptr);
    if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
    if (!owns_device_) return;
    if (device_) vkDestroyDevice(device_, nullptr);
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

void Context::set_name(VkObjectType type, uint64_t handle, const std::string& name) const {
    if (!set_object_name_ || handle == 0) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    set_object_name_(device_, &info);
}

Status Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record, const char* what) {
    return guarded([&] { submit_recorded(record, what); });
}

Status Context::submit_and_wait(VkCommandBuffer cmd, const char* what) {
    return guarded([&] {
        std::lock_guard lock(submit_mutex_);
        submit_locked(cmd, what);
    });
}

void Context::submit_recorded(const std::function<void(VkCommandBuffer)>& record, const char* what) {
    std::lock_guard lock(submit_mutex_);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = command_pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    vk_check(vkAllocateCommandBuffers(device_, &alloc, &cmd), "vkAllocateCommandBuffers");
    set_name(cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, "facet one-shot");
    struct Free {
        const Context& context;
        VkCommandBuffer cmd;
        // A command buffer whose wait timed out may still be executing: it is left to
        // the pool, freed with it.
        ~Free() {
            if (!context.timed_out_) vkFreeCommandBuffers(context.device_, context.command_pool_, 1, &cmd);
        }
    } free_later{*this, cmd};
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    record(cmd);
    vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    submit_locked(cmd, what);
}

void Context::submit_locked(VkCommandBuffer cmd, const char* what) {
    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    // After a loss every later submission fails the same way, without touching the
    // device again (vkQueueSubmit2's valid usage no longer holds for a lost device).
    if (device_lost_) throw VulkanError(VK_ERROR_DEVICE_LOST, "vkQueueSubmit2 (the device was lost earlier)");
    // After a timeout the fence may still be pending, so it cannot be reset.
    if (timed_out_)
        throw VulkanError(VK_TIMEOUT, "vkQueueSubmit2 (an earlier wait for the GPU timed out; this context "
                                      "takes no more work)");
    vk_check(vkResetFences(device_, 1, &fence_), "vkResetFences");
    VkResult r = take_injected_fault(FaultSite::submit);
    // An injected hang: the submission is dropped, so the fence never signals.
    const bool hang = r == VK_SUCCESS && take_injected_fault(FaultSite::hang) != VK_SUCCESS;
    if (r == VK_SUCCESS && !hang) {
        std::lock_guard queue_lock(queue_mutex_);
        r = submit_hook_ ? submit_hook_(queue_, submit, fence_) : vkQueueSubmit2(queue_, 1, &submit, fence_);
    }
    if (r == VK_ERROR_DEVICE_LOST) device_lost_ = true;
    vk_check(r, submit_hook_ ? "vkQueueSubmit2 (through the host's submit hook)" : "vkQueueSubmit2");
    // Milliseconds to nanoseconds, saturating: a limit beyond 584 years waits forever.
    const uint64_t timeout_ns =
        fence_timeout_ms_ > UINT64_MAX / 1'000'000 ? UINT64_MAX : fence_timeout_ms_ * 1'000'000;
    r = vkWaitForFences(device_, 1, &fence_, VK_TRUE, timeout_ns);
    if (r == VK_TIMEOUT) {
        timed_out_ = true;
        throw VulkanError(VK_TIMEOUT, "timed out after " + std::to_string(fence_timeout_ms_) +
                                          " ms waiting for the GPU to finish " + what + " (vkWaitForFences)");
    }
    if (r == VK_ERROR_DEVICE_LOST) device_lost_ = true;
    vk_check(r, "vkWaitForFences");
}

}  // namespace facet
