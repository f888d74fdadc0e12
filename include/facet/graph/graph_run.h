#pragma once
// Executing a compiled graph: physical resources are allocated, every pass is recorded
// behind its barriers with GPU timestamps around it, and the work is submitted (or left
// in a command buffer the host submits). A GraphRun owns everything the recorded
// commands use, so it must outlive their execution.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

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

struct PassTiming {
    std::string name;
    double time_ms = 0;
};

class GraphRun {
public:
    GraphRun(Context& context, const CompiledGraph& compiled);
    ~GraphRun();
    GraphRun(const GraphRun&) = delete;
    GraphRun& operator=(const GraphRun&) = delete;

    // Records everything into the host's command buffer (which must be recording).
    void record(VkCommandBuffer cmd);
    // Records into a one-time command buffer of the context, submits it and waits.
    void submit_and_wait();
    // Progress on long work: one submission per pass, `progress` called after each with
    // the number of passes done, the total and the pass's name. Barriers still hold:
    // they order work across submissions to the same queue.
    using Progress = std::function<void(uint32_t done, uint32_t total, const std::string& pass)>;
    void submit_and_wait(const Progress& progress);

    // GPU time of every executed pass, in order; call after the work completed.
    // Empty when the queue has no timestamps.
    std::vector<PassTiming> timings() const;

    // Resources after the run (exported transients and imported ones).
    VkImage image(ImageHandle image) const;
    VkBuffer buffer(BufferHandle buffer) const;
    Image* transient_image(ImageHandle image);  // nullptr for imported images
    Buffer* transient_buffer(BufferHandle buffer);

private:
    friend class PassContext;
    struct ViewKey {
        uint32_t physical;
        VkImageSubresourceRange range;
        VkImageViewType type;
    };
    VkImageView view(uint32_t resource, ImageRange range, VkImageViewType type);
    const ImageDesc& image_desc(uint32_t resource) const;
    void allocate();
    void record_barriers(VkCommandBuffer cmd, const BarrierBatch& batch) const;
    void record_pass(VkCommandBuffer cmd, uint32_t index);
    VkImage physical_image(uint32_t physical) const;
    VkBuffer physical_buffer(uint32_t physical) const;

    Context& context_;
    const CompiledGraph& compiled_;
    std::vector<Image> images_;    // per physical image (empty for imported)
    std::vector<Buffer> buffers_;  // per physical buffer (empty for imported)
    std::vector<std::pair<ViewKey, VkImageView>> views_;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    bool recorded_ = false;
};

// Compiles nothing: runs an already compiled graph and returns its run (for timings
// and exported resources).
std::unique_ptr<GraphRun> run_graph(Context& context, const CompiledGraph& compiled);

}  // namespace facet
