#pragma once
// Owning wrappers for buffers, images and samplers: each destroys its Vulkan objects
// and frees its memory exactly once (move-only).
//
// Errors: create() returns an Error when the device fails (out of memory, naming the
// call, the object and the size); flush and invalidate likewise. UsageError marks
// programmer misuse (a zero size, mip or layer count; a format bytes_per_texel does not
// know). Thread safety: objects may be
// created and destroyed on several threads at once (Context); one object belongs to one
// thread at a time.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/gpu/memory.h>

namespace facet {

class Context;

struct ImageDesc {
    VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t mip_levels = 1;
    uint32_t array_layers = 1;  // 6 for a cube
    bool cube = false;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;

    bool operator==(const ImageDesc&) const = default;
    uint32_t mip_width(uint32_t mip) const { return width > (1u << mip) ? width >> mip : 1u; }
    uint32_t mip_height(uint32_t mip) const { return height > (1u << mip) ? height >> mip : 1u; }
};

// Every mip level and layer.
VkImageSubresourceRange whole_range(const ImageDesc& desc);
VkImageAspectFlags aspect_of(VkFormat format);
uint32_t bytes_per_texel(VkFormat format);  // throws UsageError for formats it does not know

class Buffer {
public:
    Buffer() = default;  // empty (no buffer): a placeholder to assign a created one to
    static Result<Buffer> create(Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                                 MemoryUsage memory, const std::string& name);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    VkBufferUsageFlags usage() const { return usage_; }
    // Host pointer (upload/readback memory only); call invalidate() before reading.
    void* mapped() const { return allocation_.mapped; }
    Status flush() const;
    Status invalidate() const;
    explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

private:
    Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
           const std::string& name);  // throws internally; create() returns the Error
    void reset();
    Context* context_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    VkBufferUsageFlags usage_ = 0;
    Allocation allocation_;
};

class Image {
public:
    Image() = default;  // empty (no image): a placeholder to assign a created one to
    static Result<Image> create(Context& context, const ImageDesc& desc, VkImageUsageFlags usage,
                                const std::string& name);
    ~Image();
    Image(Image&& other) noexcept;
    Image& operator=(Image&& other) noexcept;

    VkImage handle() const { return image_; }
    const ImageDesc& desc() const { return desc_; }
    VkImageUsageFlags usage() const { return usage_; }
    explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

    // A view of some mips/layers (cached; owned by the image). view_type
    // VK_IMAGE_VIEW_TYPE_MAX_ENUM means: cube for cube images, else 2D / 2D array.
    // Creating a view fails only when the driver runs out of memory: an Error.
    // (Inside a pass, PassContext::view gives views of the graph's images.)
    Result<VkImageView> view(VkImageSubresourceRange range,
                             VkImageViewType view_type = VK_IMAGE_VIEW_TYPE_MAX_ENUM);
    Result<VkImageView> view() { return view(whole_range(desc_)); }

private:
    friend class GraphRun;
    VkImageView make_view(VkImageSubresourceRange range, VkImageViewType view_type);  // throws internally
    Image(Context& context, const ImageDesc& desc, VkImageUsageFlags usage,
          const std::string& name);  // throws internally; create() returns the Error
    void reset();
    struct CachedView {
        VkImageSubresourceRange range;
        VkImageViewType type;
        VkImageView view;
    };
    Context* context_ = nullptr;
    VkImage image_ = VK_NULL_HANDLE;
    ImageDesc desc_;
    VkImageUsageFlags usage_ = 0;
    std::string name_;
    Allocation allocation_;
    std::vector<CachedView> views_;
};

class Sampler {
public:
    Sampler() = default;  // empty (no sampler): a placeholder to assign a created one to
    // Clamp-to-edge on all axes (repeat in u when repeat_u: equirect longitude).
    static Result<Sampler> create(Context& context, VkFilter filter, bool mipmaps, bool repeat_u,
                                  const std::string& name);
    // Any other state (e.g. a glTF sampler's filters and wraps).
    static Result<Sampler> create(Context& context, const VkSamplerCreateInfo& info, const std::string& name);
    ~Sampler();
    Sampler(Sampler&& other) noexcept;
    Sampler& operator=(Sampler&& other) noexcept;
    VkSampler handle() const { return sampler_; }
    explicit operator bool() const { return sampler_ != VK_NULL_HANDLE; }

private:
    Sampler(Context& context, const VkSamplerCreateInfo& info, const std::string& name);
    Context* context_ = nullptr;
    VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace facet
