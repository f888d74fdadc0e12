#pragma once
// A long-lived executor for graphs built anew every frame: each of N frame slots keeps
// the physical resources (images, buffers, their views, the timestamp query pool) of its
// last run and hands them to the next run in that slot, so a steady frame whose compiled
// graph has the same shape creates no image and allocates no device memory.
//
// Frames in flight: the host picks N and a slot per frame (frame_index % N). The executor
// never waits on the device for a slot: before reusing slot k the host must have waited
// for the work last recorded in slot k (its own fence), as it does for its command buffers.
//
// Errors: prepare, record, submit_and_wait and detach_image return an Error (with its
// VkResult) for what the device can cause: a graph it cannot hold, out of memory, device
// lost, a wait that timed out. UsageError marks programmer misuse: frames_in_flight 0,
// a frame slot out of range, a run recorded twice.
#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/graph/graph_run.h>

namespace facet {

class Context;

class GraphExecutor {
public:
    explicit GraphExecutor(Context& context, uint32_t frames_in_flight = 1);
    ~GraphExecutor();
    GraphExecutor(const GraphExecutor&) = delete;
    GraphExecutor& operator=(const GraphExecutor&) = delete;

    uint32_t frames_in_flight() const { return static_cast<uint32_t>(slots_.size()); }

    // A run of `compiled` in slot `frame` (< frames_in_flight), its resources taken over
    // from the slot's previous run where description and usage match; resources the new
    // shape does not use are freed. The run (owned here) stays valid until the slot is
    // used again; `compiled` and its RenderGraph must live until it is recorded (and
    // while its images are looked up), not until the GPU is done. Errors: a graph the
    // device cannot hold, out of device memory (the slot then holds no run and no
    // resources). frame out of range: UsageError.
    Result<GraphRun*> prepare(const CompiledGraph& compiled, uint32_t frame = 0);
    // prepare() and record every pass into the host's command buffer (recording).
    Result<GraphRun*> record(const CompiledGraph& compiled, VkCommandBuffer cmd, uint32_t frame = 0);
    // prepare() and run on the context's queue, waiting for it (optionally one submission
    // per pass with progress; see GraphRun::submit_and_wait).
    Result<GraphRun*> submit_and_wait(const CompiledGraph& compiled, uint32_t frame = 0,
                                      const GraphRun::Progress& progress = {});

    // The slot's latest run (nullptr before the first): exported images, timings.
    GraphRun* run(uint32_t frame = 0) const;
    // Takes an exported transient image of the slot's latest run out, as an owned Image
    // (in the layout its export named); the slot's next run creates a new one in its place.
    Result<Image> detach_image(ImageHandle image, uint32_t frame = 0);

    // Frees every slot's resources; the host must have waited for all of them.
    void release();

private:
    struct Slot {
        std::unique_ptr<GraphRun> run;
        GraphResourcePool pool;
    };
    Slot& slot(uint32_t frame);
    void free_pool(GraphResourcePool& pool);

    Context& context_;
    std::vector<Slot> slots_;
};

}  // namespace facet
