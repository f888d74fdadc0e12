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

Result<const Pipeline*> ProgramCache::graphics(const std::string& vertex_shader, const std::string& fragment_shader,
                                               Pipeline::GraphicsDesc desc, std::span<const ShaderDefine> defines) {
    // The key names every piece of state that makes two pipelines differ.
    std::string key = vertex_shader + "+" + fragment_shader;
    for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
    for (VkFormat f : desc.color_formats) key += "|c" + std::to_string(f);
    for (VkDescriptorType t : desc.bindings) key += "|b" + std::to_string(t);
    for (const auto& a : desc.vertex_attributes) key += "|a" + std::to_string(a.format) + "@" + std::to_string(a.offset);
    key += "|d" + std::to_string(desc.depth_format) + "|s" + std::to_string(desc.samples) + "|cull" +
           std::to_string(desc.cull) + "|t" + std::to_string(desc.depth_test) + std::to_string(desc.depth_write) +
           "|blend" + std::to_string(desc.alpha_blend) + "|pc" + std::to_string(desc.push_constant_bytes) + "|topo" +
           std::to_string(desc.topology);
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second.get();
    auto vertex = compiler_.compile(ShaderStage::vertex, vertex_shader, defines);
    if (!vertex) return vertex.error();
    auto fragment = compiler_.compile(ShaderStage::fragment, fragment_shader, defines);
    if (!fragment) return fragment.error();
    desc.vertex_spirv = vertex->words;
    desc.fragment_spirv = fragment->words;
    try {
        auto pipeline = std::make_unique<Pipeline>(Pipeline::graphics(context_, desc, fragment_shader));
        const Pipeline* result = pipeline.get();
        pipelines_[key] = std::move(pipeline);
        return result;
    } catch (const VulkanError& e) {
        return Error{fragment_shader + ": cannot create the pipeline: " + e.what(), e.result()};
    }
}

}  // namespace facet
