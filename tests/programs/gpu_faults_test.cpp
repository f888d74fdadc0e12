// Teardown and driver failures. Every test here makes its own validated context and
// destroys it, so the validation layer's object tracking reports any Vulkan object left
// behind (vkDestroyDevice/vkDestroyInstance), also after a failure part-way through a
// bake or a render. The failures are injected (gpu/fault_injection.h) at every call of
// their kind that a bake + render makes.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include <facet/gpu/context.h>
#include "gpu/fault_injection.h"
#include <facet/gpu/memory.h>
#include "support/tiny_session.h"

namespace facet {
namespace {

// The calls of each kind one tiny bake + render makes (counted once per process).
uint64_t calls_per_session(FaultSite site) {
    static const auto counts = [] {
        std::array<uint64_t, fault_site_count> before{}, after{};
        for (int s = 0; s < fault_site_count; ++s) before[s] = fault_site_calls(FaultSite(s));
        auto context = test::own_context();
        EXPECT_TRUE(test::run_tiny_session(*context).error.empty());
        for (int s = 0; s < fault_site_count; ++s) after[s] = fault_site_calls(FaultSite(s));
        std::array<uint64_t, fault_site_count> n{};
        for (int s = 0; s < fault_site_count; ++s) n[s] = after[s] - before[s];
        return n;
    }();
    return counts[static_cast<size_t>(site)];
}

TEST(Teardown, ObjectTrackingReportsAnObjectLeftBehind) {
    // The check the other tests rely on: a sampler never destroyed is reported when
    // the device is destroyed, and counted although its context is gone.
    auto context = test::own_context();
    ASSERT_TRUE(context);
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    VkSampler leaked = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateSampler(context->device(), &info, nullptr, &leaked), VK_SUCCESS);
    const uint32_t before = Context::process_validation_message_count();
    std::fprintf(stderr, "(a validation error about a VkSampler not destroyed is expected next)\n");
    context.reset();
    EXPECT_GT(Context::process_validation_message_count(), before);
}

TEST(Teardown, BakeAndRenderLeaveNoVulkanObject) {
    const uint32_t before = Context::process_validation_message_count();
    auto context = test::own_context();
    ASSERT_TRUE(context);
    const test::TinyResult result = test::run_tiny_session(*context);
    ASSERT_EQ(result.error, "");
    EXPECT_GT(result.mean_radiance, 0.0);
    const AllocatorStats stats = context->allocator().stats();
    EXPECT_EQ(stats.live_allocations, 0u) << "device memory still allocated after the session";
    context.reset();
    EXPECT_EQ(Context::process_validation_message_count(), before) << "messages printed above";
}

struct FaultCase {
    FaultSite site;
    VkResult expected;
    const char* call;  // what the message must name
};

class InjectedFault : public ::testing::TestWithParam<FaultCase> {};

// Each call of the kind fails in turn; the error reaches the caller with its VkResult
// and the call named, and tearing down what was made so far leaves nothing behind. That
// the same context then works again (out of memory and a failed pipeline) or stays lost
// (a lost device) is checked after every fourth failure and the last: it is a whole
// session more each time.
TEST_P(InjectedFault, EveryCallFailsCleanly) {
    const FaultCase c = GetParam();
    const uint64_t calls = calls_per_session(c.site);
    ASSERT_GT(calls, 0u) << "a bake + render makes no such call";
    std::printf("failing each of the %llu calls in turn\n", static_cast<unsigned long long>(calls));
    for (uint64_t skip = 0; skip < calls; ++skip) {
        SCOPED_TRACE("failing call " + std::to_string(skip + 1) + " of " + std::to_string(calls));
        const uint32_t before = Context::process_validation_message_count();
        auto context = test::own_context();
        ASSERT_TRUE(context);
        inject_fault(c.site, static_cast<uint32_t>(skip));
        const test::TinyResult result = test::run_tiny_session(*context);
        clear_injected_faults();
        EXPECT_EQ(result.vk_result, c.expected) << result.error;
        EXPECT_NE(result.error.find(c.call), std::string::npos) << result.error;
        EXPECT_NE(result.error.find(vk_result_name(c.expected)), std::string::npos) << result.error;
        EXPECT_EQ(context->allocator().stats().live_allocations, 0u);
        const bool again = skip % 4 == 0 || skip + 1 == calls;
        if (c.site == FaultSite::submit) {
            EXPECT_TRUE(context->device_lost());
            // A lost device stays lost: the next piece of work fails at once, no hang.
            if (again) EXPECT_EQ(test::run_tiny_session(*context).vk_result, VK_ERROR_DEVICE_LOST);
        } else if (again) {
            // Out of memory and a failed pipeline are not fatal: the same context recovers.
            EXPECT_EQ(test::run_tiny_session(*context).error, "");
        }
        context.reset();
        EXPECT_EQ(Context::process_validation_message_count(), before) << "messages printed above";
    }
}

INSTANTIATE_TEST_SUITE_P(
    Sites, InjectedFault,
    ::testing::Values(FaultCase{FaultSite::memory, VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory"},
                      FaultCase{FaultSite::submit, VK_ERROR_DEVICE_LOST, "vkQueueSubmit2"},
                      FaultCase{FaultSite::pipeline, VK_ERROR_UNKNOWN, "Pipelines"}),
    [](const auto& info) {
        switch (info.param.site) {
            case FaultSite::memory: return std::string("OutOfDeviceMemory");
            case FaultSite::submit: return std::string("DeviceLost");
            case FaultSite::pipeline: return std::string("PipelineCreation");
        }
        return std::string("unknown");
    });

TEST(Teardown, ANewContextWorksAfterADeviceLoss) {
    const uint32_t before = Context::process_validation_message_count();
    {
        auto lost = test::own_context();
        inject_fault(FaultSite::submit);
        EXPECT_EQ(test::run_tiny_session(*lost).vk_result, VK_ERROR_DEVICE_LOST);
        clear_injected_faults();
    }
    auto fresh = test::own_context();
    EXPECT_EQ(test::run_tiny_session(*fresh).error, "");
    fresh.reset();
    EXPECT_EQ(Context::process_validation_message_count(), before);
}

// The same fault part-way through a bake + render reaches the caller as one error.
TEST(Teardown, AHangDuringABakeIsAnErrorNotAHang) {
    const uint32_t before = Context::process_validation_message_count();
    // A GPU that never finishes the third submission (FaultSite::hang), waited for 200 ms.
    ContextOptions options = test::context_options();
    options.fence_timeout_ms = 200;
    options.inject_fault = FaultInjection{FaultSite::hang, 2};
    auto created = test::create_context(options);
    ASSERT_TRUE(created) << created.error().message;
    std::unique_ptr<Context> context = std::move(created).value();
    const test::TinyResult result = test::run_tiny_session(*context);
    EXPECT_EQ(result.vk_result, VK_TIMEOUT) << result.error;
    EXPECT_NE(result.error.find("timed out after 200 ms"), std::string::npos) << result.error;
    EXPECT_EQ(context->allocator().stats().live_allocations, 0u);
    context.reset();
    EXPECT_EQ(Context::process_validation_message_count(), before) << "messages printed above";
}

}  // namespace
}  // namespace facet

// The programs report the same failures as one clear error, exit 1, and write nothing.
#include <filesystem>
#include <unistd.h>

#include "support/process.h"

namespace {

namespace fs = std::filesystem;

struct ProgramFault {
    const char* fault;     // FACET_INJECT_FAULT
    const char* program;   // "render" or "bake"
    const char* expected;  // in the message
};

class ProgramUnderFault : public ::testing::TestWithParam<ProgramFault> {};

TEST_P(ProgramUnderFault, OneClearErrorAndNoOutput) {
    const ProgramFault p = GetParam();
    const fs::path dir = fs::temp_directory_path() / ("facet_faults_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string env = std::string("FACET_VALIDATION=1 FACET_INJECT_FAULT=") + p.fault + " ";
    const std::string command =
        std::string(p.program) == "render"
            ? env + FACET_RENDER_PATH + " --out " + (dir / "frame.png").string() +
                  " --width 32 --height 32 --env builtin:sky --env-width 64 --ibl-size 16 --ibl-samples 64"
            : env + FACET_BAKE_PATH + " builtin:sky --out " + (dir / "bake").string() +
                  " --width 64 --size 16 --samples 64 --lut-size 16 --lut-samples 64";
    const facet::test::Ran ran = facet::test::run_command(command);
    EXPECT_EQ(ran.status, 1) << ran.output;
    EXPECT_NE(ran.output.find(p.expected), std::string::npos) << ran.output;
    EXPECT_EQ(ran.output.find("validation:"), std::string::npos) << ran.output;
    size_t files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file()) ++files;
    EXPECT_EQ(files, 0u) << "output written despite the failure";
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Programs, ProgramUnderFault,
    ::testing::Values(ProgramFault{"memory:5", "render", "VK_ERROR_OUT_OF_DEVICE_MEMORY"},
                      ProgramFault{"submit:3", "render", "VK_ERROR_DEVICE_LOST"},
                      ProgramFault{"pipeline:4", "render", "VK_ERROR_UNKNOWN"},
                      ProgramFault{"memory:5", "bake", "VK_ERROR_OUT_OF_DEVICE_MEMORY"},
                      ProgramFault{"submit:1", "bake", "VK_ERROR_DEVICE_LOST"},
                      ProgramFault{"pipeline:2", "bake", "VK_ERROR_UNKNOWN"},
                      ProgramFault{"disk", "render", "FACET_INJECT_FAULT='disk'"},
                      ProgramFault{"submit:x", "bake", "SKIP must be a whole number"}),
    [](const auto& info) { return std::string(info.param.program) + std::to_string(info.index); });

}  // namespace
