#include <facet/graph/graph_executor.h>

#include <string>

#include <facet/gpu/context.h>

namespace facet {

GraphExecutor::GraphExecutor(Context& context, uint32_t frames_in_flight) : context_(context) {
    if (frames_in_flight == 0) throw UsageError("GraphExecutor: frames_in_flight must be at least 1");
    slots_.resize(frames_in_flight);
}

GraphExecutor::~GraphExecutor() { release(); }

GraphExecutor::Slot& GraphExecutor::slot(uint32_t frame) {
    if (frame >= slots_.size())
        throw UsageError("GraphExecutor: frame slot " + std::to_string(frame) + " of " +
                         std::to_string(slots_.size()));
    return slots_[frame];
}

void GraphExecutor::free_pool(GraphResourcePool& pool) {
    pool.images.clear();
    pool.buffers.clear();
    if (pool.queries) vkDestroyQueryPool(context_.device(), pool.queries, nullptr);
    pool.queries = VK_NULL_HANDLE;
    pool.query_count = 0;
}

Result<GraphRun*> GraphExecutor::prepare(const CompiledGraph& compiled, uint32_t frame) {
    Slot& s = slot(frame);
    if (s.run) {
        s.run->release_into(s.pool);
        s.run.reset();
    }
    s.run = std::make_unique<GraphRun>(context_, compiled, s.pool);
    if (Status made = s.run->prepare(); !made) {
        s.run.reset();
        free_pool(s.pool);
        return made.error();
    }
    // What this shape does not use is not kept for a shape that may never come back.
    s.pool.images.clear();
    s.pool.buffers.clear();
    return s.run.get();
}

Result<GraphRun*> GraphExecutor::record(const CompiledGraph& compiled, VkCommandBuffer cmd, uint32_t frame) {
    auto run = prepare(compiled, frame);
    if (!run) return run.error();
    if (Status recorded = (*run)->record(cmd); !recorded) return recorded.error();
    return run;
}

Result<GraphRun*> GraphExecutor::submit_and_wait(const CompiledGraph& compiled, uint32_t frame,
                                                 const GraphRun::Progress& progress) {
    auto run = prepare(compiled, frame);
    if (!run) return run.error();
    Status done = progress ? (*run)->submit_and_wait(progress) : (*run)->submit_and_wait();
    if (!done) return done.error();
    return run;
}

GraphRun* GraphExecutor::run(uint32_t frame) const {
    if (frame >= slots_.size()) return nullptr;
    return slots_[frame].run.get();
}

Result<Image> GraphExecutor::detach_image(ImageHandle image, uint32_t frame) {
    Slot& s = slot(frame);
    if (!s.run) return Error{"detach_image: frame slot " + std::to_string(frame) + " has not run"};
    if (!s.run->transient_image(image))
        return Error{"detach_image: the image is imported, unused by the graph or already detached"};
    return s.run->detach_image(image);
}

void GraphExecutor::release() {
    for (Slot& s : slots_) {
        s.run.reset();
        free_pool(s.pool);
    }
}

}  // namespace facet
