#include <facet/graph/transfer_passes.h>

#include <facet/graph/graph_run.h>

namespace facet {

ImageHandle add_upload_pass(RenderGraph& graph, const std::string& name, BufferHandle staging, ImageHandle image) {
    ImageHandle written;
    graph.add_transfer_pass(name, [&](PassBuilder& b) {
        b.read(staging, Access::transfer_src);
        written = b.copy_to(image, ImageRange::mip(0));
    }, [staging, image](PassContext& pc) {
        const ImageDesc& d = pc.desc(image);
        VkBufferImageCopy region{};
        region.imageSubresource = {aspect_of(d.format), 0, 0, 1};
        region.imageExtent = {d.width, d.height, 1};
        vkCmdCopyBufferToImage(pc.cmd(), pc.buffer(staging), pc.image(image), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &region);
    });
    return written;
}

}  // namespace facet
