#pragma once
// One Vulkan context per test executable, with the validation layer and
// synchronization validation on; every GPU test fails on any validation message.
#include <gtest/gtest.h>

#include <facet/gpu/context.h>

namespace facet::test {

// The shared context (created on first use; a test that cannot get it fails).
Context& gpu();

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    Context& ctx() { return gpu(); }

private:
    uint32_t messages_at_start_ = 0;
};

}  // namespace facet::test
