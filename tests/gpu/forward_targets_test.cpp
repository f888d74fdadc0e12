// The forward pass as a host engine inserts it: into colour and depth images the host
// owns (imported into its graph), with the host's matrices, stopping at linear HDR;
// two frames in flight each with its own camera; and steady frames through the
// executor allocating nothing. The default path (RenderSession, Facet's own RGBA32F
// target) is the reference. The fixture fails on any validation message.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/graph_executor.h>
#include <facet/render/gpu_scene.h>
#include <facet/render/render_job.h>
#include "support/gpu_test.h"
#include "support/tiny_session.h"

namespace facet {
namespace {

const ResourceState readable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                             VK_ACCESS_2_TRANSFER_READ_BIT};
const ResourceState untouched{VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};

// A host engine's own render targets: RGBA16F colour and D32 depth.
struct HostTargets {
    Image color, depth;
    HostTargets(Context& context, uint32_t w, uint32_t h) {
        ImageDesc desc;
        desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        desc.width = w;
        desc.height = h;
        color = test::must(Image::create(context, desc,
                                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                         "host colour"));
        desc.format = VK_FORMAT_D32_SFLOAT;
        depth = test::must(Image::create(context, desc, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "host depth"));
    }
    ForwardTargets import(RenderGraph& graph) const {
        ForwardTargets t;
        t.color = graph.import_image("host colour", {color.handle(), color.desc(), untouched, readable});
        t.depth = graph.import_image("host depth", {depth.handle(), depth.desc(), untouched, {}});
        return t;
    }
    std::vector<float> read(Context& context) const {
        auto bytes = test::must(read_image(context, color, 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
        std::vector<uint16_t> halves(bytes.size() / 2);
        std::memcpy(halves.data(), bytes.data(), bytes.size());
        std::vector<float> out(halves.size());
        for (size_t i = 0; i < halves.size(); ++i) out[i] = glm::unpackHalf1x16(halves[i]);
        return out;
    }
};

class ForwardTargetsTest : public test::GpuTest {
protected:
    std::unique_ptr<RenderSession> session(uint32_t w, uint32_t h) {
        RenderJob job = test::tiny_job();
        job.frame.width = w;
        job.frame.height = h;
        job.frame.samples = 1;
        job.frame.skybox = false;  // linear HDR of the forward pass alone
        auto created = RenderSession::create(ctx(), job);
        EXPECT_TRUE(created) << (created ? "" : created.error().message);
        return created ? std::move(*created) : nullptr;
    }
    // The forward pass alone into `host`, slot `frame` of `renderer`, run and waited for.
    void render_into(RenderSession& s, ForwardRenderer& renderer, GraphExecutor& executor, const HostTargets& host,
                     const CameraMatrices& camera, uint32_t frame) {
        RenderGraph graph;
        auto drawn = renderer.add_forward_pass(graph, s.gpu_scene(), s.frame(), camera, host.import(graph),
                                               s.import_baked(graph), frame);
        ASSERT_TRUE(drawn) << drawn.error().message;
        CompiledGraph compiled = graph.compile();
        ASSERT_TRUE(executor.submit_and_wait(compiled, frame));
    }
};

// Pixels where a and b differ by more than half float's rounding (relative 2^-10, with
// an absolute floor for values near 0).
size_t mismatches(const std::vector<float>& a, const std::vector<float>& b, double* worst = nullptr) {
    if (a.size() != b.size()) return SIZE_MAX;
    size_t n = 0;
    double w = 0;
    for (size_t i = 0; i < a.size(); i += 4) {
        bool bad = false;
        for (int c = 0; c < 4; ++c) {
            const double d = std::abs(double(a[i + c]) - double(b[i + c]));
            const double tolerance = std::ldexp(1.0, -10) * std::abs(double(b[i + c])) + 1e-4;
            w = std::max(w, d / tolerance);
            bad = bad || !(d <= tolerance);
        }
        n += bad;
    }
    if (worst) *worst = w;
    return n;
}

TEST_F(ForwardTargetsTest, ForwardPassIntoHostRgba16fEqualsTheDefaultLinearHdr) {
    const uint32_t w = 48, h = 32;
    auto s = session(w, h);
    ASSERT_TRUE(s);
    auto reference = s->render_frame();
    ASSERT_TRUE(reference) << reference.error().message;

    HostTargets host(ctx(), w, h);
    GraphExecutor executor(ctx());
    render_into(*s, s->renderer(), executor, host, s->camera().matrices(float(w) / float(h)), 0);
    const std::vector<float> hdr = host.read(ctx());

    // The frame is not trivial: spheres (alpha 1) over nothing (alpha 0).
    size_t covered = 0;
    for (size_t i = 3; i < reference->hdr.size(); i += 4) covered += reference->hdr[i] == 1.0f;
    EXPECT_GT(covered, size_t(w) * h / 10);
    EXPECT_LT(covered, size_t(w) * h);
    double worst = 0;
    EXPECT_EQ(mismatches(hdr, reference->hdr, &worst), 0u) << "worst difference " << worst << " x tolerance";
}

// Two frames in flight: slot 0 and slot 1 are recorded one after the other before either
// runs (one command buffer), each with its own camera. Each must equal the same camera
// rendered alone: a slot's camera and lights are not overwritten by the other's.
TEST_F(ForwardTargetsTest, TwoFramesInFlightKeepTheirOwnCameras) {
    const uint32_t w = 40, h = 40;
    auto s = session(w, h);
    ASSERT_TRUE(s);
    auto renderer_owner = ForwardRenderer::create(ctx(), s->programs(), 2);
    ASSERT_TRUE(renderer_owner) << renderer_owner.error().message;
    ForwardRenderer& renderer = **renderer_owner;
    GraphExecutor executor(ctx(), 2);
    const CameraView a = s->camera();
    const glm::vec3 target = a.target;
    const CameraView b = orbit_camera(target, 50.0f, 25.0f, glm::length(a.position - target), a.yfov);
    const CameraMatrices cameras[2] = {a.matrices(1.0f), b.matrices(1.0f)};

    HostTargets alone[2] = {{ctx(), w, h}, {ctx(), w, h}};
    for (uint32_t f = 0; f < 2; ++f) render_into(*s, renderer, executor, alone[f], cameras[f], 0);
    const std::vector<float> expected[2] = {alone[0].read(ctx()), alone[1].read(ctx())};
    EXPECT_GT(mismatches(expected[0], expected[1]), size_t(w) * h / 20) << "the two cameras must see different images";

    HostTargets together[2] = {{ctx(), w, h}, {ctx(), w, h}};
    RenderGraph graphs[2];
    CompiledGraph compiled[2];
    for (uint32_t f = 0; f < 2; ++f) {
        auto drawn = renderer.add_forward_pass(graphs[f], s->gpu_scene(), s->frame(), cameras[f],
                                               together[f].import(graphs[f]), s->import_baked(graphs[f]), f);
        ASSERT_TRUE(drawn) << drawn.error().message;
        compiled[f] = graphs[f].compile();
    }
    ASSERT_TRUE(ctx().submit_and_wait([&](VkCommandBuffer cmd) {
        for (uint32_t f = 0; f < 2; ++f) ASSERT_TRUE(executor.record(compiled[f], cmd, f));
    }));
    for (uint32_t f = 0; f < 2; ++f) EXPECT_EQ(mismatches(together[f].read(ctx()), expected[f]), 0u) << "slot " << f;
}

// The viewer's frame (forward with MSAA, skybox, display transform, a component view)
// through the executor: after the first frame nothing is allocated and no image created,
// and the images are the same every frame. Prints the CPU cost of a steady frame (graph
// build + compile + record, no submission), median of the frames; not a pass criterion.
// FACET_FRAME_COST="WxH FRAMES" measures another size (the figures in the report).
TEST_F(ForwardTargetsTest, SteadyViewerFramesAllocateNothing) {
    RenderJob job = test::tiny_job();
    job.frame.width = 320;
    job.frame.height = 180;
    int frames = 30;
    if (const char* size = std::getenv("FACET_FRAME_COST"))
        std::sscanf(size, "%ux%u %d", &job.frame.width, &job.frame.height, &frames);
    job.frame.views = {View::normal};
    auto created = RenderSession::create(ctx(), job);
    ASSERT_TRUE(created) << created.error().message;
    RenderSession& s = **created;
    GraphExecutor executor(ctx());
    std::vector<double> cpu_ms;
    AllocatorStats settled{};
    for (int frame = 0; frame < frames; ++frame) {
        const auto start = std::chrono::steady_clock::now();
        RenderGraph graph;
        auto images = s.add_frame_passes(graph);
        ASSERT_TRUE(images) << images.error().message;
        graph.export_image(images->ldr, readable);
        CompiledGraph compiled = graph.compile();
        ASSERT_TRUE(ctx().submit_and_wait([&](VkCommandBuffer cmd) {
            ASSERT_TRUE(executor.record(compiled, cmd));
            cpu_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }));
        if (frame == 0) settled = ctx().allocator().stats();
    }
    const AllocatorStats steady = ctx().allocator().stats();
    EXPECT_EQ(steady.allocations_made, settled.allocations_made);
    EXPECT_EQ(steady.images_bound, settled.images_bound);
    std::vector<double> sorted(cpu_ms.begin() + 1, cpu_ms.end());
    std::sort(sorted.begin(), sorted.end());
    std::printf("steady frame CPU (build + compile + record), %ux%u MSAA 4 + skybox + tonemap + view: median %.3f ms "
                "over %d frames; first frame %.3f ms; device allocations per steady frame %.2f, images %.2f\n",
                job.frame.width, job.frame.height, sorted[sorted.size() / 2], int(sorted.size()), cpu_ms[0],
                double(steady.allocations_made - settled.allocations_made) / (frames - 1),
                double(steady.images_bound - settled.images_bound) / (frames - 1));
}

}  // namespace
}  // namespace facet
