#pragma once
// Runs a one-invocation compute shader that writes floats to
// `layout(std430, binding = 0) writeonly buffer Out { float values[]; };` and returns
// them: how the tests read GLSL values (constants, include functions) back to the CPU.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include <facet/gpu/context.h>
#include <facet/gpu/pipeline.h>
#include <facet/gpu/resources.h>
#include <facet/gpu/transfer.h>
#include <facet/shader/compiler.h>
#include "support/gpu_test.h"

namespace facet::test {

// Empty (and a test failure) when the shader does not compile.
inline std::vector<float> run_compute_probe(Context& context, std::string_view name, std::string_view source,
                                            size_t count) {
    ShaderCompiler compiler;
    auto spirv = compiler.compile_source(ShaderStage::compute, name, source);
    if (!spirv) {
        ADD_FAILURE() << spirv.error().message;
        return {};
    }
    auto built = Pipeline::compute(context, spirv->words, std::string(name));
    if (!built) {
        ADD_FAILURE() << built.error().message;
        return {};
    }
    Pipeline pipeline = std::move(built).value();
    Buffer out = must(Buffer::create(context, count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     MemoryUsage::readback, "probe output"));
    must(context.submit_and_wait([&](VkCommandBuffer cmd) {
        pipeline.bind(cmd);
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(out.handle())};
        pipeline.push_descriptors(cmd, writes);
        vkCmdDispatch(cmd, 1, 1, 1);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    }));
    must(out.invalidate());
    std::vector<float> values(count);
    std::memcpy(values.data(), out.mapped(), count * sizeof(float));
    return values;
}

}  // namespace facet::test
