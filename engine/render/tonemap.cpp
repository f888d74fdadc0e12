#include <facet/render/tonemap.h>

#include <facet/gpu/resources.h>
#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>

namespace facet {

Result<ImageHandle> add_tonemap_pass(RenderGraph& graph, ProgramCache& programs, const Sampler& nearest,
                                     ImageHandle hdr, ImageHandle ldr, const DisplaySettings& display) {
    struct Params {
        float exposure;
        uint32_t tonemap;
        float gamma;
    };
    auto pipeline = programs.compute("render/tonemap.comp");
    if (!pipeline) return pipeline.error();
    ImageHandle written;
    graph.add_compute_pass("tonemap", [&](PassBuilder& b) {
        b.sample(hdr, ImageRange::mip(0));
        written = b.write_storage(ldr, ImageRange::mip(0));
    }, [p = pipeline.value(), hdr, ldr, sampler = nearest.handle(), display](PassContext& pc) {
        const ImageDesc& d = pc.desc(ldr);
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::sampled_image(pc.view(hdr, ImageRange::mip(0)), sampler),
                                          DescriptorWrite::storage_image(pc.view(ldr, ImageRange::mip(0)))};
        p->push_descriptors(pc.cmd(), writes);
        const Params params{display.exposure, uint32_t(display.tonemap), display.gamma};
        p->push_constants(pc.cmd(), params);
        const auto local = p->workgroup_size();
        vkCmdDispatch(pc.cmd(), group_count(d.width, local[0]), group_count(d.height, local[1]), 1);
    });
    return written;
}

}  // namespace facet
