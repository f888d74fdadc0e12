#include <facet/gpu/transfer.h>

#include <cstring>

#include <facet/core/result.h>
#include <facet/gpu/context.h>
#include "core/guarded.h"

namespace facet {

namespace {

// Conservative on purpose: these helpers run outside any graph, between unknown work.
void layout_transition(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                       VkImageLayout to) {
    image_barrier(cmd, image, range, from, to, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

VkDeviceSize subresource_bytes(const ImageDesc& desc, uint32_t mip) {
    return VkDeviceSize(desc.mip_width(mip)) * desc.mip_height(mip) * bytes_per_texel(desc.format);
}

void check_subresource(const Image& image, uint32_t mip, uint32_t layer) {
    if (mip >= image.desc().mip_levels || layer >= image.desc().array_layers)
        throw UsageError("mip " + std::to_string(mip) + " / layer " + std::to_string(layer) +
                         " is outside the image");
}

VkBufferImageCopy copy_region(const Image& image, uint32_t mip, uint32_t layer) {
    VkBufferImageCopy region{};
    region.imageSubresource = {aspect_of(image.desc().format), mip, layer, 1};
    region.imageExtent = {image.desc().mip_width(mip), image.desc().mip_height(mip), 1};
    return region;
}

}  // namespace

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access) {
    VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    b.srcStageMask = src_stages;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stages;
    b.dstAccessMask = dst_access;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                   VkImageLayout to, VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stages, VkAccessFlags2 dst_access) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = src_stages;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stages;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = range;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

Status upload_image(Context& context, Image& image, uint32_t mip, uint32_t layer,
                    std::span<const std::byte> data, VkImageLayout current_layout, VkImageLayout final_layout) {
    check_subresource(image, mip, layer);
    const VkDeviceSize bytes = subresource_bytes(image.desc(), mip);
    if (data.size() != bytes)
        throw UsageError("upload_image: " + std::to_string(data.size()) + " bytes given, the subresource holds " +
                         std::to_string(bytes));
    auto staging = Buffer::create(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload,
                                  "upload staging");
    if (!staging) return staging.error();
    std::memcpy(staging->mapped(), data.data(), bytes);
    if (Status flushed = staging->flush(); !flushed) return flushed;
    VkImageSubresourceRange range{aspect_of(image.desc().format), mip, 1, layer, 1};
    return context.submit_and_wait([&](VkCommandBuffer cmd) {
        layout_transition(cmd, image.handle(), range, current_layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy region = copy_region(image, mip, layer);
        vkCmdCopyBufferToImage(cmd, staging->handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &region);
        layout_transition(cmd, image.handle(), range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout);
    });
}

Result<std::vector<std::byte>> read_image(Context& context, const Image& image, uint32_t mip, uint32_t layer,
                                          VkImageLayout current_layout) {
    check_subresource(image, mip, layer);
    const VkDeviceSize bytes = subresource_bytes(image.desc(), mip);
    auto made = Buffer::create(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::readback,
                               "readback staging");
    if (!made) return made.error();
    Buffer& staging = *made;
    VkImageSubresourceRange range{aspect_of(image.desc().format), mip, 1, layer, 1};
    Status done = context.submit_and_wait([&](VkCommandBuffer cmd) {
        layout_transition(cmd, image.handle(), range, current_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region = copy_region(image, mip, layer);
        vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1,
                               &region);
        layout_transition(cmd, image.handle(), range, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, current_layout);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    });
    if (!done) return done.error();
    if (Status visible = staging.invalidate(); !visible) return visible.error();
    std::vector<std::byte> out(bytes);
    std::memcpy(out.data(), staging.mapped(), bytes);
    return out;
}

Status upload_buffer(Context& context, Buffer& buffer, std::span<const std::byte> data) {
    if (data.size() > buffer.size()) throw UsageError("upload_buffer: data larger than the buffer");
    if (buffer.mapped()) {
        std::memcpy(buffer.mapped(), data.data(), data.size());
        return buffer.flush();
    }
    auto made = Buffer::create(context, data.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload,
                               "upload staging");
    if (!made) return made.error();
    Buffer& staging = *made;
    std::memcpy(staging.mapped(), data.data(), data.size());
    if (Status flushed = staging.flush(); !flushed) return flushed;
    return context.submit_and_wait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, data.size()};
        vkCmdCopyBuffer(cmd, staging.handle(), buffer.handle(), 1, &region);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    });
}

Result<std::vector<std::byte>> read_buffer(Context& context, const Buffer& buffer) {
    std::vector<std::byte> out(buffer.size());
    if (buffer.mapped()) {
        if (Status visible = buffer.invalidate(); !visible) return visible.error();
        std::memcpy(out.data(), buffer.mapped(), out.size());
        return out;
    }
    auto made = Buffer::create(context, buffer.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::readback,
                               "readback staging");
    if (!made) return made.error();
    Buffer& staging = *made;
    Status done = context.submit_and_wait([&](VkCommandBuffer cmd) {
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferCopy region{0, 0, buffer.size()};
        vkCmdCopyBuffer(cmd, buffer.handle(), staging.handle(), 1, &region);
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    });
    if (!done) return done.error();
    if (Status visible = staging.invalidate(); !visible) return visible.error();
    std::memcpy(out.data(), staging.mapped(), out.size());
    return out;
}

}  // namespace facet
