#pragma once
// Render-graph vocabulary: versioned resource handles, the kinds of access a pass
// declares, and what imported resources bring in and must leave in.
#include <cstdint>
#include <limits>
#include <string>

#include <vulkan/vulkan.h>

#include <facet/gpu/resources.h>

namespace facet {

constexpr uint32_t invalid_index = std::numeric_limits<uint32_t>::max();

// A resource at one version: every write returns a new version, and only the newest
// version may be used (Filament FrameGraph's rule), so stale handles are caught.
struct ImageHandle {
    uint32_t index = invalid_index;
    uint32_t version = 0;
    bool valid() const { return index != invalid_index; }
};
struct BufferHandle {
    uint32_t index = invalid_index;
    uint32_t version = 0;
    bool valid() const { return index != invalid_index; }
};

enum class PassKind { compute, graphics, transfer };

enum class Access {
    sampled,             // images: sampled in a shader
    storage_read,        // images and buffers
    storage_write,
    storage_read_write,
    color_attachment,    // graphics passes
    depth_attachment,    // depth test and write
    depth_read,          // depth test only
    transfer_src,
    transfer_dst,
    uniform_read,        // buffers
    vertex_read,         // buffers: vertex attributes
    index_read,          // buffers: indices
};

const char* access_name(Access access);
bool is_write(Access access);

constexpr uint32_t all_remaining = std::numeric_limits<uint32_t>::max();

// Mips and array layers a pass touches; the default is the whole image.
struct ImageRange {
    uint32_t base_mip = 0;
    uint32_t mip_count = all_remaining;
    uint32_t base_layer = 0;
    uint32_t layer_count = all_remaining;

    static ImageRange mip(uint32_t level) { return {level, 1, 0, all_remaining}; }
};

// Where a resource is, as far as synchronisation goes: the layout (images) and the
// stages/accesses whose work must be waited for or made visible.
struct ResourceState {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

// An image the graph does not own (a swapchain image, a host engine's texture).
struct ImportedImage {
    VkImage image = VK_NULL_HANDLE;
    ImageDesc desc;
    ResourceState initial;  // how the host leaves it before the graph runs
    ResourceState final;    // how the graph must leave it (layout UNDEFINED: as it ends)
};

struct ImportedBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    ResourceState initial;
    ResourceState final;
};

struct BufferDesc {
    VkDeviceSize size = 0;
    bool operator==(const BufferDesc&) const = default;
};

}  // namespace facet
