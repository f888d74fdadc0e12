#pragma once
// Staging upload and readback outside any render graph (for setup and tests).
// Inside a graph, copies are passes of their own.
//
// Each call submits and waits (Context::submit_and_wait, bounded by
// ContextOptions::fence_timeout_ms). Errors: an Error (with its VkResult) when the
// device fails, memory runs out or the wait times out; UsageError for programmer misuse
// (a mip or layer the image lacks, data of the wrong size). Thread safety: as
// Context::submit_and_wait.
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/gpu/resources.h>

namespace facet {

// Copies `data` (tightly packed texels of one mip level/layer) into that subresource,
// which is in `current_layout` (UNDEFINED: contents may be discarded) and is left in
// `final_layout`. Waits for completion.
Status upload_image(Context& context, Image& image, uint32_t mip, uint32_t layer,
                    std::span<const std::byte> data, VkImageLayout current_layout,
                    VkImageLayout final_layout);

// Reads one mip level/layer back (tightly packed texels). The image must be in
// `current_layout` and is left in it. Waits for completion.
Result<std::vector<std::byte>> read_image(Context& context, const Image& image, uint32_t mip,
                                          uint32_t layer, VkImageLayout current_layout);

// One image layout transition / dependency (synchronization2), for work recorded outside
// a render graph (uploads, mip generation, clears); the graph derives its own barriers.
void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                   VkImageLayout to, VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access);

// A global memory barrier (synchronization2), e.g. compute writes -> host reads.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access);

// Writes `data` at the start of `buffer` (through its mapping when it has one).
Status upload_buffer(Context& context, Buffer& buffer, std::span<const std::byte> data);
Result<std::vector<std::byte>> read_buffer(Context& context, const Buffer& buffer);

}  // namespace facet
