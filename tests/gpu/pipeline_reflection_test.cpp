// Pipelines whose layout comes from the SPIR-V: a dispatch sized by the reflected
// workgroup size covers an image of awkward size exactly once, and pushing constants or
// descriptors that differ from what the shader declares is caught as misuse.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include <facet/gpu/context.h>
#include <facet/gpu/pipeline.h>
#include <facet/gpu/resources.h>
#include <facet/gpu/transfer.h>
#include <facet/shader/compiler.h>
#include <facet/shader/program_cache.h>
#include "gpu/fault_injection.h"
#include "support/gpu_test.h"

namespace facet {
namespace {

// Groups of 16 x 4: neither divides the 37 x 23 grid, so a dispatch sized with any other
// constant misses or doubles texels. Each invocation inside the grid adds its index x
// scale + 1 once (atomicAdd: a texel reached twice shows twice the value).
constexpr const char* grid_source = R"(#version 460
layout(local_size_x = 16, local_size_y = 4) in;
layout(std430, binding = 0) buffer Grid { uint values[]; };
layout(push_constant) uniform Params {
    uint width;
    uint height;
    uint scale;
} params;
void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= params.width || p.y >= params.height) return;
    uint i = p.y * params.width + p.x;
    atomicAdd(values[i], i * params.scale + 1u);
}
)";

struct GridParams {
    uint32_t width, height, scale;
};

class PipelineReflectionTest : public test::GpuTest {
protected:
    Pipeline build(const char* source) {
        auto spirv = compiler_.compile_source(ShaderStage::compute, "grid.comp", source);
        EXPECT_TRUE(spirv) << spirv.error().message;
        if (!spirv) return {};
        auto pipeline = Pipeline::compute(ctx(), spirv->words, "grid");
        EXPECT_TRUE(pipeline) << pipeline.error().message;
        return pipeline ? std::move(pipeline).value() : Pipeline{};
    }
    ShaderCompiler compiler_;
};

TEST_F(PipelineReflectionTest, DispatchSizedByTheReflectedWorkgroupCoversTheGridOnce) {
    Pipeline pipeline = build(grid_source);
    ASSERT_NE(pipeline.handle(), VK_NULL_HANDLE);
    EXPECT_EQ(pipeline.workgroup_size(), (std::array<uint32_t, 3>{16, 4, 1}));
    EXPECT_EQ(pipeline.reflection().push_constant_bytes, sizeof(GridParams));
    ASSERT_EQ(pipeline.reflection().bindings.size(), 1u);
    EXPECT_EQ(pipeline.reflection().bindings[0].type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);

    const GridParams params{37, 23, 3};
    const uint32_t count = params.width * params.height;
    Buffer grid = test::must(Buffer::create(ctx(), count * 4,
                                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                            MemoryUsage::readback, "reflection grid"));
    test::must(ctx().submit_and_wait([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, grid.handle(), 0, VK_WHOLE_SIZE, 0);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        pipeline.bind(cmd);
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(grid.handle())};
        pipeline.push_descriptors(cmd, writes);
        pipeline.push_constants(cmd, params);
        const auto local = pipeline.workgroup_size();
        vkCmdDispatch(cmd, group_count(params.width, local[0]), group_count(params.height, local[1]), 1);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    }));
    test::must(grid.invalidate());
    std::vector<uint32_t> values(count);
    std::memcpy(values.data(), grid.mapped(), count * 4);
    uint32_t wrong = 0;
    for (uint32_t i = 0; i < count; ++i)
        if (values[i] != i * params.scale + 1) ++wrong;
    EXPECT_EQ(wrong, 0u) << "of " << count << " texels";
}

TEST_F(PipelineReflectionTest, PushingTheWrongNumberOfBytesIsMisuse) {
    Pipeline pipeline = build(grid_source);
    ASSERT_NE(pipeline.handle(), VK_NULL_HANDLE);
    const uint32_t too_few[2] = {1, 2};
    const uint32_t too_many[4] = {1, 2, 3, 4};
    test::must(ctx().submit_and_wait([&](VkCommandBuffer cmd) {
        pipeline.bind(cmd);
        EXPECT_THROW(pipeline.push_constants(cmd, too_few), UsageError);
        EXPECT_THROW(pipeline.push_constants(cmd, too_many), UsageError);
        try {
            pipeline.push_constants(cmd, too_few);
        } catch (const UsageError& e) {
            // The message names the pipeline and both sizes.
            const std::string message = e.what();
            EXPECT_NE(message.find("grid"), std::string::npos) << message;
            EXPECT_NE(message.find("8 bytes"), std::string::npos) << message;
            EXPECT_NE(message.find("12"), std::string::npos) << message;
        }
        EXPECT_NO_THROW(pipeline.push_constants(cmd, GridParams{1, 1, 1}));
    }));
}

TEST_F(PipelineReflectionTest, PushingDescriptorsTheShaderDoesNotDeclareIsMisuse) {
    Pipeline pipeline = build(grid_source);
    ASSERT_NE(pipeline.handle(), VK_NULL_HANDLE);
    Buffer buffer = test::must(Buffer::create(ctx(), 64,
                                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                              MemoryUsage::upload, "reflection descriptors"));
    test::must(ctx().submit_and_wait([&](VkCommandBuffer cmd) {
        pipeline.bind(cmd);
        const DescriptorWrite wrong_type[] = {DescriptorWrite::uniform_buffer(buffer.handle())};
        EXPECT_THROW(pipeline.push_descriptors(cmd, wrong_type), UsageError);
        const DescriptorWrite two[] = {DescriptorWrite::storage_buffer(buffer.handle()),
                                       DescriptorWrite::storage_buffer(buffer.handle())};
        EXPECT_THROW(pipeline.push_descriptors(cmd, two), UsageError);
    }));
}

// compute() in two steps: the reflection first, the VkPipeline once create_compute() ran;
// binding it before is misuse, and so is creating it twice.
TEST_F(PipelineReflectionTest, ADeferredPipelineIsBoundOnlyOnceCreated) {
    auto spirv = compiler_.compile_source(ShaderStage::compute, "grid.comp", grid_source);
    ASSERT_TRUE(spirv) << spirv.error().message;
    auto deferred = Pipeline::compute_deferred(ctx(), spirv->words, "grid");
    ASSERT_TRUE(deferred) << deferred.error().message;
    EXPECT_FALSE(deferred->created());
    EXPECT_EQ(deferred->workgroup_size(), (std::array<uint32_t, 3>{16, 4, 1}));
    test::must(ctx().submit_and_wait([&](VkCommandBuffer cmd) { EXPECT_THROW(deferred->bind(cmd), UsageError); }));
    ASSERT_TRUE(deferred->create_compute());
    EXPECT_TRUE(deferred->created());
    EXPECT_THROW((void)deferred->create_compute(), UsageError);
    test::must(ctx().submit_and_wait([&](VkCommandBuffer cmd) { deferred->bind(cmd); }));
}

// A ProgramCache::Batch: the pipelines asked for have their reflection at once and are
// created by finish(); the same key gives the same pipeline; a pipeline that fails to be
// created is finish()'s error and leaves the cache, so that asking again makes it anew.
TEST_F(PipelineReflectionTest, ABatchCreatesItsPipelinesOnWorkersByFinish) {
    ProgramCache programs(ctx(), compiler_);
    const char* shaders[] = {"ibl/to_half.comp", "ibl/cube_downsample.comp", "ibl/output_range.comp",
                             "ibl/cube_copy_level.comp"};
    std::vector<const Pipeline*> made;
    {
        ProgramCache::Batch batch(programs);
        EXPECT_THROW(ProgramCache::Batch second(programs), UsageError);
        for (const char* shader : shaders) {
            auto p = programs.compute(shader);
            ASSERT_TRUE(p) << p.error().message;
            EXPECT_EQ((*p)->workgroup_size()[2], 1u) << shader;
            made.push_back(*p);
        }
        EXPECT_EQ(*programs.compute(shaders[0]), made[0]);
        ASSERT_TRUE(batch.finish());
    }
    for (const Pipeline* p : made) EXPECT_TRUE(p->created());
    EXPECT_EQ(*programs.compute(shaders[1]), made[1]);

    // A pipeline of a second batch fails: finish() says so; the first batch's stays.
    ProgramCache fresh(ctx(), compiler_);
    {
        ProgramCache::Batch batch(fresh);
        ASSERT_TRUE(fresh.compute(shaders[0]));
        ASSERT_TRUE(batch.finish());
    }
    inject_fault(FaultSite::pipeline, 0);
    {
        ProgramCache::Batch batch(fresh);
        ASSERT_TRUE(fresh.compute(shaders[0]));  // made already: nothing to create
        ASSERT_TRUE(fresh.compute(shaders[1]));
        Status finished = batch.finish();
        ASSERT_FALSE(finished);
        EXPECT_NE(finished.error().message.find("vkCreateComputePipelines failed"), std::string::npos)
            << finished.error().message;
        EXPECT_NE(finished.error().message.find(shaders[1]), std::string::npos) << finished.error().message;
    }
    clear_injected_faults();
    EXPECT_TRUE((*fresh.compute(shaders[0]))->created());
    auto again = fresh.compute(shaders[1]);
    ASSERT_TRUE(again) << again.error().message;
    EXPECT_TRUE((*again)->created());
}

TEST_F(PipelineReflectionTest, OnlyComputePipelinesHaveAWorkgroupSize) {
    auto vs = compiler_.compile_source(ShaderStage::vertex, "fullscreen.vert", R"(#version 460
void main() { gl_Position = vec4(vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1) * 4.0 - 1.0, 0.0, 1.0); }
)");
    auto fs = compiler_.compile_source(ShaderStage::fragment, "flat.frag", R"(#version 460
layout(push_constant) uniform Colour { vec4 value; } colour;
layout(location = 0) out vec4 color;
void main() { color = colour.value; }
)");
    ASSERT_TRUE(vs && fs);
    Pipeline::GraphicsDesc desc;
    desc.vertex_spirv = vs->words;
    desc.fragment_spirv = fs->words;
    desc.color_formats = {VK_FORMAT_R8G8B8A8_UNORM};
    auto graphics = Pipeline::graphics(ctx(), desc, "flat");
    ASSERT_TRUE(graphics) << graphics.error().message;
    EXPECT_EQ(graphics->reflection().push_constant_bytes, 16u);
    EXPECT_EQ(graphics->reflection().stages,
              VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));
    EXPECT_THROW(graphics->workgroup_size(), UsageError);

    // A vertex shader is no compute pipeline: an Error, not a driver failure.
    auto compute = Pipeline::compute(ctx(), vs->words, "not compute");
    ASSERT_FALSE(compute);
    EXPECT_NE(compute.error().message.find("not a compute shader"), std::string::npos) << compute.error().message;
}

}  // namespace
}  // namespace facet
