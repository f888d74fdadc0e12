#include <facet/shader/program_cache.h>

#include <facet/gpu/context.h>

namespace facet {

Result<const Pipeline*> ProgramCache::get(const std::string& key, std::function<Result<Pipeline>()> build) {
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second.pipeline.get();
    auto built = build();
    if (!built) return built.error();
    Entry entry{std::make_unique<Pipeline>(std::move(built).value()), std::move(build)};
    const Pipeline* result = entry.pipeline.get();
    pipelines_.emplace(key, std::move(entry));
    return result;
}

Result<const Pipeline*> ProgramCache::compute(const std::string& shader, std::span<const ShaderDefine> defines) {
    std::string key = shader;
    for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
    std::vector<ShaderDefine> define_list(defines.begin(), defines.end());
    return get(key, [this, shader, define_list]() -> Result<Pipeline> {
        auto spirv = compiler_.compile(ShaderStage::compute, shader, define_list);
        if (!spirv) return spirv.error();
        return Pipeline::compute(context_, spirv->words, shader);
    });
}

Result<const Pipeline*> ProgramCache::graphics(const std::string& vertex_shader, const std::string& fragment_shader,
                                               Pipeline::GraphicsDesc desc, std::span<const ShaderDefine> defines) {
    // The key names every piece of state that makes two pipelines differ.
    std::string key = vertex_shader + "+" + fragment_shader;
    for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
    for (VkFormat f : desc.color_formats) key += "|c" + std::to_string(f);
    for (const auto& a : desc.vertex_attributes) key += "|a" + std::to_string(a.format) + "@" + std::to_string(a.offset);
    key += "|d" + std::to_string(desc.depth_format) + "|s" + std::to_string(desc.samples) + "|cull" +
           std::to_string(desc.cull) + "|t" + std::to_string(desc.depth_test) + std::to_string(desc.depth_write) +
           "|blend" + std::to_string(desc.alpha_blend) + "|topo" +
           std::to_string(desc.topology);
    std::vector<ShaderDefine> define_list(defines.begin(), defines.end());
    desc.vertex_spirv = {};
    desc.fragment_spirv = {};
    return get(key, [this, vertex_shader, fragment_shader, desc, define_list]() -> Result<Pipeline> {
        auto vertex = compiler_.compile(ShaderStage::vertex, vertex_shader, define_list);
        if (!vertex) return vertex.error();
        auto fragment = compiler_.compile(ShaderStage::fragment, fragment_shader, define_list);
        if (!fragment) return fragment.error();
        Pipeline::GraphicsDesc d = desc;
        d.vertex_spirv = vertex->words;
        d.fragment_spirv = fragment->words;
        return Pipeline::graphics(context_, d, vertex_shader + " + " + fragment_shader);
    });
}

Result<size_t> ProgramCache::reload() {
    std::vector<std::pair<Entry*, Pipeline>> rebuilt;
    for (auto& [key, entry] : pipelines_) {
        auto built = entry.build();
        if (!built) return built.error();
        rebuilt.emplace_back(&entry, std::move(built).value());
    }
    for (auto& [entry, pipeline] : rebuilt) *entry->pipeline = std::move(pipeline);
    return rebuilt.size();
}

}  // namespace facet
