// A host engine owns the Vulkan instance and device and hands them to Facet: Facet must
// run its work on them and destroy only its own objects.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <future>
#include <mutex>
#include <vector>

#include <facet/gpu/context.h>
#include <facet/gpu/resources.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/graph/render_graph.h>
#include <facet/gpu/pipeline.h>
#include <facet/gpu/requirements.h>
#include <facet/shader/compiler.h>
#include "gpu/fault_injection.h"
#include "support/gpu_test.h"

namespace facet {
namespace {

// Two compute passes on the given context: fill a buffer with i*i, then add 7 in place;
// the result is read back and checked.
void run_graph_on(Context& context) {
    ShaderCompiler compiler;
    auto fill = compiler.compile_source(ShaderStage::compute, "fill.comp", R"(#version 460
layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer V { uint v[]; };
void main() { uint i = gl_GlobalInvocationID.x; v[i] = i * i; }
)");
    auto add = compiler.compile_source(ShaderStage::compute, "add.comp", R"(#version 460
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer V { uint v[]; };
void main() { v[gl_GlobalInvocationID.x] += 7u; }
)");
    ASSERT_TRUE(fill && add);
    auto fill_built = Pipeline::compute(context, fill->words, "fill");
    auto add_built = Pipeline::compute(context, add->words, "add");
    ASSERT_TRUE(fill_built && add_built);
    Pipeline fill_pipeline = std::move(fill_built).value(), add_pipeline = std::move(add_built).value();
    const uint32_t count = 1024;
    Buffer result = test::must(Buffer::create(context, count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                              MemoryUsage::readback, "host test result"));

    RenderGraph g;
    ImportedBuffer imported{result.handle(), count * 4, {},
                            {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT}};
    auto values = g.import_buffer("result", imported);
    auto dispatch = [&](const Pipeline& p, BufferHandle h) {
        return [&p, h, count](PassContext& pc) {
            p.bind(pc.cmd());
            const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(h))};
            p.push_descriptors(pc.cmd(), writes);
            vkCmdDispatch(pc.cmd(), group_count(count, p.workgroup_size()[0]), 1, 1);
        };
    };
    BufferHandle before_fill = values;
    g.add_compute_pass("fill", [&](PassBuilder& b) { values = b.write(values); }, dispatch(fill_pipeline, before_fill));
    BufferHandle before_add = values;
    g.add_compute_pass("add", [&](PassBuilder& b) { values = b.write(values, Access::storage_read_write); },
                       dispatch(add_pipeline, before_add));
    CompiledGraph compiled = g.compile();
    ASSERT_EQ(compiled.passes.size(), 2u);
    auto run = test::must(run_graph(context, compiled));
    test::must(result.invalidate());
    const auto* v = static_cast<const uint32_t*>(result.mapped());
    for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(v[i], i * i + 7) << "element " << i;
}

struct HostCounts {
    uint32_t messages = 0;
};

VKAPI_ATTR VkBool32 VKAPI_CALL count_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    ++static_cast<HostCounts*>(user)->messages;
    ADD_FAILURE() << "validation: " << data->pMessage;
    return VK_FALSE;
}

// What the host leaves out of its device, to see adopt name it.
struct HostSetup {
    bool dynamic_rendering = true;
    bool synchronization2 = true;
    bool push_descriptor = true;
};

// The host's own minimal Vulkan set-up, written without Facet's helpers except
// device_requirements(), which it chains into its device as an engine would.
struct HostEngine {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;  // the host's own object, must survive Facet
    HostCounts counts;
    DeviceRequirements needs = device_requirements();  // read by handles(): not moved

    // What Facet is told about the device (features chain: `needs`, alive with this).
    HostVulkan handles() const {
        HostVulkan h{instance, physical, device, queue, family, true};
        h.api_version = VK_API_VERSION_1_3;
        h.device_extensions.assign(needs.device_extensions.begin(), needs.device_extensions.end());
        h.enabled_features = &needs.features;
        return h;
    }

    void create(const HostSetup& setup = {}) {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.apiVersion = VK_API_VERSION_1_3;
        const char* layers[] = {"VK_LAYER_KHRONOS_validation"};
        const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
        VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        messenger_info.messageSeverity =
            VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
        messenger_info.pfnUserCallback = count_message;
        messenger_info.pUserData = &counts;
        VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        info.pApplicationInfo = &app;
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = layers;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = extensions;
        ASSERT_EQ(vkCreateInstance(&info, nullptr, &instance), VK_SUCCESS);
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        ASSERT_EQ(create_messenger(instance, &messenger_info, nullptr, &messenger), VK_SUCCESS);

        uint32_t count = 1;
        VkResult r = vkEnumeratePhysicalDevices(instance, &count, &physical);
        ASSERT_TRUE(r == VK_SUCCESS || r == VK_INCOMPLETE);
        ASSERT_EQ(count, 1u);
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, nullptr);
        std::vector<VkQueueFamilyProperties> props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, props.data());
        while (family < families && !(props[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;
        ASSERT_LT(family, families);

        needs.vulkan13.dynamicRendering = setup.dynamic_rendering;
        needs.vulkan13.synchronization2 = setup.synchronization2;
        if (!setup.push_descriptor) needs.device_extensions.clear();
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue_info.queueFamilyIndex = family;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        device_info.pNext = needs.chain();
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        device_info.enabledExtensionCount = static_cast<uint32_t>(needs.device_extensions.size());
        device_info.ppEnabledExtensionNames = needs.device_extensions.data();
        ASSERT_EQ(vkCreateDevice(physical, &device_info, nullptr, &device), VK_SUCCESS);
        vkGetDeviceQueue(device, family, 0, &queue);
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.queueFamilyIndex = family;
        ASSERT_EQ(vkCreateCommandPool(device, &pool_info, nullptr, &pool), VK_SUCCESS);
    }

    void destroy() {
        if (pool) vkDestroyCommandPool(device, pool, nullptr);
        if (device) vkDestroyDevice(device, nullptr);
        if (messenger) {
            auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
            destroy_messenger(instance, messenger, nullptr);
        }
        if (instance) vkDestroyInstance(instance, nullptr);
    }
};

TEST(HostDevice, FacetRunsOnTheHostsDeviceAndLeavesItAlive) {
    HostEngine host;
    host.create();
    ASSERT_FALSE(testing::Test::HasFatalFailure());
    {
        auto adopted = test::adopt_context(host.handles());
        ASSERT_TRUE(adopted) << adopted.error().message;
        Context& context = *adopted.value();
        EXPECT_FALSE(context.owns_device());
        EXPECT_EQ(context.device(), host.device);

        run_graph_on(context);  // a compute graph on the host's device, checked on the CPU
    }
    // Facet is gone: the host's device, queue and pool still work.
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = host.pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateCommandBuffers(host.device, &alloc, &cmd), VK_SUCCESS);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    ASSERT_EQ(vkBeginCommandBuffer(cmd, &begin), VK_SUCCESS);
    ASSERT_EQ(vkEndCommandBuffer(cmd), VK_SUCCESS);
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    EXPECT_EQ(vkQueueSubmit(host.queue, 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);
    EXPECT_EQ(vkQueueWaitIdle(host.queue), VK_SUCCESS);
    vkFreeCommandBuffers(host.device, host.pool, 1, &cmd);
    // The validation layer reports objects Facet left behind when the device is destroyed.
    host.destroy();
    EXPECT_EQ(host.counts.messages, 0u);
}

TEST(HostDevice, MissingHandlesAreAClearError) {
    auto adopted = test::adopt_context(HostVulkan{});
    ASSERT_FALSE(adopted);
    EXPECT_NE(adopted.error().message.find("required"), std::string::npos);
}

// A host that leaves out what Facet needs is told each missing piece by name; the same
// host with everything enabled is adopted.
TEST(HostDevice, AMissingFeatureOrExtensionIsNamed) {
    HostEngine host;
    host.create({.dynamic_rendering = false, .synchronization2 = true, .push_descriptor = false});
    ASSERT_FALSE(testing::Test::HasFatalFailure());
    {
        auto adopted = test::adopt_context(host.handles());
        ASSERT_FALSE(adopted);
        const std::string& message = adopted.error().message;
        EXPECT_NE(message.find("feature dynamicRendering (VkPhysicalDeviceVulkan13Features)"), std::string::npos)
            << message;
        EXPECT_NE(message.find("extension VK_KHR_push_descriptor"), std::string::npos) << message;
        EXPECT_EQ(message.find("synchronization2"), std::string::npos) << "enabled, yet named: " << message;
    }
    {
        // The host forgot to say which version its instance asks for.
        HostVulkan handles = host.handles();
        handles.api_version = 0;
        handles.enabled_features = nullptr;
        auto adopted = test::adopt_context(handles);
        ASSERT_FALSE(adopted);
        EXPECT_NE(adopted.error().message.find("Vulkan 1.3"), std::string::npos) << adopted.error().message;
        EXPECT_NE(adopted.error().message.find("feature synchronization2"), std::string::npos)
            << adopted.error().message;
    }
    host.destroy();
    EXPECT_EQ(host.counts.messages, 0u);

    HostEngine complete;
    complete.create();
    ASSERT_FALSE(testing::Test::HasFatalFailure());
    {
        auto adopted = test::adopt_context(complete.handles());
        EXPECT_TRUE(adopted) << adopted.error().message;
    }
    complete.destroy();
    EXPECT_EQ(complete.counts.messages, 0u);
}

// Every submission of Facet's goes through the host's hook, which holds the host's own
// queue lock (Vulkan requires the host to synchronise access to its queue); the
// results are still right.
TEST(HostDevice, EverySubmissionGoesThroughTheHostsHook) {
    HostEngine host;
    host.create();
    ASSERT_FALSE(testing::Test::HasFatalFailure());
    std::mutex host_queue_lock;
    uint64_t hooked = 0;
    {
        HostVulkan handles = host.handles();
        handles.submit = [&](VkQueue queue, const VkSubmitInfo2& submit, VkFence fence) {
            std::lock_guard lock(host_queue_lock);
            ++hooked;
            EXPECT_EQ(queue, host.queue);
            return vkQueueSubmit2(queue, 1, &submit, fence);
        };
        auto adopted = test::adopt_context(handles);
        ASSERT_TRUE(adopted) << adopted.error().message;
        const uint64_t submissions_before = fault_site_calls(FaultSite::submit);
        run_graph_on(*adopted.value());
        const uint64_t submissions = fault_site_calls(FaultSite::submit) - submissions_before;
        EXPECT_GT(submissions, 0u);
        EXPECT_EQ(hooked, submissions) << "a submission bypassed the host's hook";
    }
    host.destroy();
    EXPECT_EQ(host.counts.messages, 0u);
}

// Destroying Facet's context does not wait for the host's device: with host work still
// blocked on the queue (an event the host has not set), the destruction returns. Were it
// to call vkDeviceWaitIdle or vkQueueWaitIdle it would block until the event is set.
TEST(HostDevice, DestroyingFacetDoesNotWaitForTheHostsWork) {
    HostEngine host;
    host.create();
    ASSERT_FALSE(testing::Test::HasFatalFailure());
    auto adopted = test::adopt_context(host.handles());
    ASSERT_TRUE(adopted) << adopted.error().message;
    run_graph_on(*adopted.value());

    VkEventCreateInfo event_info{VK_STRUCTURE_TYPE_EVENT_CREATE_INFO};
    VkEvent event = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateEvent(host.device, &event_info, nullptr, &event), VK_SUCCESS);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = host.pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateCommandBuffers(host.device, &alloc, &cmd), VK_SUCCESS);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    ASSERT_EQ(vkBeginCommandBuffer(cmd, &begin), VK_SUCCESS);
    vkCmdWaitEvents(cmd, 1, &event, VK_PIPELINE_STAGE_HOST_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, nullptr, 0,
                    nullptr, 0, nullptr);
    ASSERT_EQ(vkEndCommandBuffer(cmd), VK_SUCCESS);
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    ASSERT_EQ(vkQueueSubmit(host.queue, 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);

    auto destroyed = std::async(std::launch::async, [&] { adopted.value().reset(); });
    const bool returned = destroyed.wait_for(std::chrono::seconds(5)) == std::future_status::ready;
    vkSetEvent(host.device, event);  // the host's work finishes either way
    destroyed.wait();
    EXPECT_TRUE(returned) << "destroying the adopted context waited for the host's blocked work";
    EXPECT_EQ(vkQueueWaitIdle(host.queue), VK_SUCCESS);
    vkFreeCommandBuffers(host.device, host.pool, 1, &cmd);
    vkDestroyEvent(host.device, event, nullptr);
    host.destroy();
    EXPECT_EQ(host.counts.messages, 0u);
}

}  // namespace
}  // namespace facet
