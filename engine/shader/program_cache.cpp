#include <facet/shader/program_cache.h>

#include <algorithm>

#include <facet/core/result.h>
#include <facet/gpu/context.h>

namespace facet {

Result<const Pipeline*> ProgramCache::get(const std::string& key, std::function<Result<Pipeline>()> build,
                                          const std::function<Result<Pipeline>()>& first) {
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second.pipeline.get();
    auto built = first ? first() : build();
    if (!built) return built.error();
    Entry entry{std::make_unique<Pipeline>(std::move(built).value()), std::move(build)};
    Pipeline* result = entry.pipeline.get();
    pipelines_.emplace(key, std::move(entry));
    if (first) batch_->add(key, result);
    return result;
}

Result<const Pipeline*> ProgramCache::compute(const std::string& shader, std::span<const ShaderDefine> defines) {
    std::string key = shader;
    for (const ShaderDefine& d : defines) key += "|" + d.name + "=" + d.value;
    std::vector<ShaderDefine> define_list(defines.begin(), defines.end());
    // In a batch the driver's compilation (Pipeline::create_compute) goes to its workers.
    auto make = [this, shader, define_list](bool deferred) -> Result<Pipeline> {
        auto spirv = compiler_.compile(ShaderStage::compute, shader, define_list);
        if (!spirv) return spirv.error();
        return deferred ? Pipeline::compute_deferred(context_, spirv->words, shader)
                        : Pipeline::compute(context_, spirv->words, shader);
    };
    std::function<Result<Pipeline>()> first;
    if (batch_) first = [make] { return make(true); };
    return get(key, [make] { return make(false); }, first);
}

ProgramCache::Batch::Batch(ProgramCache& cache) : cache_(cache) {
    if (cache_.batch_) throw UsageError("ProgramCache: one Batch at a time");
    cache_.batch_ = this;
}

ProgramCache::Batch::~Batch() { (void)finish(); }

void ProgramCache::Batch::add(const std::string& key, Pipeline* pipeline) {
    std::lock_guard lock(mutex_);
    queue_.emplace_back(key, pipeline);
    if (workers_.size() < std::max(1u, std::thread::hardware_concurrency())) workers_.emplace_back([this] { work(); });
    wake_.notify_one();
}

void ProgramCache::Batch::work() {
    std::unique_lock lock(mutex_);
    for (;;) {
        wake_.wait(lock, [&] { return closing_ || !queue_.empty(); });
        if (queue_.empty()) return;
        auto [key, pipeline] = queue_.front();
        queue_.pop_front();
        lock.unlock();
        Status created = pipeline->create_compute();
        lock.lock();
        if (!created) failed_.emplace_back(key, created.error());
    }
}

Status ProgramCache::Batch::finish() {
    if (finished_) return Ok{};
    {
        std::lock_guard lock(mutex_);
        closing_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
    finished_ = true;
    cache_.batch_ = nullptr;
    for (const auto& [key, error] : failed_) cache_.pipelines_.erase(key);
    if (!failed_.empty()) return failed_.front().second;
    return Ok{};
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
    if (batch_)
        if (Status s = batch_->finish(); !s) return s.error();
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
