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
    const VkDescriptorType bindings[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    auto pipeline = programs.compute("render/tonemap.comp", bindings, sizeof(Params));
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
        vkCmdDispatch(pc.cmd(), group_count(d.width, 8), group_count(d.height, 8), 1);
    });
    return written;
}

}  // namespace facet
