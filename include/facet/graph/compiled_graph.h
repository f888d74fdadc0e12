#pragma once
// The result of RenderGraph::compile(), a pure step with no Vulkan calls: the passes
// that contribute to an output, in order, each with the barriers to record before it;
// lifetimes of transient resources and the physical resources they share.
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/graph/render_graph.h>

namespace facet {

struct ImageBarrier {
    uint32_t physical = 0;  // index into CompiledGraph::physical_images
    VkImageSubresourceRange range{};
    VkPipelineStageFlags2 src_stages = 0, dst_stages = 0;
    VkAccessFlags2 src_access = 0, dst_access = 0;
    VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED, new_layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

struct BufferBarrier {
    uint32_t physical = 0;  // index into CompiledGraph::physical_buffers
    VkPipelineStageFlags2 src_stages = 0, dst_stages = 0;
    VkAccessFlags2 src_access = 0, dst_access = 0;
};

struct BarrierBatch {
    std::vector<ImageBarrier> images;
    std::vector<BufferBarrier> buffers;
    bool empty() const { return images.empty() && buffers.empty(); }
};

struct CompiledPass {
    uint32_t pass = 0;  // index into RenderGraph::passes()
    BarrierBatch barriers_before;
};

// One Vulkan image or buffer at run time; several transient resources with the same
// description and disjoint lifetimes share one.
struct PhysicalResource {
    std::string name;
    bool imported = false;
    uint32_t imported_resource = invalid_index;  // the resource node when imported
    ImageDesc image_desc;
    BufferDesc buffer_desc;
    VkImageUsageFlags image_usage = 0;
    VkBufferUsageFlags buffer_usage = 0;
    std::vector<uint32_t> resources;  // resource nodes mapped onto it, in order of use
};

struct Lifetime {
    uint32_t first = invalid_index;  // position in CompiledGraph::passes
    uint32_t last = invalid_index;
    bool used() const { return first != invalid_index; }
};

struct CompiledGraph {
    const RenderGraph* graph = nullptr;
    std::vector<CompiledPass> passes;      // in execution order
    std::vector<uint32_t> culled;          // passes that contribute nothing
    BarrierBatch final_barriers;           // to the imported/exported resources' final states
    std::vector<Lifetime> lifetimes;       // per resource node
    std::vector<uint32_t> physical_of;     // per resource node: physical index (invalid if unused)
    std::vector<PhysicalResource> physical_images;
    std::vector<PhysicalResource> physical_buffers;

    std::string to_text() const;  // passes, uses with versions, barriers, lifetimes
    std::string to_dot() const;   // Graphviz: passes and resource versions
};

class Context;
// The transient images and buffers `compiled` allocates when it runs, against the
// device's limits (facet/gpu/device_limits.h); the error names the resource.
Status check_graph_fits(const Context& context, const CompiledGraph& compiled);

}  // namespace facet
