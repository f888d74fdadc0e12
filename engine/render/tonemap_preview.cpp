#include <facet/render/tonemap_preview.h>

#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>

namespace facet {

Result<ImageHandle> add_tonemap_preview_pass(RenderGraph& graph, ProgramCache& programs, ImageHandle hdr,
                                             ImageHandle ldr, float exposure) {
    auto pipeline = programs.compute("render/tonemap_preview.comp");
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
        const auto local = p->workgroup_size();
        vkCmdDispatch(pc.cmd(), group_count(d.width, local[0]), group_count(d.height, local[1]), 1);
    });
    return written;
}

}  // namespace facet
