#include "support/gpu_test.h"

#include <cstdlib>
#include <cstring>
#include <memory>

#include <facet/shader/program_cache.h>

namespace facet::test {

namespace {

std::unique_ptr<Context>& shared_context() {
    static std::unique_ptr<Context> context;
    return context;
}

// gpu_programs()'s cache and its compiler; made after the context, so that at exit too
// (a test that never reached the teardown below) they go before it.
struct SharedPrograms {
    ShaderCompiler compiler;
    ProgramCache programs;
    explicit SharedPrograms(Context& context) : programs(context, compiler) {}
};
std::unique_ptr<SharedPrograms>& shared_programs() {
    static std::unique_ptr<SharedPrograms> programs;
    return programs;
}

// The shared context is destroyed after the last test of the process rather than at
// exit, so that the validation layer's object tracking (every object must be destroyed
// before its device) is checked for every GPU test executable.
class SharedContextTeardown : public ::testing::Environment {
public:
    void TearDown() override {
        std::unique_ptr<Context>& context = shared_context();
        if (!context) return;
        const uint32_t before = Context::process_validation_message_count();
        shared_programs().reset();
        context.reset();
        EXPECT_EQ(Context::process_validation_message_count(), before)
            << "Vulkan objects left undestroyed at teardown (validation messages above)";
    }
};

[[maybe_unused]] ::testing::Environment* const teardown =
    ::testing::AddGlobalTestEnvironment(new SharedContextTeardown);

}  // namespace

ContextOptions context_options() {
    ContextOptions options;
    const char* validation = std::getenv("FACET_VALIDATION");
    options.validation = !(validation && std::strcmp(validation, "0") == 0);
    options.sync_validation = options.validation;
    if (const char* device = std::getenv("FACET_DEVICE")) options.device = device;
    return options;
}

Result<std::unique_ptr<Context>> create_context(const ContextOptions& options) { return Context::create(options); }

Result<std::unique_ptr<Context>> adopt_context(const HostVulkan& host, const ContextOptions& options) {
    return Context::adopt(host, options);
}

Context& gpu() {
    std::unique_ptr<Context>& context = shared_context();
    if (!context) {
        ContextOptions options = context_options();
        options.validation = true;
        options.sync_validation = true;
        auto created = create_context(options);
        if (!created) {
            ADD_FAILURE() << "cannot create a Vulkan context: " << created.error().message;
            std::abort();
        }
        context = std::move(created).value();
    }
    return *context;
}

ProgramCache& gpu_programs() {
    Context& context = gpu();
    std::unique_ptr<SharedPrograms>& shared = shared_programs();
    if (!shared) shared = std::make_unique<SharedPrograms>(context);
    return shared->programs;
}

ProgramCache* shared_programs_for(const Context& context) {
    return shared_context().get() == &context ? &gpu_programs() : nullptr;
}

void GpuTest::SetUp() {
    ASSERT_TRUE(gpu().validation_enabled()) << "tests need the Khronos validation layer";
    messages_at_start_ = gpu().validation_message_count();
}

void GpuTest::TearDown() {
    EXPECT_EQ(gpu().validation_message_count(), messages_at_start_)
        << "validation messages during this test (printed above)";
}

}  // namespace facet::test
