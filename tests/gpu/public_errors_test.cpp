// No exception crosses the public API: a failure the device causes (out of memory, a
// lost device, a GPU that never finishes) comes back from every public call as an Error
// carrying its VkResult and naming the failure. Each fault site (facet/gpu/faults.h) is
// fired while one public call runs, on a validated context of the test's own; the call
// must not throw, must fail, the context must report no validation message, and it must
// still be destroyable without leaving a Vulkan object behind.
#include <gtest/gtest.h>

#include <cstring>

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <unistd.h>
#include <vector>

#include <facet/gpu/context.h>
#include <facet/gpu/memory.h>
#include <facet/gpu/resources.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/graph_executor.h>
#include <facet/graph/render_graph.h>
#include <facet/ibl/baked_environment.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/render/forward_renderer.h>
#include <facet/render/gpu_scene.h>
#include <facet/render/render_job.h>
#include <facet/scene/builtin_scenes.h>
#include <facet/shader/program_cache.h>
#include "gpu/fault_injection.h"
#include "support/gpu_test.h"
#include "support/tiny_session.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

struct Fault {
    FaultSite site;
    VkResult expected;
    const char* names;  // what the message must say, besides the VkResult's name
};

const Fault kMemory{FaultSite::memory, VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory"};
const Fault kDeviceLost{FaultSite::submit, VK_ERROR_DEVICE_LOST, "vkQueueSubmit2"};
// Long enough for the set-up's real work on a loaded CPU device, short enough to wait for.
constexpr uint64_t kFenceTimeoutMs = 1500;
const Fault kHang{FaultSite::hang, VK_TIMEOUT, "timed out after 1500 ms"};

std::string fault_name(const ::testing::TestParamInfo<Fault>& info) {
    switch (info.param.site) {
        case FaultSite::memory: return "OutOfDeviceMemory";
        case FaultSite::submit: return "DeviceLost";
        case FaultSite::hang: return "Hang";
        case FaultSite::pipeline: return "Pipeline";
    }
    return "unknown";
}

BakeSettings tiny_bake() {
    BakeSettings b;
    b.ibl.cube_size = 16;
    b.ibl.irradiance.size = 8;
    b.ibl.irradiance.source_size = 8;
    b.ibl.specular.levels = 4;
    b.ibl.specular.sample_count = 64;
    b.ibl.lut.size = 16;
    b.ibl.lut.sample_count = 64;
    return b;
}

// A context of the test's own with a short fence timeout (the hang fault waits for it);
// on teardown: no validation message, and destroying it leaves no object behind.
class PublicErrors : public ::testing::TestWithParam<Fault> {
protected:
    void SetUp() override {
        clear_injected_faults();
        process_messages_before_ = Context::process_validation_message_count();
        ContextOptions options = test::context_options();
        options.fence_timeout_ms = kFenceTimeoutMs;
        auto created = test::create_context(options);
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created).value();
    }
    void TearDown() override {
        clear_injected_faults();
        if (!context_) return;
        EXPECT_EQ(context_->validation_message_count(), 0u) << "validation messages printed above";
        EXPECT_NO_THROW(context_.reset());
        EXPECT_EQ(Context::process_validation_message_count(), process_messages_before_)
            << "objects left behind (printed above)";
    }
    Context& ctx() { return *context_; }
    // Arms the test's fault at the next call of its kind.
    void arm() { inject_fault(GetParam().site); }

    // The call failed with the fault's VkResult and says what failed.
    template <class T>
    void expect_failed(const Result<T>& result, const char* call) {
        const Fault f = GetParam();
        ASSERT_FALSE(result.ok()) << call << " succeeded although " << vk_result_name(f.expected) << " was injected";
        const std::string& message = result.error().message;
        EXPECT_EQ(result.error().vk_result, f.expected) << call << ": " << message;
        EXPECT_NE(message.find(f.names), std::string::npos) << call << ": " << message;
        EXPECT_NE(message.find(vk_result_name(f.expected)), std::string::npos) << call << ": " << message;
    }

    std::unique_ptr<Context> context_;
    uint32_t process_messages_before_ = 0;
};

// Device-local buffers and images: uploads and readbacks stage and submit.
Buffer device_buffer(Context& context, VkDeviceSize bytes) {
    return test::must(Buffer::create(context, bytes,
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     MemoryUsage::gpu_only, "test buffer"));
}

Image device_image(Context& context) {
    ImageDesc desc;
    desc.width = desc.height = 4;
    return test::must(
        Image::create(context, desc, VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test image"));
}

// ---- allocation: only the memory fault reaches it ----

class AllocationErrors : public PublicErrors {};

TEST_P(AllocationErrors, BufferCreate) {
    arm();
    Result<Buffer> buffer = Buffer{};
    EXPECT_NO_THROW(buffer = Buffer::create(ctx(), 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::gpu_only,
                                            "doomed buffer"));
    expect_failed(buffer, "Buffer::create");
    EXPECT_NE(buffer.error().message.find("doomed buffer"), std::string::npos) << buffer.error().message;
    EXPECT_EQ(ctx().allocator().stats().live_allocations, 0u);
}

TEST_P(AllocationErrors, ImageCreate) {
    arm();
    ImageDesc desc;
    desc.width = desc.height = 64;
    Result<Image> image = Image{};
    EXPECT_NO_THROW(image = Image::create(ctx(), desc, VK_IMAGE_USAGE_SAMPLED_BIT, "doomed image"));
    expect_failed(image, "Image::create");
    EXPECT_NE(image.error().message.find("doomed image"), std::string::npos) << image.error().message;
    EXPECT_EQ(ctx().allocator().stats().live_allocations, 0u);
}

TEST_P(AllocationErrors, AllocatorAllocate) {
    arm();
    VkMemoryRequirements requirements{};
    requirements.size = 1024;
    requirements.alignment = 256;
    requirements.memoryTypeBits = ~0u;
    Result<Allocation> allocation = Allocation{};
    EXPECT_NO_THROW(allocation = ctx().allocator().allocate(requirements, MemoryUsage::gpu_only));
    expect_failed(allocation, "Allocator::allocate");
}

TEST_P(AllocationErrors, GpuSceneAndForwardRendererCreate) {
    const Scene scene = test::must(builtin_scene("builtin:spheres"));
    arm();
    Result<std::unique_ptr<GpuScene>> gpu_scene = std::unique_ptr<GpuScene>();
    EXPECT_NO_THROW(gpu_scene = GpuScene::create(ctx(), scene));
    expect_failed(gpu_scene, "GpuScene::create");

    ShaderCompiler compiler;
    ProgramCache programs(ctx(), compiler);
    arm();
    Result<std::unique_ptr<ForwardRenderer>> renderer = std::unique_ptr<ForwardRenderer>();
    EXPECT_NO_THROW(renderer = ForwardRenderer::create(ctx(), programs));
    expect_failed(renderer, "ForwardRenderer::create");
}

INSTANTIATE_TEST_SUITE_P(Sites, AllocationErrors, ::testing::Values(kMemory), fault_name);

// ---- submissions: a lost device and a hang ----

class SubmitErrors : public PublicErrors {};

TEST_P(SubmitErrors, ContextSubmitAndWait) {
    Buffer buffer = device_buffer(ctx(), 256);
    arm();
    Status done = Ok{};
    EXPECT_NO_THROW(done = ctx().submit_and_wait(
                        [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 0, 256, 7); }, "a fill"));
    expect_failed(done, "Context::submit_and_wait");
    // The context takes no more work, and says so at once.
    Status again = Ok{};
    EXPECT_NO_THROW(again = ctx().submit_and_wait(
                        [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer.handle(), 0, 256, 7); }, "a fill"));
    EXPECT_FALSE(again.ok());
    EXPECT_EQ(again.error().vk_result, GetParam().expected) << again.error().message;
}

INSTANTIATE_TEST_SUITE_P(Sites, SubmitErrors, ::testing::Values(kDeviceLost, kHang), fault_name);

// ---- everything else: every fault ----

class EveryFault : public PublicErrors {};

// A device whose device-local memory is host-visible (lavapipe) maps every buffer: then
// upload_buffer and read_buffer copy on the host, reach no fault site and must succeed
// with the right bytes although a fault is armed; elsewhere they stage and submit, and
// must fail with the fault.
TEST_P(EveryFault, UploadBuffer) {
    std::vector<uint32_t> data(64);
    for (uint32_t i = 0; i < data.size(); ++i) data[i] = 7u * i + 1u;
    Buffer buffer = device_buffer(ctx(), data.size() * 4);
    arm();
    Status uploaded = Ok{};
    EXPECT_NO_THROW(uploaded = upload_buffer(ctx(), buffer, std::as_bytes(std::span(data))));
    if (!buffer.mapped()) {
        expect_failed(uploaded, "upload_buffer");
        return;
    }
    ASSERT_TRUE(uploaded.ok()) << "a host copy failed: " << uploaded.error().message;
    clear_injected_faults();
    auto read = read_buffer(ctx(), buffer);
    ASSERT_TRUE(read.ok()) << read.error().message;
    ASSERT_EQ(read->size(), data.size() * 4);
    EXPECT_EQ(std::memcmp(read->data(), data.data(), read->size()), 0) << "the host copy changed the bytes";
}

TEST_P(EveryFault, ReadBuffer) {
    std::vector<uint32_t> data(64);
    for (uint32_t i = 0; i < data.size(); ++i) data[i] = 3u * i + 5u;
    Buffer buffer = device_buffer(ctx(), data.size() * 4);
    test::must(upload_buffer(ctx(), buffer, std::as_bytes(std::span(data))));
    arm();
    Result<std::vector<std::byte>> read = std::vector<std::byte>{};
    EXPECT_NO_THROW(read = read_buffer(ctx(), buffer));
    if (!buffer.mapped()) {
        expect_failed(read, "read_buffer");
        return;
    }
    ASSERT_TRUE(read.ok()) << "a host copy failed: " << read.error().message;
    ASSERT_EQ(read->size(), data.size() * 4);
    EXPECT_EQ(std::memcmp(read->data(), data.data(), read->size()), 0) << "the host copy changed the bytes";
}

TEST_P(EveryFault, UploadImage) {
    Image image = device_image(ctx());
    const std::vector<float> texels(4 * 4 * 4, 0.5f);
    arm();
    Status uploaded = Ok{};
    EXPECT_NO_THROW(uploaded = upload_image(ctx(), image, 0, 0, std::as_bytes(std::span(texels)),
                                            VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL));
    expect_failed(uploaded, "upload_image");
}

TEST_P(EveryFault, ReadImage) {
    Image image = device_image(ctx());
    const std::vector<float> texels(4 * 4 * 4, 0.5f);
    test::must(upload_image(ctx(), image, 0, 0, std::as_bytes(std::span(texels)), VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_GENERAL));
    arm();
    Result<std::vector<std::byte>> read = std::vector<std::byte>{};
    EXPECT_NO_THROW(read = read_image(ctx(), image, 0, 0, VK_IMAGE_LAYOUT_GENERAL));
    expect_failed(read, "read_image");
}

TEST_P(EveryFault, BakeEnvironment) {
    ShaderCompiler compiler;
    ProgramCache programs(ctx(), compiler);
    const EnvironmentSource source = test::must(resolve_environment("builtin:sky", 64));
    arm();
    Result<BakedEnvironment> baked = Error{"not run"};
    EXPECT_NO_THROW(baked = bake_environment(ctx(), programs, source, tiny_bake()));
    expect_failed(baked, "bake_environment");
}

TEST_P(EveryFault, BakedEnvironmentLoad) {
    const fs::path dir = fs::temp_directory_path() / ("facet_public_errors_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    {
        ShaderCompiler compiler;
        ProgramCache programs(ctx(), compiler);
        const EnvironmentSource source = test::must(resolve_environment("builtin:sky", 64));
        BakedEnvironment baked = test::must(bake_environment(ctx(), programs, source, tiny_bake()));
        test::must(baked.save(dir.string()));
    }
    arm();
    Result<BakedEnvironment> loaded = Error{"not run"};
    EXPECT_NO_THROW(loaded = BakedEnvironment::load(ctx(), dir.string()));
    expect_failed(loaded, "BakedEnvironment::load");
    fs::remove_all(dir);
}

// A host's frame: the session's ForwardRenderer and scene, a GraphExecutor of the host's.
TEST_P(EveryFault, GraphExecutorFrameWithForwardRenderer) {
    auto session = test::must(RenderSession::create(ctx(), test::tiny_job()));
    GraphExecutor executor(ctx());
    RenderGraph graph;
    auto images = session->add_frame_passes(graph);
    ASSERT_TRUE(images) << images.error().message;
    graph.export_image(images->ldr, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                     VK_ACCESS_2_TRANSFER_READ_BIT});
    const CompiledGraph compiled = graph.compile();
    arm();
    Result<GraphRun*> ran = static_cast<GraphRun*>(nullptr);
    EXPECT_NO_THROW(ran = executor.submit_and_wait(compiled));
    expect_failed(ran, "GraphExecutor::submit_and_wait");
    executor.release();
}

TEST_P(EveryFault, RenderSessionCreateAndRenderFrame) {
    arm();
    Result<std::unique_ptr<RenderSession>> created = Error{"not run"};
    EXPECT_NO_THROW(created = RenderSession::create(ctx(), test::tiny_job()));
    expect_failed(created, "RenderSession::create");
    if (GetParam().site != FaultSite::memory) return;  // the context takes no more work
    // Out of memory is not fatal: a session can be made, and its frame fail the same way.
    auto session = test::must(RenderSession::create(ctx(), test::tiny_job()));
    arm();
    Result<RenderedImages> frame = Error{"not run"};
    EXPECT_NO_THROW(frame = session->render_frame());
    expect_failed(frame, "RenderSession::render_frame");
}

INSTANTIATE_TEST_SUITE_P(Sites, EveryFault, ::testing::Values(kMemory, kDeviceLost, kHang), fault_name);

}  // namespace
}  // namespace facet
