// A host engine owns the Vulkan instance and device and hands them to Facet: Facet must
// run its work on them and destroy only its own objects.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include <facet/gpu/context.h>
#include <facet/gpu/resources.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/graph/render_graph.h>
#include <facet/gpu/pipeline.h>
#include <facet/shader/compiler.h>

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
    const VkDescriptorType bindings[] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    Pipeline fill_pipeline = Pipeline::compute(context, fill->words, bindings, 0, "fill");
    Pipeline add_pipeline = Pipeline::compute(context, add->words, bindings, 0, "add");
    const uint32_t count = 1024;
    Buffer result(context, count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::readback, "host test result");

    RenderGraph g;
    ImportedBuffer imported{result.handle(), count * 4, {},
                            {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT}};
    auto values = g.import_buffer("result", imported);
    auto dispatch = [&](const Pipeline& p, BufferHandle h) {
        return [&p, h, count](PassContext& pc) {
            p.bind(pc.cmd());
            const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(h))};
            p.push_descriptors(pc.cmd(), writes);
            vkCmdDispatch(pc.cmd(), count / 64, 1, 1);
        };
    };
    BufferHandle before_fill = values;
    g.add_compute_pass("fill", [&](PassBuilder& b) { values = b.write(values); }, dispatch(fill_pipeline, before_fill));
    BufferHandle before_add = values;
    g.add_compute_pass("add", [&](PassBuilder& b) { values = b.write(values, Access::storage_read_write); },
                       dispatch(add_pipeline, before_add));
    CompiledGraph compiled = g.compile();
    ASSERT_EQ(compiled.passes.size(), 2u);
    auto run = run_graph(context, compiled);
    result.invalidate();
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

// The host's own minimal Vulkan set-up, written without Facet's helpers.
struct HostEngine {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;  // the host's own object, must survive Facet
    HostCounts counts;

    void create() {
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

        VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        features13.synchronization2 = VK_TRUE;
        features13.dynamicRendering = VK_TRUE;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        features.pNext = &features13;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue_info.queueFamilyIndex = family;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        const char* device_extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
        VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        device_info.pNext = &features;
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        device_info.enabledExtensionCount = 1;
        device_info.ppEnabledExtensionNames = device_extensions;
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
        HostVulkan handles{host.instance, host.physical, host.device, host.queue, host.family, true};
        auto adopted = Context::adopt(handles);
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
    auto adopted = Context::adopt(HostVulkan{});
    ASSERT_FALSE(adopted);
    EXPECT_NE(adopted.error().message.find("required"), std::string::npos);
}

}  // namespace
}  // namespace facet
