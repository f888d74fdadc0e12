#pragma once
// Executing a compiled graph: physical resources are allocated (or taken over from an
// earlier run, see graph/graph_executor.h), every pass is recorded behind its barriers
// with GPU timestamps around it, and the work is submitted (or left in a command buffer
// the host submits). A GraphRun owns everything the recorded commands use, so it must
// outlive their execution. The CompiledGraph (and its RenderGraph) must live while the
// run allocates, records and looks up images; timings() does not need them.
//
// Errors: prepare, record and submit_and_wait return an Error (with its VkResult) when
// the device fails: a graph no device holds, out of memory, device lost, a wait that
// timed out, a pass whose engine-side work failed. UsageError marks programmer misuse
// (recording a run twice, looking up an image the graph does not use or before
// prepare). Inside a pass's execute step, PassContext::view fails (out of memory) by
// throwing the engine's internal exception through the pass: the run that executes it
// catches it and returns an Error, so it never reaches the caller.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/graph/compiled_graph.h>

namespace facet {

class Context;
class GraphRun;

// What a pass's execute step sees: the command buffer and its resources.
class PassContext {
public:
    VkCommandBuffer cmd() const { return cmd_; }
    Context& context() const { return context_; }

    VkImage image(ImageHandle image) const;
    const ImageDesc& desc(ImageHandle image) const;
    // A view of some mips/layers (default: all; cube images get a cube view when all
    // six faces are included, else 2D / 2D array).
    VkImageView view(ImageHandle image, ImageRange range = {},
                     VkImageViewType type = VK_IMAGE_VIEW_TYPE_MAX_ENUM) const;
    VkBuffer buffer(BufferHandle buffer) const;
    VkDeviceSize size(BufferHandle buffer) const;

private:
    friend class GraphRun;
    PassContext(GraphRun& run, Context& context, VkCommandBuffer cmd) : run_(run), context_(context), cmd_(cmd) {}
    GraphRun& run_;
    Context& context_;
    VkCommandBuffer cmd_;
};

// Physical resources a finished run hands to the next (GraphExecutor's frame slots):
// images and buffers are taken over when their description and usage match, so a frame
// of the same shape creates no image and allocates no memory.
struct GraphResourcePool {
    std::vector<Image> images;
    std::vector<Buffer> buffers;
    VkQueryPool queries = VK_NULL_HANDLE;
    uint32_t query_count = 0;
};

struct PassTiming {
    std::string name;
    double time_ms = 0;
};

class GraphRun {
public:
    // Makes nothing on the device yet: prepare() (or the first record/submit_and_wait)
    // allocates the physical resources.
    GraphRun(Context& context, const CompiledGraph& compiled);
    // prepare() takes matching images, buffers and the query pool from `pool` (what is
    // left there is the caller's to keep or free); `pool` must live until then, and its
    // resources must be idle.
    GraphRun(Context& context, const CompiledGraph& compiled, GraphResourcePool& pool);
    ~GraphRun();
    // Moves every transient resource and the query pool into `pool` (for the next run);
    // the run is empty afterwards. Only once the recorded work has completed.
    void release_into(GraphResourcePool& pool);
    GraphRun(const GraphRun&) = delete;
    GraphRun& operator=(const GraphRun&) = delete;

    // Allocates the physical resources (after a success, later calls do nothing). An
    // Error names a graph the device cannot hold or the allocation that failed; nothing
    // is left half made (what was taken from the pool goes back to it).
    Status prepare();
    // Records everything into the host's command buffer (which must be recording).
    Status record(VkCommandBuffer cmd);
    // Records into a one-time command buffer of the context, submits it and waits.
    Status submit_and_wait();
    // Progress on long work: one submission per pass, `progress` called after each with
    // the number of passes done, the total and the pass's name. Barriers still hold:
    // they order work across submissions to the same queue. An exception `progress`
    // throws (e.g. to stop) passes through to the caller.
    using Progress = std::function<void(uint32_t done, uint32_t total, const std::string& pass)>;
    Status submit_and_wait(const Progress& progress);

    // GPU time of every executed pass, in order; call after the work completed (the
    // compiled graph may be gone by then). Empty when the queue has no timestamps.
    std::vector<PassTiming> timings() const;

    // Resources after the run (exported transients and imported ones).
    VkImage image(ImageHandle image) const;
    VkBuffer buffer(BufferHandle buffer) const;
    Image* transient_image(ImageHandle image);  // nullptr for imported or detached images
    Buffer* transient_buffer(BufferHandle buffer);
    // Takes an exported transient image out of the run: the caller owns it (in the layout
    // the graph left it), and the next run of the same shape creates a new one. Throws
    // UsageError for an imported, unused or already detached image.
    Image detach_image(ImageHandle image);

private:
    friend class PassContext;
    struct ViewKey {  // views of imported images (transient images cache their own)
        uint32_t physical;
        VkImageSubresourceRange range;
        VkImageViewType type;
    };
    VkImageView view(uint32_t resource, ImageRange range, VkImageViewType type);
    const ImageDesc& image_desc(uint32_t resource) const;
    void release_all();
    void allocate(GraphResourcePool* pool);  // throws internally; prepare() returns the Error
    void record_or_throw(VkCommandBuffer cmd);
    void submit_or_throw(const Progress& progress);
    void record_barriers(VkCommandBuffer cmd, const BarrierBatch& batch) const;
    void record_pass(VkCommandBuffer cmd, uint32_t index);
    VkImage physical_image(uint32_t physical) const;
    VkBuffer physical_buffer(uint32_t physical) const;

    Context& context_;
    const CompiledGraph* compiled_;
    std::vector<Image> images_;    // per physical image (empty for imported)
    std::vector<Buffer> buffers_;  // per physical buffer (empty for imported)
    std::vector<std::pair<ViewKey, VkImageView>> views_;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    uint32_t query_count_ = 0;
    std::vector<std::string> pass_names_;  // in execution order
    GraphResourcePool* pool_ = nullptr;    // until prepare()
    bool prepared_ = false;
    bool recorded_ = false;
};

// Compiles nothing: runs an already compiled graph and returns its run (for timings
// and exported resources), or the Error that stopped it.
Result<std::unique_ptr<GraphRun>> run_graph(Context& context, const CompiledGraph& compiled);

}  // namespace facet
