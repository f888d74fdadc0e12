// Several contexts in one process, and one context shared by threads through its
// thread-safe entry points (gpu/context.h: resource creation, pipeline creation,
// submission; everything built on them, such as a RenderSession per thread). The
// validation layer's thread-safety checks report any externally synchronized object
// used from two threads at once; the images must equal those of a lone thread.
// Also run under ThreadSanitizer by the `tsan` preset (README).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <facet/gpu/context.h>
#include <facet/gpu/memory.h>
#include "support/tiny_session.h"

namespace facet {
namespace {

// Two jobs that differ, so that crossed wires between threads would show in the image.
RenderJob job_for(int which) {
    RenderJob job = test::tiny_job();
    if (which % 2) job.preset = "gold";
    return job;
}

double alone(int which) {
    static double means[2] = {-1, -1};
    if (means[which % 2] < 0) {
        auto context = test::own_context();
        const test::TinyResult r = test::run_tiny_session(*context, job_for(which));
        EXPECT_EQ(r.error, "");
        means[which % 2] = r.mean_radiance;
    }
    return means[which % 2];
}

TEST(Threads, TwoContextsInOneProcess) {
    const double expected[2] = {alone(0), alone(1)};
    const uint32_t before = Context::process_validation_message_count();
    auto a = test::own_context();
    auto b = test::own_context();
    ASSERT_TRUE(a && b);
    // Interleaved on one thread...
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(test::run_tiny_session(*a, job_for(0)).mean_radiance, expected[0]);
        EXPECT_EQ(test::run_tiny_session(*b, job_for(1)).mean_radiance, expected[1]);
    }
    // ...and each on its own thread at the same time.
    std::vector<test::TinyResult> results(2);
    std::thread ta([&] { results[0] = test::run_tiny_session(*a, job_for(0)); });
    std::thread tb([&] { results[1] = test::run_tiny_session(*b, job_for(1)); });
    ta.join();
    tb.join();
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(results[i].error, "");
        EXPECT_EQ(results[i].mean_radiance, expected[i]);
    }
    a.reset();
    b.reset();
    EXPECT_EQ(Context::process_validation_message_count(), before) << "messages printed above";
}

TEST(Threads, OneContextFromTwoThreads) {
    const double expected[2] = {alone(0), alone(1)};
    const uint32_t before = Context::process_validation_message_count();
    auto context = test::own_context();
    ASSERT_TRUE(context);
    constexpr int threads = 2, sessions_per_thread = 4;
    std::vector<std::vector<test::TinyResult>> results(threads);
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            for (int i = 0; i < sessions_per_thread; ++i)
                results[t].push_back(test::run_tiny_session(*context, job_for(t)));
        });
    for (std::thread& w : workers) w.join();
    for (int t = 0; t < threads; ++t)
        for (const test::TinyResult& r : results[t]) {
            EXPECT_EQ(r.error, "") << "thread " << t;
            EXPECT_EQ(r.mean_radiance, expected[t]) << "thread " << t;
        }
    EXPECT_EQ(context->allocator().stats().live_allocations, 0u);
    context.reset();
    EXPECT_EQ(Context::process_validation_message_count(), before) << "messages printed above";
}

}  // namespace
}  // namespace facet
