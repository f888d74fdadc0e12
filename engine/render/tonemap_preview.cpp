#include <facet/render/tonemap_preview.h>

#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>

namespace facet {

Result<ImageHandle> add_tonemap_preview_pass(RenderGraph& graph, ProgramCache& programs, ImageHandle hdr,
                                             ImageHandle ldr, float exposure) {
    const VkDescriptorType bindings[] = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    auto pipeline = programs.compute("render/tonemap_preview.comp", bindings, sizeof(float));
    if (!pipeline) return pipeline.error();
    ImageHandle written;
    graph.add_compute_pass("tonemap preview", [&](PassBuilder& b) {
        b.read_storage(hdr, ImageRange::mip(0));
        written = b.write_storage(ldr, ImageRange::mip(0));
    }, [p = pipeline.value(), hdr, ldr, exposure](PassContext& pc) {
        const ImageDesc& d = pc.desc(ldr);
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_image(pc.view(hdr, ImageRange::mip(0))),
                                          DescriptorWrite::storage_image(pc.view(ldr, ImageRange::mip(0)))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), exposure);
        vkCmdDispatch(pc.cmd(), group_count(d.width, 8), group_count(d.height, 8), 1);
    });
    return written;
}

}  // namespace facet
