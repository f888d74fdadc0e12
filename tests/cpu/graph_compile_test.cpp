// RenderGraph::compile() is pure: these tests run without any GPU.
#include <gtest/gtest.h>

#include <facet/core/result.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/render_graph.h>

namespace facet {
namespace {

ImageDesc rgba(uint32_t size, uint32_t mips = 1) {
    ImageDesc d;
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = d.height = size;
    d.mip_levels = mips;
    return d;
}

std::vector<std::string> order_of(const CompiledGraph& g) {
    std::vector<std::string> names;
    for (const CompiledPass& p : g.passes) names.push_back(g.graph->passes()[p.pass].name);
    return names;
}

const CompiledPass& pass_named(const CompiledGraph& g, const std::string& name) {
    for (const CompiledPass& p : g.passes)
        if (g.graph->passes()[p.pass].name == name) return p;
    throw std::runtime_error("no pass " + name);
}

template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const UsageError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(GraphCompile, CullsPassesThatContributeNothing) {
    RenderGraph g;
    auto a = g.create_image("a", rgba(8));
    auto unused = g.create_image("unused", rgba(8));
    g.add_compute_pass("write a", [&](PassBuilder& b) { a = b.write_storage(a); }, {});
    g.add_compute_pass("dead end", [&](PassBuilder& b) {
        b.sample(a);
        unused = b.write_storage(unused);
    }, {});
    g.add_compute_pass("logger", [&](PassBuilder& b) { b.side_effect(); }, {});
    g.export_image(a);
    CompiledGraph c = g.compile();
    EXPECT_EQ(order_of(c), (std::vector<std::string>{"write a", "logger"}));
    ASSERT_EQ(c.culled.size(), 1u);
    EXPECT_EQ(g.passes()[c.culled[0]].name, "dead end");
    EXPECT_FALSE(c.lifetimes[unused.index].used());
}

TEST(GraphCompile, NothingExportedMeansNothingRuns) {
    RenderGraph g;
    auto a = g.create_image("a", rgba(8));
    g.add_compute_pass("write a", [&](PassBuilder& b) { a = b.write_storage(a); }, {});
    EXPECT_TRUE(g.compile().passes.empty());
}

TEST(GraphCompile, OrdersByDependenciesThenDeclaration) {
    RenderGraph g;
    auto x = g.create_image("x", rgba(8));
    auto y = g.create_image("y", rgba(8));
    const uint32_t first = g.add_compute_pass("first declared", [&](PassBuilder& b) { x = b.write_storage(x); }, {});
    const uint32_t second = g.add_compute_pass("second declared", [&](PassBuilder& b) { y = b.write_storage(y); }, {});
    g.export_image(x);
    g.export_image(y);
    EXPECT_EQ(order_of(g.compile()), (std::vector<std::string>{"first declared", "second declared"}));
    g.add_dependency(second, first);
    EXPECT_EQ(order_of(g.compile()), (std::vector<std::string>{"second declared", "first declared"}));
}

TEST(GraphCompile, ReadAfterWriteBarrierAndLayouts) {
    RenderGraph g;
    auto img = g.create_image("img", rgba(16));
    auto out = g.create_image("out", rgba(16));
    g.add_compute_pass("produce", [&](PassBuilder& b) { img = b.write_storage(img); }, {});
    g.add_compute_pass("consume", [&](PassBuilder& b) {
        b.sample(img);
        out = b.write_storage(out);
    }, {});
    g.export_image(out);
    CompiledGraph c = g.compile();
    ASSERT_EQ(c.passes.size(), 2u);

    // First use of a transient: from UNDEFINED, nothing to wait for.
    const auto& first = pass_named(c, "produce").barriers_before.images;
    ASSERT_EQ(first.size(), 1u);
    EXPECT_EQ(first[0].old_layout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(first[0].new_layout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(first[0].src_stages, VK_PIPELINE_STAGE_2_NONE);
    EXPECT_EQ(first[0].dst_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

    const auto& second = pass_named(c, "consume").barriers_before.images;
    ASSERT_EQ(second.size(), 2u);
    const ImageBarrier& raw = second[0];
    EXPECT_EQ(c.physical_images[raw.physical].name, "img");
    EXPECT_EQ(raw.old_layout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(raw.new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(raw.src_stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(raw.src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(raw.dst_stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(raw.dst_access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

TEST(GraphCompile, BufferWriteAfterReadIsAnExecutionDependencyOnly) {
    RenderGraph g;
    auto buf = g.create_buffer("buf", {256});
    auto sink = g.create_buffer("sink", {256});
    g.add_compute_pass("write 1", [&](PassBuilder& b) { buf = b.write(buf); }, {});
    g.add_compute_pass("read", [&](PassBuilder& b) {
        b.read(buf);
        sink = b.write(sink);
    }, {});
    g.add_compute_pass("write 2", [&](PassBuilder& b) { buf = b.write(buf); }, {});
    g.export_buffer(buf);
    g.export_buffer(sink);
    CompiledGraph c = g.compile();
    EXPECT_EQ(order_of(c), (std::vector<std::string>{"write 1", "read", "write 2"}));
    EXPECT_TRUE(pass_named(c, "write 1").barriers_before.empty()) << "a fresh buffer needs no barrier";

    const auto& raw = pass_named(c, "read").barriers_before.buffers;
    ASSERT_EQ(raw.size(), 1u);
    EXPECT_EQ(raw[0].src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(raw[0].dst_access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);

    const auto& war = pass_named(c, "write 2").barriers_before.buffers;
    ASSERT_EQ(war.size(), 1u);
    EXPECT_EQ(war[0].src_stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(war[0].src_access, VK_ACCESS_2_NONE) << "reads need no availability";
    EXPECT_EQ(war[0].dst_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST(GraphCompile, WriteAfterWriteIsAMemoryDependency) {
    RenderGraph g;
    auto buf = g.create_buffer("buf", {64});
    g.add_compute_pass("first", [&](PassBuilder& b) { buf = b.write(buf); }, {});
    g.add_transfer_pass("second", [&](PassBuilder& b) { buf = b.write(buf, Access::transfer_dst); }, {});
    g.export_buffer(buf);
    CompiledGraph c = g.compile();
    const auto& waw = pass_named(c, "second").barriers_before.buffers;
    ASSERT_EQ(waw.size(), 1u);
    EXPECT_EQ(waw[0].src_stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(waw[0].src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(waw[0].dst_stages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    EXPECT_EQ(waw[0].dst_access, VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

TEST(GraphCompile, ReadsAlreadyVisibleNeedNoSecondBarrier) {
    RenderGraph g;
    auto img = g.create_image("img", rgba(8));
    auto o1 = g.create_image("o1", rgba(8));
    auto o2 = g.create_image("o2", rgba(8));
    g.add_compute_pass("write", [&](PassBuilder& b) { img = b.write_storage(img); }, {});
    g.add_compute_pass("read 1", [&](PassBuilder& b) {
        b.sample(img);
        o1 = b.write_storage(o1);
    }, {});
    g.add_compute_pass("read 2", [&](PassBuilder& b) {
        b.sample(img);
        o2 = b.write_storage(o2);
    }, {});
    g.export_image(o1);
    g.export_image(o2);
    CompiledGraph c = g.compile();
    for (const ImageBarrier& b : pass_named(c, "read 2").barriers_before.images)
        EXPECT_NE(c.physical_images[b.physical].name, "img");
}

TEST(GraphCompile, AttachmentToSampledTransition) {
    RenderGraph g;
    auto color = g.create_image("color", rgba(32));
    auto out = g.create_image("out", rgba(32));
    g.add_graphics_pass("draw", [&](PassBuilder& b) { color = b.color_attachment(color); }, {});
    g.add_compute_pass("post", [&](PassBuilder& b) {
        b.sample(color);
        out = b.write_storage(out);
    }, {});
    g.export_image(out);
    CompiledGraph c = g.compile();
    const auto& first = pass_named(c, "draw").barriers_before.images;
    ASSERT_EQ(first.size(), 1u);
    EXPECT_EQ(first[0].new_layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    const ImageBarrier& b = pass_named(c, "post").barriers_before.images.at(0);
    EXPECT_EQ(b.old_layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(b.new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(b.src_stages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
    EXPECT_EQ(b.src_access & VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
}

TEST(GraphCompile, MipChainBarriersPerSubresource) {
    RenderGraph g;
    auto chain = g.create_image("chain", rgba(64, 4));
    g.add_compute_pass("mip 0", [&](PassBuilder& b) { chain = b.write_storage(chain, ImageRange::mip(0)); }, {});
    for (uint32_t m = 1; m < 4; ++m)
        g.add_compute_pass("mip " + std::to_string(m), [&, m](PassBuilder& b) {
            b.sample(chain, ImageRange::mip(m - 1));
            chain = b.write_storage(chain, ImageRange::mip(m));
        }, {});
    g.export_image(chain, {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                           VK_ACCESS_2_SHADER_SAMPLED_READ_BIT});
    CompiledGraph c = g.compile();
    ASSERT_EQ(c.passes.size(), 4u);
    for (uint32_t m = 1; m < 4; ++m) {
        const auto& bs = c.passes[m].barriers_before.images;
        ASSERT_EQ(bs.size(), 2u) << "pass " << m;
        EXPECT_EQ(bs[0].range.baseMipLevel, m - 1);
        EXPECT_EQ(bs[0].range.levelCount, 1u);
        EXPECT_EQ(bs[0].old_layout, VK_IMAGE_LAYOUT_GENERAL);
        EXPECT_EQ(bs[0].new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        EXPECT_EQ(bs[0].src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        EXPECT_EQ(bs[1].range.baseMipLevel, m);
        EXPECT_EQ(bs[1].old_layout, VK_IMAGE_LAYOUT_UNDEFINED);
        EXPECT_EQ(bs[1].new_layout, VK_IMAGE_LAYOUT_GENERAL);
    }
    // At the end mips 0..2 are already readable; only mip 3 moves, and one merged
    // barrier makes 0..2 visible to the fragment stage.
    const auto& fin = c.final_barriers.images;
    ASSERT_EQ(fin.size(), 2u);
    EXPECT_EQ(fin[0].range.baseMipLevel, 0u);
    EXPECT_EQ(fin[0].range.levelCount, 3u);
    EXPECT_EQ(fin[0].old_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(fin[1].range.baseMipLevel, 3u);
    EXPECT_EQ(fin[1].old_layout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(fin[1].new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(fin[1].dst_stages, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
}

TEST(GraphCompile, ImportedImageCarriesItsStatesInAndOut) {
    RenderGraph g;
    ImportedImage host;
    host.image = reinterpret_cast<VkImage>(uintptr_t(0x1234));
    host.desc = rgba(16);
    host.initial = {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    host.final = {VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};
    auto swap = g.import_image("swapchain", host);
    g.add_compute_pass("fill", [&](PassBuilder& b) { swap = b.write_storage(swap); }, {});
    CompiledGraph c = g.compile();  // writing an imported image keeps the pass alive
    ASSERT_EQ(c.passes.size(), 1u);
    const ImageBarrier& in = c.passes[0].barriers_before.images.at(0);
    EXPECT_EQ(in.old_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(in.src_stages, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    EXPECT_EQ(in.new_layout, VK_IMAGE_LAYOUT_GENERAL);
    ASSERT_EQ(c.final_barriers.images.size(), 1u);
    const ImageBarrier& out = c.final_barriers.images[0];
    EXPECT_EQ(out.old_layout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(out.new_layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    EXPECT_EQ(out.src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST(GraphCompile, StaleHandleNamesPassAndResource) {
    RenderGraph g;
    auto v0 = g.create_image("albedo", rgba(8));
    auto v1 = v0;
    g.add_compute_pass("writer", [&](PassBuilder& b) { v1 = b.write_storage(v0); }, {});
    g.add_compute_pass("overwriter", [&](PassBuilder& b) { b.write_storage(v1); }, {});
    const std::string message =
        error_of([&] { g.add_compute_pass("late reader", [&](PassBuilder& b) { b.sample(v1); }, {}); });
    EXPECT_NE(message.find("late reader"), std::string::npos) << message;
    EXPECT_NE(message.find("albedo"), std::string::npos) << message;
    EXPECT_NE(message.find("stale"), std::string::npos) << message;
}

TEST(GraphCompile, ReadingAnUnwrittenResourceNamesPassAndResource) {
    RenderGraph g;
    auto never = g.create_buffer("never written", {16});
    const std::string message = error_of([&] { g.add_compute_pass("reader", [&](PassBuilder& b) { b.read(never); }, {}); });
    EXPECT_NE(message.find("reader"), std::string::npos) << message;
    EXPECT_NE(message.find("never written"), std::string::npos) << message;
}

TEST(GraphCompile, CyclesAreRejectedWithThePassNames) {
    RenderGraph g;
    auto x = g.create_image("x", rgba(8));
    auto y = g.create_image("y", rgba(8));
    const uint32_t a = g.add_compute_pass("pass a", [&](PassBuilder& b) { x = b.write_storage(x); }, {});
    const uint32_t b2 = g.add_compute_pass("pass b", [&](PassBuilder& b) {
        b.sample(x);
        y = b.write_storage(y);
    }, {});
    g.export_image(y);
    g.add_dependency(b2, a);
    const std::string message = error_of([&] { g.compile(); });
    EXPECT_NE(message.find("cycle"), std::string::npos) << message;
    EXPECT_NE(message.find("pass a"), std::string::npos) << message;
    EXPECT_NE(message.find("pass b"), std::string::npos) << message;

    RenderGraph self;
    auto z = self.create_image("z", rgba(8));
    self.add_compute_pass("reads its own output", [&](PassBuilder& b) {
        auto z1 = b.write_storage(z);
        b.sample(z1);
    }, {});
    self.export_image(z);
    const std::string self_message = error_of([&] { self.compile(); });
    EXPECT_NE(self_message.find("reads its own output"), std::string::npos) << self_message;
}

TEST(GraphCompile, AccessMustFitThePassKind) {
    RenderGraph g;
    auto img = g.create_image("img", rgba(8));
    const std::string message =
        error_of([&] { g.add_compute_pass("compute", [&](PassBuilder& b) { b.color_attachment(img); }, {}); });
    EXPECT_NE(message.find("colour attachment"), std::string::npos) << message;
    auto range = error_of([&] { g.add_compute_pass("oob", [&](PassBuilder& b) { b.write_storage(img, ImageRange::mip(3)); }, {}); });
    EXPECT_NE(range.find("outside"), std::string::npos) << range;
}

TEST(GraphCompile, LifetimesAndPhysicalSharing) {
    RenderGraph g;
    auto t1 = g.create_image("t1", rgba(32));
    auto t2 = g.create_image("t2", rgba(32));
    auto other = g.create_image("other format", [] {
        ImageDesc d = rgba(32);
        d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        return d;
    }());
    auto out = g.create_buffer("out", {64});
    g.add_compute_pass("make t1", [&](PassBuilder& b) { t1 = b.write_storage(t1); }, {});
    g.add_compute_pass("use t1", [&](PassBuilder& b) {
        b.sample(t1);
        out = b.write(out);
    }, {});
    g.add_compute_pass("make t2", [&](PassBuilder& b) { t2 = b.write_storage(t2); }, {});
    g.add_compute_pass("make other", [&](PassBuilder& b) { other = b.write_storage(other); }, {});
    g.add_compute_pass("use t2", [&](PassBuilder& b) {
        b.sample(t2);
        b.sample(other);
        out = b.write(out);
    }, {});
    g.export_buffer(out);
    CompiledGraph c = g.compile();
    EXPECT_EQ(c.lifetimes[t1.index].first, 0u);
    EXPECT_EQ(c.lifetimes[t1.index].last, 1u);
    EXPECT_EQ(c.lifetimes[t2.index].first, 2u);
    EXPECT_EQ(c.lifetimes[t2.index].last, 4u);
    EXPECT_EQ(c.physical_of[t1.index], c.physical_of[t2.index]) << "same description, disjoint lifetimes";
    EXPECT_NE(c.physical_of[other.index], c.physical_of[t1.index]);
    EXPECT_EQ(c.physical_images.size(), 2u);
    // The second tenant starts from UNDEFINED and waits for the first tenant's last read.
    const ImageBarrier& b = pass_named(c, "make t2").barriers_before.images.at(0);
    EXPECT_EQ(b.old_layout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(b.src_stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

TEST(GraphCompile, DumpsNameEveryPass) {
    RenderGraph g;
    auto a = g.create_image("sky", rgba(8));
    g.add_compute_pass("procedural sky", [&](PassBuilder& b) { a = b.write_storage(a); }, {});
    g.add_compute_pass("culled one", [&](PassBuilder&) {}, {});
    g.export_image(a);
    CompiledGraph c = g.compile();
    const std::string text = c.to_text();
    EXPECT_NE(text.find("pass 'procedural sky'"), std::string::npos) << text;
    EXPECT_NE(text.find("culled: 'culled one'"), std::string::npos) << text;
    EXPECT_NE(text.find("UNDEFINED -> GENERAL"), std::string::npos) << text;
    const std::string dot = c.to_dot();
    EXPECT_EQ(dot.rfind("digraph", 0), 0u);
    EXPECT_NE(dot.find("\"pass:procedural sky\" -> \"res:sky v1\""), std::string::npos) << dot;
}

}  // namespace
}  // namespace facet
