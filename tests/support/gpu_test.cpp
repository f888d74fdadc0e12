#include "support/gpu_test.h"

#include <cstdlib>
#include <memory>

namespace facet::test {

Context& gpu() {
    static std::unique_ptr<Context> context = [] {
        ContextOptions options;
        options.validation = true;
        options.sync_validation = true;
        auto created = Context::create(options);
        if (!created) {
            ADD_FAILURE() << "cannot create a Vulkan context: " << created.error().message;
            std::abort();
        }
        return std::move(created).value();
    }();
    return *context;
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
