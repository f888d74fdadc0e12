#pragma once
// What a device can hold, so that sizes a user asks for (cube faces, LUTs, frames,
// environments) are refused with one clear message before any image is created, not
// met by a validation error or a multi-gigabyte allocation that fails half way.
#include <cstdint>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/core/units.h>
#include <facet/gpu/resources.h>

namespace facet {

class Context;

struct DeviceLimits {
    std::string device_name;
    uint32_t max_image_2d = 0;        // maxImageDimension2D
    uint32_t max_image_cube = 0;      // maxImageDimensionCube
    uint32_t max_framebuffer = 0;     // min(maxFramebufferWidth, maxFramebufferHeight)
    uint64_t max_allocation_bytes = 0;  // maxMemoryAllocationSize: one image or buffer
    uint64_t heap_bytes = 0;            // the largest device-local heap
    // MSAA sample counts colour and depth attachments both take (lavapipe: 1 and 4);
    // 0: not checked.
    VkSampleCountFlags sample_counts = 0;
};
DeviceLimits device_limits(const Context& context);

// Every mip level, layer and sample.
uint64_t image_bytes(const ImageDesc& desc);

struct NamedImage {
    std::string name;
    ImageDesc desc;
    bool attachment = false;  // rendered to: the framebuffer limits apply too
};

// Each image within the device's dimension and single-allocation limits, and all of
// them (plus `buffer_bytes`) within its largest heap. The error names the image, its
// size and the limit it breaks.
Status check_images_fit(const DeviceLimits& limits, const std::vector<NamedImage>& images, uint64_t buffer_bytes = 0);

// check_graph_fits (a graph's transient images and buffers) lives with the graph:
// facet/graph/compiled_graph.h.

}  // namespace facet
