// The graph's transient resources against the device's limits (gpu/device_limits.h):
// kept beside the graph so that the device layer does not depend on it.
#include <facet/gpu/device_limits.h>
#include <facet/graph/compiled_graph.h>

namespace facet {

Status check_graph_fits(const Context& context, const CompiledGraph& compiled) {
    std::vector<NamedImage> images;
    for (const PhysicalResource& p : compiled.physical_images)
        if (!p.imported)
            images.push_back({p.name, p.image_desc,
                              (p.image_usage & (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                                VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT)) != 0});
    uint64_t buffers = 0;
    for (const PhysicalResource& p : compiled.physical_buffers)
        if (!p.imported) buffers += p.buffer_desc.size;
    return check_images_fit(device_limits(context), images, buffers);
}

}  // namespace facet
