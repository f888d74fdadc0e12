#include <facet/gpu/resources.h>

#include <utility>

#include <facet/core/result.h>
#include <facet/gpu/context.h>
#include "core/guarded.h"

namespace facet {

VkImageSubresourceRange whole_range(const ImageDesc& desc) {
    return {aspect_of(desc.format), 0, desc.mip_levels, 0, desc.array_layers};
}

VkImageAspectFlags aspect_of(VkFormat format) {
    switch (format) {
        case VK_FORMAT_D16_UNORM:
        case VK_FORMAT_D32_SFLOAT:
        case VK_FORMAT_X8_D24_UNORM_PACK32:
            return VK_IMAGE_ASPECT_DEPTH_BIT;
        case VK_FORMAT_D24_UNORM_S8_UINT:
        case VK_FORMAT_D32_SFLOAT_S8_UINT:
        case VK_FORMAT_D16_UNORM_S8_UINT:
            return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
        default:
            return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

uint32_t bytes_per_texel(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8_UNORM: return 1;
        case VK_FORMAT_R8G8_UNORM:
        case VK_FORMAT_R16_SFLOAT:
        case VK_FORMAT_D16_UNORM: return 2;
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_R8G8B8A8_SRGB:
        case VK_FORMAT_B8G8R8A8_UNORM:
        case VK_FORMAT_B8G8R8A8_SRGB:
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_R32_UINT:
        case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
        case VK_FORMAT_D32_SFLOAT:
        case VK_FORMAT_X8_D24_UNORM_PACK32: return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT: return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
        default:
            throw UsageError("bytes_per_texel: unsupported VkFormat " +
                             std::to_string(static_cast<int>(format)));
    }
}

// ---- Buffer ----

Buffer::Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
               const std::string& name)
    : context_(&context), size_(size), usage_(usage) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    vk_check(vkCreateBuffer(context.device(), &info, nullptr, &buffer_), ("vkCreateBuffer " + name).c_str());
    Result<Allocation> allocation = context.allocator().allocate_for(buffer_, memory);
    if (!allocation) {
        vkDestroyBuffer(context.device(), buffer_, nullptr);
        buffer_ = VK_NULL_HANDLE;
        throw VulkanError(Error{"buffer '" + name + "': " + allocation.error().message, allocation.error().vk_result});
    }
    allocation_ = *allocation;
    context.set_name(buffer_, VK_OBJECT_TYPE_BUFFER, name);
}

Result<Buffer> Buffer::create(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
                              const std::string& name) {
    return guarded([&]() -> Result<Buffer> { return Buffer(context, size, usage, memory, name); });
}

Buffer::~Buffer() { reset(); }

Buffer::Buffer(Buffer&& other) noexcept
    : context_(other.context_),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      size_(other.size_),
      usage_(other.usage_),
      allocation_(std::exchange(other.allocation_, Allocation{})) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        reset();
        context_ = other.context_;
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        size_ = other.size_;
        usage_ = other.usage_;
        allocation_ = std::exchange(other.allocation_, Allocation{});
    }
    return *this;
}

void Buffer::reset() {
    if (!buffer_) return;
    vkDestroyBuffer(context_->device(), buffer_, nullptr);
    context_->allocator().free(allocation_);
    buffer_ = VK_NULL_HANDLE;
}

Status Buffer::flush() const { return context_ ? context_->allocator().flush(allocation_) : Status(Ok{}); }
Status Buffer::invalidate() const {
    return context_ ? context_->allocator().invalidate(allocation_) : Status(Ok{});
}

// ---- Image ----

Image::Image(Context& context, const ImageDesc& desc, VkImageUsageFlags usage, const std::string& name)
    : context_(&context), desc_(desc), usage_(usage), name_(name) {
    if (desc.width == 0 || desc.height == 0 || desc.mip_levels == 0 || desc.array_layers == 0)
        throw UsageError("image '" + name + "' has a zero size, mip count or layer count");
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.flags = desc.cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.width, desc.height, 1};
    info.mipLevels = desc.mip_levels;
    info.arrayLayers = desc.array_layers;
    info.samples = desc.samples;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    vk_check(vkCreateImage(context.device(), &info, nullptr, &image_), ("vkCreateImage " + name).c_str());
    Result<Allocation> allocation = context.allocator().allocate_for(image_, MemoryUsage::gpu_only);
    if (!allocation) {
        vkDestroyImage(context.device(), image_, nullptr);
        image_ = VK_NULL_HANDLE;
        throw VulkanError(Error{"image '" + name + "': " + allocation.error().message, allocation.error().vk_result});
    }
    allocation_ = *allocation;
    context.set_name(image_, VK_OBJECT_TYPE_IMAGE, name);
}

Result<Image> Image::create(Context& context, const ImageDesc& desc, VkImageUsageFlags usage,
                            const std::string& name) {
    return guarded([&]() -> Result<Image> { return Image(context, desc, usage, name); });
}

Image::~Image() { reset(); }

Image::Image(Image&& other) noexcept
    : context_(other.context_),
      image_(std::exchange(other.image_, VK_NULL_HANDLE)),
      desc_(other.desc_),
      usage_(other.usage_),
      name_(std::move(other.name_)),
      allocation_(std::exchange(other.allocation_, Allocation{})),
      views_(std::move(other.views_)) {
    other.views_.clear();
}

Image& Image::operator=(Image&& other) noexcept {
    if (this != &other) {
        reset();
        context_ = other.context_;
        image_ = std::exchange(other.image_, VK_NULL_HANDLE);
        desc_ = other.desc_;
        usage_ = other.usage_;
        name_ = std::move(other.name_);
        allocation_ = std::exchange(other.allocation_, Allocation{});
        views_ = std::move(other.views_);
        other.views_.clear();
    }
    return *this;
}

void Image::reset() {
    if (!image_) return;
    for (const CachedView& v : views_) vkDestroyImageView(context_->device(), v.view, nullptr);
    views_.clear();
    vkDestroyImage(context_->device(), image_, nullptr);
    context_->allocator().free(allocation_);
    image_ = VK_NULL_HANDLE;
}

VkImageView Image::make_view(VkImageSubresourceRange range, VkImageViewType type) {
    if (range.levelCount == VK_REMAINING_MIP_LEVELS) range.levelCount = desc_.mip_levels - range.baseMipLevel;
    if (range.layerCount == VK_REMAINING_ARRAY_LAYERS)
        range.layerCount = desc_.array_layers - range.baseArrayLayer;
    if (type == VK_IMAGE_VIEW_TYPE_MAX_ENUM) {
        if (desc_.cube && range.layerCount % 6 == 0)
            type = range.layerCount == 6 ? VK_IMAGE_VIEW_TYPE_CUBE : VK_IMAGE_VIEW_TYPE_CUBE_ARRAY;
        else
            type = range.layerCount == 1 ? VK_IMAGE_VIEW_TYPE_2D : VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    }
    for (const CachedView& v : views_)
        if (v.type == type && v.range.aspectMask == range.aspectMask &&
            v.range.baseMipLevel == range.baseMipLevel && v.range.levelCount == range.levelCount &&
            v.range.baseArrayLayer == range.baseArrayLayer && v.range.layerCount == range.layerCount)
            return v.view;
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = image_;
    info.viewType = type;
    info.format = desc_.format;
    info.subresourceRange = range;
    VkImageView view = VK_NULL_HANDLE;
    vk_check(vkCreateImageView(context_->device(), &info, nullptr, &view), ("vkCreateImageView " + name_).c_str());
    context_->set_name(view, VK_OBJECT_TYPE_IMAGE_VIEW,
                       name_ + " mips " + std::to_string(range.baseMipLevel) + "+" +
                           std::to_string(range.levelCount) + " layers " +
                           std::to_string(range.baseArrayLayer) + "+" + std::to_string(range.layerCount));
    views_.push_back({range, type, view});
    return view;
}

Result<VkImageView> Image::view(VkImageSubresourceRange range, VkImageViewType type) {
    return guarded([&]() -> Result<VkImageView> { return make_view(range, type); });
}

// ---- Sampler ----

Result<Sampler> Sampler::create(Context& context, VkFilter filter, bool mipmaps, bool repeat_u,
                                const std::string& name) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = filter == VK_FILTER_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = repeat_u ? VK_SAMPLER_ADDRESS_MODE_REPEAT : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.maxLod = mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
    return create(context, info, name);
}

Result<Sampler> Sampler::create(Context& context, const VkSamplerCreateInfo& info, const std::string& name) {
    return guarded([&]() -> Result<Sampler> { return Sampler(context, info, name); });
}

Sampler::Sampler(Context& context, const VkSamplerCreateInfo& info, const std::string& name) : context_(&context) {
    vk_check(vkCreateSampler(context.device(), &info, nullptr, &sampler_), ("vkCreateSampler " + name).c_str());
    context.set_name(sampler_, VK_OBJECT_TYPE_SAMPLER, name);
}

Sampler::~Sampler() {
    if (sampler_) vkDestroySampler(context_->device(), sampler_, nullptr);
}

Sampler::Sampler(Sampler&& other) noexcept
    : context_(other.context_), sampler_(std::exchange(other.sampler_, VK_NULL_HANDLE)) {}

Sampler& Sampler::operator=(Sampler&& other) noexcept {
    if (this != &other) {
        if (sampler_) vkDestroySampler(context_->device(), sampler_, nullptr);
        context_ = other.context_;
        sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
    }
    return *this;
}

}  // namespace facet
