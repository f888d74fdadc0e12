#pragma once
// One Vulkan context per test executable, with the validation layer and
// synchronization validation on; every GPU test fails on any validation message.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <facet/gpu/context.h>

namespace facet {
class ProgramCache;
}

namespace facet::test {

// The one place tests turn the environment into context options (the library reads
// none): validation and synchronization validation on unless FACET_VALIDATION=0 (ctest
// sets 1), the device FACET_DEVICE names.
ContextOptions context_options();
// Context::create / Context::adopt for tests; every test context is made here.
Result<std::unique_ptr<Context>> create_context(const ContextOptions& options = context_options());
Result<std::unique_ptr<Context>> adopt_context(const HostVulkan& host, const ContextOptions& options = context_options());

// A Result's value for test set-up that is expected to succeed; its Error otherwise
// ends the test as a failure (gtest reports the exception with the message).
template <class T>
T must(Result<T> result) {
    if (!result.ok()) throw std::runtime_error("unexpected Error: " + result.error().message);
    return std::move(result).value();
}

// The shared context (created on first use; a test that cannot get it fails).
Context& gpu();
// Pipelines on the shared context for every test of the executable that shares them
// (RenderJob::programs, run_ibl): each shader variant is compiled and its pipeline created
// once per process instead of once per session or pass. Embedded shaders, no disk cache;
// destroyed just before the shared context. Not for tests that count the context's objects.
ProgramCache& gpu_programs();
// gpu_programs() when `context` is the shared context, else nullptr (creates neither).
ProgramCache* shared_programs_for(const Context& context);

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    Context& ctx() { return gpu(); }

private:
    uint32_t messages_at_start_ = 0;
};

}  // namespace facet::test
