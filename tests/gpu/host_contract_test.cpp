// The host contract as data (facet/gpu/requirements.h), fence waits that end in an
// error instead of a hang, and a library that reads no environment variable.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <facet/core/log.h>
#include <facet/gpu/context.h>
#include <facet/gpu/memory.h>
#include <facet/gpu/requirements.h>
#include <facet/gpu/resources.h>
#include "support/gpu_test.h"

namespace facet {
namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(HostContract, RequirementsAreVulkan13WithTheirFeaturesAndExtension) {
    DeviceRequirements needs = device_requirements();
    EXPECT_EQ(needs.api_version, VK_API_VERSION_1_3);
    ASSERT_EQ(needs.device_extensions.size(), 1u);
    EXPECT_STREQ(needs.device_extensions[0], VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    EXPECT_TRUE(needs.vulkan13.synchronization2);
    EXPECT_TRUE(needs.vulkan13.dynamicRendering);

    // The chain a host hands to VkDeviceCreateInfo::pNext, ending in the host's own struct.
    VkPhysicalDeviceVulkan11Features host_own{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceFeatures2* head = needs.chain(&host_own);
    ASSERT_EQ(head, &needs.features);
    EXPECT_EQ(head->sType, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    EXPECT_EQ(head->pNext, &needs.vulkan12);
    EXPECT_EQ(needs.vulkan12.pNext, &needs.vulkan13);
    EXPECT_EQ(needs.vulkan13.pNext, &host_own);

    // What it asks for is what it checks: a device stated with exactly this chain meets it.
    EnabledDevice device;
    device.api_version = VK_API_VERSION_1_3;
    device.extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    device.features = head;
    EXPECT_TRUE(unmet_device_requirements(needs, device).empty());
}

TEST(HostContract, EachUnmetRequirementIsNamed) {
    const DeviceRequirements needs = device_requirements();
    EnabledDevice nothing;
    nothing.api_version = VK_API_VERSION_1_2;
    const std::vector<std::string> unmet = unmet_device_requirements(needs, nothing);
    ASSERT_EQ(unmet.size(), 4u);
    EXPECT_EQ(unmet[0], "Vulkan 1.3 (the instance asks for 1.2)");
    EXPECT_EQ(unmet[1], "feature synchronization2 (VkPhysicalDeviceVulkan13Features)");
    EXPECT_EQ(unmet[2], "feature dynamicRendering (VkPhysicalDeviceVulkan13Features)");
    EXPECT_EQ(unmet[3], "extension VK_KHR_push_descriptor");

    // The features may come in their own structs (the extensions' form), in any order.
    VkPhysicalDeviceDynamicRenderingFeatures rendering{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    rendering.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceSynchronization2Features sync2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES,
                                                   &rendering};
    sync2.synchronization2 = VK_TRUE;
    EnabledDevice split;
    split.api_version = VK_API_VERSION_1_3;
    split.extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    split.features = &sync2;
    EXPECT_TRUE(unmet_device_requirements(needs, split).empty());
    rendering.dynamicRendering = VK_FALSE;
    const std::vector<std::string> one = unmet_device_requirements(needs, split);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_TRUE(contains(one[0], "dynamicRendering")) << one[0];
}

TEST(HostContract, ValidationDefaultFollowsTheBuildNotTheEnvironment) {
#ifdef NDEBUG
    EXPECT_FALSE(ContextOptions::default_validation());
#else
    EXPECT_TRUE(ContextOptions::default_validation());
#endif
    EXPECT_EQ(ContextOptions{}.fence_timeout_ms, 60'000u);
    ContextOptions zero = test::context_options();
    zero.fence_timeout_ms = 0;
    auto created = test::create_context(zero);
    ASSERT_FALSE(created);
    EXPECT_TRUE(contains(created.error().message, "fence_timeout_ms")) << created.error().message;
}

// A GPU that never signals: the submission is dropped (FaultSite::hang), so its fence
// never signals. The wait ends after the timeout with an error naming it, the context
// refuses more work at once, and its teardown leaves nothing behind.
TEST(HostContract, AFenceThatNeverSignalsTimesOut) {
    const uint32_t before = Context::process_validation_message_count();
    ContextOptions options = test::context_options();
    options.fence_timeout_ms = 200;
    options.inject_fault = FaultInjection{FaultSite::hang, 0};
    auto created = test::create_context(options);
    ASSERT_TRUE(created) << created.error().message;
    std::unique_ptr<Context> context = std::move(created).value();
    {
        Buffer buffer = test::must(
            Buffer::create(*context, 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::gpu_only, "never filled"));
        const auto start = std::chrono::steady_clock::now();
        Status waited = Ok{};
        EXPECT_NO_THROW(waited = context->submit_and_wait(
                            [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 0, 256, 7); },
                            "the test's fill"));
        ASSERT_FALSE(waited.ok()) << "the wait returned although the fence never signals";
        EXPECT_EQ(waited.error().vk_result, VK_TIMEOUT);
        EXPECT_TRUE(contains(waited.error().message,
                             "timed out after 200 ms waiting for the GPU to finish the test's fill"))
            << waited.error().message;
        const double waited_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        EXPECT_GE(waited_ms, 190.0);
        EXPECT_LT(waited_ms, 5000.0);
        EXPECT_TRUE(context->timed_out());

        // No more work, and no second wait.
        const auto again = std::chrono::steady_clock::now();
        Status refused = Ok{};
        EXPECT_NO_THROW(refused = context->submit_and_wait(
                            [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 0, 256, 7); }));
        ASSERT_FALSE(refused.ok()) << "a context that timed out took more work";
        EXPECT_EQ(refused.error().vk_result, VK_TIMEOUT);
        EXPECT_TRUE(contains(refused.error().message, "an earlier wait for the GPU timed out"))
            << refused.error().message;
        const double refused_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - again).count();
        EXPECT_LT(refused_ms, 100.0);
    }
    EXPECT_EQ(context->allocator().stats().live_allocations, 0u);
    context.reset();
    EXPECT_EQ(Context::process_validation_message_count(), before) << "messages printed above";
}

TEST(HostContract, LogLevelIsAnOption) {
    const LogLevel saved = log_level();
    set_log_level(LogLevel::warning);
    testing::internal::CaptureStderr();
    log(LogLevel::info, "an info line that must not print");
    log(LogLevel::warning, "a warning line that must print");
    const std::string printed = testing::internal::GetCapturedStderr();
    set_log_level(saved);
    EXPECT_FALSE(contains(printed, "must not print")) << printed;
    EXPECT_TRUE(contains(printed, "must print")) << printed;
}

// Nothing in the library reads the environment: devices, logging, validation, shader
// directories and fault injection are options; the programs map their FACET_* variables.
TEST(HostContract, TheLibraryReadsNoEnvironmentVariable) {
    namespace fs = std::filesystem;
    std::vector<std::string> readers;
    size_t files = 0;
    for (const char* folder : {"engine", "include"}) {
        for (const auto& entry : fs::recursive_directory_iterator(fs::path(FACET_SOURCE_DIR) / folder)) {
            const std::string ext = entry.path().extension().string();
            if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
            ++files;
            std::ifstream in(entry.path());
            std::stringstream text;
            text << in.rdbuf();
            const std::string source = text.str();
            for (const char* call : {"getenv", "secure_getenv", "environ"})
                if (source.find(std::string(call) + "(") != std::string::npos ||
                    (std::string(call) == "environ" && source.find("extern char** environ") != std::string::npos))
                    readers.push_back(entry.path().string() + " (" + call + ")");
        }
    }
    EXPECT_GT(files, 50u) << "the sources were not found under " << FACET_SOURCE_DIR;
    for (const std::string& reader : readers) ADD_FAILURE() << "the library reads the environment: " << reader;
}

// The device layer stands below the graph: nothing in gpu/ includes a graph header.
TEST(HostContract, TheDeviceLayerDoesNotIncludeTheGraph) {
    namespace fs = std::filesystem;
    size_t files = 0;
    for (const char* folder : {"engine/gpu", "include/facet/gpu"}) {
        for (const auto& entry : fs::directory_iterator(fs::path(FACET_SOURCE_DIR) / folder)) {
            if (!entry.is_regular_file()) continue;
            ++files;
            std::ifstream in(entry.path());
            for (std::string line; std::getline(in, line);)
                if (line.rfind("#include", 0) == 0 && contains(line, "graph/"))
                    ADD_FAILURE() << entry.path().string() << " includes the graph: " << line;
        }
    }
    EXPECT_GT(files, 10u);
}

}  // namespace
}  // namespace facet
