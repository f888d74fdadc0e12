#include "ibl/baked_outputs.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/io/ktx2.h>
#include "core/guarded.h"

namespace facet {


namespace {

// Where each level starts in a staging buffer holding every level, its layers one after
// another (a copy region per level covers all its layers: tightly packed, layer after layer).
std::vector<VkBufferImageCopy> level_regions(const ImageDesc& d, const std::vector<VkDeviceSize>& level_bytes) {
    std::vector<VkBufferImageCopy> regions;
    VkDeviceSize offset = 0;
    for (uint32_t m = 0; m < d.mip_levels; ++m) {
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {aspect_of(d.format), m, 0, d.array_layers};
        r.imageExtent = {d.mip_width(m), d.mip_height(m), 1};
        regions.push_back(r);
        offset += level_bytes[m];
    }
    return regions;
}

std::vector<VkDeviceSize> level_sizes(const ImageDesc& d) {
    // RGBA8: the tone-mapped preview.
    const VkDeviceSize texel = d.format == VK_FORMAT_R8G8B8A8_UNORM ? 4 : ktx2_texel_size(d.format);
    if (texel == 0) throw UsageError("baked images are RGBA16F, RGBA32F or (the preview) RGBA8");
    std::vector<VkDeviceSize> sizes;
    for (uint32_t m = 0; m < d.mip_levels; ++m)
        sizes.push_back(VkDeviceSize(d.mip_width(m)) * d.mip_height(m) * d.array_layers * texel);
    return sizes;
}

}  // namespace

// One staging buffer and one submission for every image (not one per level and layer).
ReadBack read_back(Context& context, std::span<const Image* const> images, VkImageLayout layout) {
    std::vector<std::vector<VkDeviceSize>> sizes(images.size());
    std::vector<std::vector<VkBufferImageCopy>> regions(images.size());
    VkDeviceSize total = 0;
    for (size_t i = 0; i < images.size(); ++i) {
        if (!images[i]) continue;
        sizes[i] = level_sizes(images[i]->desc());
        regions[i] = level_regions(images[i]->desc(), sizes[i]);
        for (VkBufferImageCopy& r : regions[i]) r.bufferOffset += total;
        for (VkDeviceSize s : sizes[i]) total += s;
    }
    ReadBack out;
    out.levels.resize(images.size());
    if (total == 0) return out;
    out.staging = std::make_shared<Buffer>(or_throw(
        Buffer::create(context, total, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::readback, "baked image readback")));
    or_throw(context.submit_and_wait([&](VkCommandBuffer cmd) {
        for (size_t i = 0; i < images.size(); ++i) {
            if (!images[i]) continue;
            const Image& image = *images[i];
            const VkImageSubresourceRange all = whole_range(image.desc());
            image_barrier(cmd, image.handle(), all, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
            vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.staging->handle(),
                                   uint32_t(regions[i].size()), regions[i].data());
            image_barrier(cmd, image.handle(), all, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                          VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          VK_ACCESS_2_NONE);
        }
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    }, "reading a baked image back"));
    or_throw(out.staging->invalidate());
    const auto* bytes = static_cast<const std::byte*>(out.staging->mapped());
    for (size_t i = 0; i < images.size(); ++i)
        for (size_t m = 0; m < regions[i].size(); ++m)
            out.levels[i].emplace_back(bytes + regions[i][m].bufferOffset, sizes[i][m]);
    return out;
}

Levels read_levels(Context& context, const Image& image, VkImageLayout layout) {
    const Image* one[] = {&image};
    const ReadBack read = read_back(context, one, layout);
    Levels levels;
    for (std::span<const std::byte> level : read.levels.front()) levels.emplace_back(level.begin(), level.end());
    return levels;
}

Image make_baked_image(Context& context, const ImageDesc& desc, const Levels& levels, const std::string& name) {
    Image image = or_throw(Image::create(
        context, desc, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, name));
    const std::vector<VkDeviceSize> sizes = level_sizes(desc);
    VkDeviceSize total = 0;
    for (uint32_t m = 0; m < desc.mip_levels; ++m) {
        if (m >= levels.size() || levels[m].size() != sizes[m])
            throw UsageError("make_baked_image: level " + std::to_string(m) + " of " + name + " has the wrong size");
        total += sizes[m];
    }
    Buffer staging = or_throw(
        Buffer::create(context, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload, "baked image upload"));
    const auto regions = level_regions(desc, sizes);
    auto* bytes = static_cast<std::byte*>(staging.mapped());
    for (uint32_t m = 0; m < desc.mip_levels; ++m)
        std::memcpy(bytes + regions[m].bufferOffset, levels[m].data(), sizes[m]);
    or_throw(staging.flush());
    const VkImageSubresourceRange all = whole_range(desc);
    or_throw(context.submit_and_wait([&](VkCommandBuffer cmd) {
        image_barrier(cmd, image.handle(), all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
        vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
        image_barrier(cmd, image.handle(), all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kBakedLayout,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }, "uploading a baked image"));
    return image;
}

const char* format_name(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R16G16B16A16_SFLOAT: return "R16G16B16A16_SFLOAT";
        case VK_FORMAT_R32G32B32A32_SFLOAT: return "R32G32B32A32_SFLOAT";
        default: return "unsupported";
    }
}

VkFormat parse_format_name(const std::string& name) {
    if (name == "R16G16B16A16_SFLOAT") return VK_FORMAT_R16G16B16A16_SFLOAT;
    if (name == "R32G32B32A32_SFLOAT") return VK_FORMAT_R32G32B32A32_SFLOAT;
    return VK_FORMAT_UNDEFINED;
}

}  // namespace facet
