// The render graph on lavapipe: compute passes chained through images, a mip chain, a
// graphics pass drawing a triangle, timestamps. Results are checked against values
// computed here on the CPU; the fixture fails on any validation message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_executor.h>
#include <facet/graph/graph_run.h>
#include <facet/graph/render_graph.h>
#include <facet/gpu/pipeline.h>
#include <facet/gpu/transfer.h>
#include <facet/shader/compiler.h>
#include "support/gpu_test.h"

namespace facet {
namespace {

constexpr const char* pattern_source = R"(#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2D dst;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(dst)))) return;
    imageStore(dst, p, vec4(p.x, p.y, p.x * 0.5 + p.y * 0.25, 1.0));
}
)";

// Reads `src` through a sampler at texel centres (nearest), writes 2 * src + 1.
constexpr const char* transform_source = R"(#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D src;
layout(binding = 1, rgba32f) uniform writeonly image2D dst;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(dst)))) return;
    imageStore(dst, p, 2.0 * texelFetch(src, p, 0) + 1.0);
}
)";

// Box-filters mip m-1 into mip m (each texel the mean of its 2x2 parents).
constexpr const char* downsample_source = R"(#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D src;
layout(binding = 1, rgba32f) uniform writeonly image2D dst;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(dst)))) return;
    vec4 sum = texelFetch(src, 2 * p, 0) + texelFetch(src, 2 * p + ivec2(1, 0), 0) +
               texelFetch(src, 2 * p + ivec2(0, 1), 0) + texelFetch(src, 2 * p + ivec2(1, 1), 0);
    imageStore(dst, p, sum * 0.25);
}
)";

constexpr const char* triangle_vertex = R"(#version 460
void main() {
    // A triangle covering the lower-left half of the target (clip space, y down).
    vec2 corners[3] = vec2[](vec2(-1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));
    gl_Position = vec4(corners[gl_VertexIndex], 0.0, 1.0);
}
)";

constexpr const char* triangle_fragment = R"(#version 460
layout(location = 0) out vec4 color;
void main() { color = vec4(0.25, 0.5, 1.0, 1.0); }
)";

// Largest difference between add_pattern_then_transform's output and its closed form.
double transform_error(const std::vector<float>& values, uint32_t w, uint32_t h) {
    if (values.size() != size_t(w) * h * 4) return INFINITY;
    double max_error = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float* t = &values[(size_t(y) * w + x) * 4];
            const double expected[4] = {2.0 * x + 1, 2.0 * y + 1, 2 * (x * 0.5 + y * 0.25) + 1, 3.0};
            for (int c = 0; c < 4; ++c) max_error = std::max(max_error, std::abs(t[c] - expected[c]));
        }
    return max_error;
}

const ResourceState readable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                             VK_ACCESS_2_TRANSFER_READ_BIT};

class GraphGpuTest : public test::GpuTest {
protected:
    Pipeline compute(const char* source) {
        auto spirv = compiler_.compile_source(ShaderStage::compute, "test.comp", source);
        EXPECT_TRUE(spirv) << spirv.error().message;
        auto pipeline = Pipeline::compute(ctx(), spirv->words, "test pipeline");
        EXPECT_TRUE(pipeline) << pipeline.error().message;
        return pipeline ? std::move(pipeline).value() : Pipeline{};
    }
    std::vector<float> read_rgba32f(GraphRun& run, ImageHandle h, uint32_t mip, VkImageLayout layout) {
        Image* image = run.transient_image(h);
        EXPECT_NE(image, nullptr);
        auto bytes = test::must(read_image(ctx(), *image, mip, 0, layout));
        std::vector<float> values(bytes.size() / 4);
        std::memcpy(values.data(), bytes.data(), bytes.size());
        return values;
    }
    // Pass "pattern" writes a w x h image from its texel coordinates; pass "transform"
    // samples it and writes 2 * value + 1 into the returned image (exported, readable).
    ImageHandle add_pattern_then_transform(RenderGraph& g, uint32_t w, uint32_t h) {
        pattern_ = compute(pattern_source);
        transform_ = compute(transform_source);
        ImageDesc desc;
        desc.width = w;
        desc.height = h;
        auto a = g.create_image("pattern", desc);
        auto b = g.create_image("transformed", desc);
        g.add_compute_pass("pattern", [&](PassBuilder& pb) { a = pb.write_storage(a); }, [this, a, w, h](PassContext& pc) {
            pattern_.bind(pc.cmd());
            const DescriptorWrite writes[] = {DescriptorWrite::storage_image(pc.view(a))};
            pattern_.push_descriptors(pc.cmd(), writes);
            const auto local = pattern_.workgroup_size();
            vkCmdDispatch(pc.cmd(), group_count(w, local[0]), group_count(h, local[1]), 1);
        });
        g.add_compute_pass("transform", [&](PassBuilder& pb) {
            pb.sample(a);
            b = pb.write_storage(b);
        }, [this, a, b, w, h](PassContext& pc) {
            transform_.bind(pc.cmd());
            const DescriptorWrite writes[] = {DescriptorWrite::sampled_image(pc.view(a), sampler_.handle()),
                                              DescriptorWrite::storage_image(pc.view(b))};
            transform_.push_descriptors(pc.cmd(), writes);
            const auto local = transform_.workgroup_size();
            vkCmdDispatch(pc.cmd(), group_count(w, local[0]), group_count(h, local[1]), 1);
        });
        g.export_image(b, readable);
        return b;
    }

    ShaderCompiler compiler_;
    Sampler sampler_ = test::must(Sampler::create(ctx(), VK_FILTER_NEAREST, false, false, "test nearest"));
    Pipeline pattern_, transform_;
};

TEST_F(GraphGpuTest, ComputeChainMatchesCpu) {
    const uint32_t w = 256, h = 128;  // 32 x 16 workgroups: enough for every lavapipe thread
    RenderGraph g;
    auto b = add_pattern_then_transform(g, w, h);
    CompiledGraph compiled = g.compile();
    auto run = test::must(run_graph(ctx(), compiled));
    auto values = read_rgba32f(*run, b, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    ASSERT_EQ(values.size(), size_t(w) * h * 4);
    double max_error = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float* t = &values[(size_t(y) * w + x) * 4];
            const double expected[4] = {2.0 * x + 1, 2.0 * y + 1, 2 * (x * 0.5 + y * 0.25) + 1, 3.0};
            for (int c = 0; c < 4; ++c) max_error = std::max(max_error, std::abs(t[c] - expected[c]));
        }
    EXPECT_EQ(max_error, 0.0);

    auto timings = run->timings();
    ASSERT_EQ(timings.size(), 2u);
    EXPECT_EQ(timings[0].name, "pattern");
    for (const PassTiming& t : timings) {
        EXPECT_GE(t.time_ms, 0.0);
        EXPECT_TRUE(std::isfinite(t.time_ms));
    }
}

TEST_F(GraphGpuTest, MipChainPassesReadThePreviousLevel) {
    const uint32_t size = 64, mips = 4;
    Pipeline pattern = compute(pattern_source);
    Pipeline downsample = compute(downsample_source);
    ImageDesc desc;
    desc.width = desc.height = size;
    desc.mip_levels = mips;
    RenderGraph g;
    auto chain = g.create_image("chain", desc);
    g.add_compute_pass("mip 0", [&](PassBuilder& pb) { chain = pb.write_storage(chain, ImageRange::mip(0)); },
                       [&, handle = chain](PassContext& pc) {
                           pattern.bind(pc.cmd());
                           const DescriptorWrite writes[] = {
                               DescriptorWrite::storage_image(pc.view(handle, ImageRange::mip(0)))};
                           pattern.push_descriptors(pc.cmd(), writes);
                           const auto local = pattern.workgroup_size();
                           vkCmdDispatch(pc.cmd(), group_count(size, local[0]), group_count(size, local[1]), 1);
                       });
    for (uint32_t m = 1; m < mips; ++m) {
        g.add_compute_pass("mip " + std::to_string(m), [&, m](PassBuilder& pb) {
            pb.sample(chain, ImageRange::mip(m - 1));
            chain = pb.write_storage(chain, ImageRange::mip(m));
        }, [&, m, handle = chain](PassContext& pc) {
            downsample.bind(pc.cmd());
            const DescriptorWrite writes[] = {
                DescriptorWrite::sampled_image(pc.view(handle, ImageRange::mip(m - 1)), sampler_.handle()),
                DescriptorWrite::storage_image(pc.view(handle, ImageRange::mip(m)))};
            downsample.push_descriptors(pc.cmd(), writes);
            const auto local = downsample.workgroup_size();
            vkCmdDispatch(pc.cmd(), group_count(size >> m, local[0]), group_count(size >> m, local[1]), 1);
        });
    }
    g.export_image(chain, readable);
    CompiledGraph compiled = g.compile();
    auto run = test::must(run_graph(ctx(), compiled));
    // The mean of a linear pattern over a block is its value at the block centre.
    for (uint32_t m = 0; m < mips; ++m) {
        auto values = read_rgba32f(*run, chain, m, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        const uint32_t n = size >> m;
        ASSERT_EQ(values.size(), size_t(n) * n * 4);
        double max_error = 0;
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) {
                const double cx = x * double(1 << m) + ((1 << m) - 1) / 2.0;
                const double cy = y * double(1 << m) + ((1 << m) - 1) / 2.0;
                const float* t = &values[(size_t(y) * n + x) * 4];
                max_error = std::max({max_error, std::abs(t[0] - cx), std::abs(t[1] - cy),
                                      std::abs(t[2] - (cx * 0.5 + cy * 0.25))});
            }
        EXPECT_LT(max_error, 1e-4) << "mip " << m;
    }
}

TEST_F(GraphGpuTest, GraphicsPassClearsAndDrawsATriangle) {
    const uint32_t w = 64, h = 64;
    auto vs = compiler_.compile_source(ShaderStage::vertex, "triangle.vert", triangle_vertex);
    auto fs = compiler_.compile_source(ShaderStage::fragment, "triangle.frag", triangle_fragment);
    ASSERT_TRUE(vs && fs);
    Pipeline::GraphicsDesc pd;
    pd.vertex_spirv = vs->words;
    pd.fragment_spirv = fs->words;
    pd.color_formats = {VK_FORMAT_R8G8B8A8_UNORM};
    auto built = Pipeline::graphics(ctx(), pd, "triangle");
    ASSERT_TRUE(built) << built.error().message;
    Pipeline triangle = std::move(built).value();
    ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.width = w;
    desc.height = h;
    RenderGraph g;
    auto target = g.create_image("target", desc);
    g.add_graphics_pass("draw", [&](PassBuilder& pb) { target = pb.color_attachment(target); },
                        [&, handle = target](PassContext& pc) {
                            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
                            color.imageView = pc.view(handle);
                            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
                            color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
                            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
                            color.clearValue.color = {{1.0f, 0.0f, 0.0f, 1.0f}};
                            VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                            info.renderArea = {{0, 0}, {w, h}};
                            info.layerCount = 1;
                            info.colorAttachmentCount = 1;
                            info.pColorAttachments = &color;
                            vkCmdBeginRendering(pc.cmd(), &info);
                            VkViewport viewport{0, 0, float(w), float(h), 0, 1};
                            VkRect2D scissor{{0, 0}, {w, h}};
                            vkCmdSetViewport(pc.cmd(), 0, 1, &viewport);
                            vkCmdSetScissor(pc.cmd(), 0, 1, &scissor);
                            triangle.bind(pc.cmd());
                            vkCmdDraw(pc.cmd(), 3, 1, 0, 0);
                            vkCmdEndRendering(pc.cmd());
                        });
    g.export_image(target, readable);
    CompiledGraph compiled = g.compile();
    auto run = test::must(run_graph(ctx(), compiled));
    auto bytes = test::must(read_image(ctx(), *run->transient_image(target), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
    ASSERT_EQ(bytes.size(), size_t(w) * h * 4);
    auto pixel = [&](uint32_t x, uint32_t y) {
        const auto* p = reinterpret_cast<const uint8_t*>(bytes.data()) + (size_t(y) * w + x) * 4;
        return std::array<int, 4>{p[0], p[1], p[2], p[3]};
    };
    const std::array<int, 4> blue{64, 128, 255, 255}, red{255, 0, 0, 255};
    // The diagonal runs from the top-left to the bottom-right corner: below it is inside.
    EXPECT_EQ(pixel(2, 60), blue);
    EXPECT_EQ(pixel(10, 40), blue);
    EXPECT_EQ(pixel(60, 2), red);
    EXPECT_EQ(pixel(40, 10), red);
    int inside = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) inside += pixel(x, y) == blue;
    EXPECT_NEAR(inside, w * h / 2, w);  // half the target, give or take the diagonal
}

// Progress mode: one submission per pass, same results, barriers still honoured across
// submissions (the fixture fails on any synchronization-validation message).
TEST_F(GraphGpuTest, PerPassSubmissionsReportProgress) {
    const uint32_t w = 64, h = 32;
    RenderGraph g;
    auto b = add_pattern_then_transform(g, w, h);
    CompiledGraph compiled = g.compile();
    GraphRun run(ctx(), compiled);
    std::vector<std::string> reported;
    ASSERT_TRUE(run.submit_and_wait([&](uint32_t done, uint32_t total, const std::string& pass) {
        EXPECT_EQ(total, 2u);
        EXPECT_EQ(done, reported.size() + 1);
        reported.push_back(pass);
    }));
    EXPECT_EQ(reported, (std::vector<std::string>{"pattern", "transform"}));
    auto values = read_rgba32f(run, b, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    EXPECT_EQ(values[(7 * w + 5) * 4 + 0], 2.0f * 5 + 1);
    EXPECT_EQ(values[(7 * w + 5) * 4 + 1], 2.0f * 7 + 1);
    EXPECT_EQ(run.timings().size(), 2u);
}

TEST_F(GraphGpuTest, HostRecordedCommandBuffer) {
    Pipeline pattern = compute(pattern_source);
    ImageDesc desc;
    desc.width = desc.height = 16;
    RenderGraph g;
    auto a = g.create_image("pattern", desc);
    g.add_compute_pass("pattern", [&](PassBuilder& pb) { a = pb.write_storage(a); }, [&](PassContext& pc) {
        pattern.bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_image(pc.view(a))};
        pattern.push_descriptors(pc.cmd(), writes);
        const auto local = pattern.workgroup_size();
        vkCmdDispatch(pc.cmd(), group_count(16, local[0]), group_count(16, local[1]), 1);
    });
    g.export_image(a, readable);
    CompiledGraph compiled = g.compile();
    GraphRun run(ctx(), compiled);
    test::must(ctx().submit_and_wait([&](VkCommandBuffer cmd) { test::must(run.record(cmd)); }));  // the host's buffer
    auto values = read_rgba32f(run, a, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    EXPECT_EQ(values[(5 * 16 + 3) * 4 + 0], 3.0f);
    EXPECT_EQ(values[(5 * 16 + 3) * 4 + 1], 5.0f);
    EXPECT_EQ(run.timings().size(), 1u);
    EXPECT_THROW((void)run.record(VK_NULL_HANDLE), UsageError);
}

// Frames of the same shape in two slots: after each slot's first frame, no allocation and
// no image creation (the allocator's running totals stay put), and each slot keeps its own
// images (two frames in flight must not share them).
TEST_F(GraphGpuTest, ExecutorSteadyFramesCreateNoImagesAndAllocateNothing) {
    const uint32_t w = 64, h = 32;
    GraphExecutor executor(ctx(), 2);
    AllocatorStats settled{};
    ImageHandle last;
    std::vector<std::unique_ptr<RenderGraph>> graphs;  // each slot's graph outlives its run
    std::vector<CompiledGraph> compiled(2);
    for (uint32_t frame = 0; frame < 8; ++frame) {
        const uint32_t slot = frame % 2;
        auto graph = std::make_unique<RenderGraph>();
        last = add_pattern_then_transform(*graph, w, h);
        compiled[slot] = graph->compile();
        if (graphs.size() < 2) graphs.push_back(std::move(graph));
        else graphs[slot] = std::move(graph);
        auto run = executor.submit_and_wait(compiled[slot], slot);
        ASSERT_TRUE(run) << run.error().message;
        if (frame == 1) settled = ctx().allocator().stats();
    }
    const AllocatorStats steady = ctx().allocator().stats();
    EXPECT_EQ(steady.allocations_made, settled.allocations_made);
    EXPECT_EQ(steady.images_bound, settled.images_bound);
    EXPECT_EQ(steady.live_allocations, settled.live_allocations);
    EXPECT_NE(executor.run(0)->image(last), executor.run(1)->image(last));
    EXPECT_EQ(transform_error(read_rgba32f(*executor.run(1), last, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL), w, h), 0.0);

    // Another shape in slot 0: its two images are new (the counter does count).
    const uint64_t images_before = ctx().allocator().stats().images_bound;
    RenderGraph other;
    auto b = add_pattern_then_transform(other, w / 2, h);
    CompiledGraph other_compiled = other.compile();
    ASSERT_TRUE(executor.submit_and_wait(other_compiled, 0));
    EXPECT_EQ(ctx().allocator().stats().images_bound, images_before + 2);
    EXPECT_EQ(transform_error(read_rgba32f(*executor.run(0), b, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL), w / 2, h),
              0.0);
    EXPECT_THROW(executor.prepare(other_compiled, 2), UsageError);
}

// A result leaves the graph: the caller owns the image after the executor and its graph
// are gone, and the slot's next frame creates a replacement.
TEST_F(GraphGpuTest, ExecutorDetachesAnExportedImage) {
    const uint32_t w = 32, h = 16;
    Image kept;
    {
        GraphExecutor executor(ctx());
        RenderGraph g;
        auto b = add_pattern_then_transform(g, w, h);
        CompiledGraph compiled = g.compile();
        ASSERT_TRUE(executor.submit_and_wait(compiled));
        auto detached = executor.detach_image(b);
        ASSERT_TRUE(detached) << detached.error().message;
        kept = std::move(*detached);
        EXPECT_EQ(executor.run()->transient_image(b), nullptr);
        EXPECT_FALSE(executor.detach_image(b));  // already taken
        const uint64_t images_before = ctx().allocator().stats().images_bound;
        ASSERT_TRUE(executor.submit_and_wait(compiled));
        EXPECT_EQ(ctx().allocator().stats().images_bound, images_before + 1);
    }
    ASSERT_TRUE(kept);
    auto bytes = test::must(read_image(ctx(), kept, 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
    std::vector<float> values(bytes.size() / 4);
    std::memcpy(values.data(), bytes.data(), bytes.size());
    EXPECT_EQ(transform_error(values, w, h), 0.0);
}

}  // namespace
}  // namespace facet
