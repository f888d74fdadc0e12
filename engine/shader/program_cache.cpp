#include "shader/program_cache.h"

#include "gpu/context.h"

namespace facet {

Result<const Pipeline*> ProgramCache::compute(const std::string& shader, std::span<const VkDescriptorType> bindings,
                                              uint32_t push_constant_bytes, std::span<const ShaderDefine> defines) {
    std::string key = shader;
    for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second.get();
    auto spirv = compiler_.compile(ShaderStage::compute, shader, defines);
    if (!spirv) return spirv.error();
    try {
        auto pipeline = std::make_unique<Pipeline>(
            Pipeline::compute(context_, spirv->words, bindings, push_constant_bytes, shader));
        const Pipeline* result = pipeline.get();
        pipelines_[key] = std::move(pipeline);
        return result;
    } catch (const VulkanError& e) {
        return Error{shader + ": cannot create the pipeline: " + e.what(), e.result()};
    }
}

}  // namespace facet
