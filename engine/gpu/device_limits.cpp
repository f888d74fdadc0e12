#include <facet/gpu/device_limits.h>

#include <algorithm>
#include <cstdio>

#include <facet/gpu/context.h>

namespace facet {

namespace {

std::string describe(const ImageDesc& d) {
    std::string text = std::to_string(d.width) + "x" + std::to_string(d.height);
    if (d.cube) text += " cube";
    else if (d.array_layers > 1) text += " x " + std::to_string(d.array_layers) + " layers";
    if (d.mip_levels > 1) text += ", " + std::to_string(d.mip_levels) + " mips";
    if (d.samples > 1) text += ", " + std::to_string(int(d.samples)) + " samples";
    return text;
}

uint32_t texel_bytes(VkFormat format) {
    try {
        return bytes_per_texel(format);
    } catch (const UsageError&) {
        return 16;  // the widest format Facet uses; errs on the side of refusing
    }
}

}  // namespace

DeviceLimits device_limits(const Context& context) {
    DeviceLimits l;
    const VkPhysicalDeviceLimits& p = context.properties().limits;
    l.device_name = context.device_name();
    l.max_image_2d = p.maxImageDimension2D;
    l.max_image_cube = p.maxImageDimensionCube;
    l.max_framebuffer = std::min(p.maxFramebufferWidth, p.maxFramebufferHeight);
    l.sample_counts = p.framebufferColorSampleCounts & p.framebufferDepthSampleCounts;
    VkPhysicalDeviceMaintenance3Properties maintenance3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &maintenance3};
    vkGetPhysicalDeviceProperties2(context.physical_device(), &properties);
    l.max_allocation_bytes = maintenance3.maxMemoryAllocationSize;
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(context.physical_device(), &memory);
    for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
        if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            l.heap_bytes = std::max<uint64_t>(l.heap_bytes, memory.memoryHeaps[h].size);
    return l;
}

uint64_t image_bytes(const ImageDesc& d) {
    uint64_t texels = 0;
    for (uint32_t m = 0; m < std::max(d.mip_levels, 1u); ++m) texels += uint64_t(d.mip_width(m)) * d.mip_height(m);
    return texels * std::max(d.array_layers, 1u) * uint64_t(std::max<int>(d.samples, 1)) * texel_bytes(d.format);
}

Status check_images_fit(const DeviceLimits& limits, const std::vector<NamedImage>& images, uint64_t buffer_bytes) {
    const std::string device = " on " + limits.device_name;
    uint64_t total = buffer_bytes;
    const NamedImage* largest = nullptr;
    for (const NamedImage& image : images) {
        const ImageDesc& d = image.desc;
        const uint32_t side = std::max(d.width, d.height);
        const uint32_t max_side = d.cube ? limits.max_image_cube : limits.max_image_2d;
        const char* limit_name = d.cube ? "maxImageDimensionCube" : "maxImageDimension2D";
        if (side > max_side)
            return Error{image.name + " (" + describe(d) + ") is larger than the device allows" + device + ": " +
                         limit_name + " is " + std::to_string(max_side)};
        if (image.attachment && side > limits.max_framebuffer)
            return Error{image.name + " (" + describe(d) + ") is larger than a framebuffer may be" + device + " (" +
                         std::to_string(limits.max_framebuffer) + ")"};
        if (d.samples > 1 && limits.sample_counts && !(limits.sample_counts & d.samples)) {
            std::string offered;
            for (uint32_t n = 1; n <= 64; n *= 2)
                if (limits.sample_counts & n) offered += (offered.empty() ? "" : ", ") + std::to_string(n);
            return Error{image.name + " (" + describe(d) + "): the device does not render " +
                         std::to_string(int(d.samples)) + " samples" + device + " (it offers " + offered + ")"};
        }
        const uint64_t bytes = image_bytes(d);
        if (limits.max_allocation_bytes && bytes > limits.max_allocation_bytes)
            return Error{image.name + " (" + describe(d) + ") needs " + format_bytes(bytes) +
                         ", more than one allocation may hold" + device + " (maxMemoryAllocationSize " +
                         format_bytes(limits.max_allocation_bytes) + ")"};
        total += bytes;
        if (!largest || bytes > image_bytes(largest->desc)) largest = &image;
    }
    if (limits.heap_bytes && total > limits.heap_bytes)
        return Error{"the images need " + format_bytes(total) + " of GPU memory together (the largest, " +
                     largest->name + ", " + describe(largest->desc) + ": " + format_bytes(image_bytes(largest->desc)) +
                     "), more than the device's largest memory heap" + device + " (" + format_bytes(limits.heap_bytes) +
                     ")"};
    return Ok{};
}

}  // namespace facet
