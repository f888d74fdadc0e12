#include <facet/ibl/brdf_lut.h>

#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>

namespace facet {

Result<ImageHandle> add_brdf_lut_passes(RenderGraph& graph, ProgramCache& programs, const BrdfLutSettings& settings,
                                        ImageHandle lut) {
    if (settings.sample_count == 0) return Error{"BRDF LUT: sample count must be at least 1"};
    struct Params {
        uint32_t sample_count, brdf;
    } params{settings.sample_count, static_cast<uint32_t>(settings.brdf)};
    auto split_sum = programs.compute("ibl/brdf_lut.comp");
    if (!split_sum) return split_sum.error();
    auto energy = programs.compute("ibl/brdf_lut_energy.comp");
    if (!energy) return energy.error();

    ImageHandle scale_bias;
    graph.add_compute_pass("brdf lut", [&](PassBuilder& b) { scale_bias = b.write_storage(lut); },
                           [p = *split_sum, params, lut](PassContext& pc) {
                               const ImageDesc& d = pc.desc(lut);
                               p->bind(pc.cmd());
                               const DescriptorWrite writes[] = {DescriptorWrite::storage_image(pc.view(lut))};
                               p->push_descriptors(pc.cmd(), writes);
                               p->push_constants(pc.cmd(), params);
                               const auto local = p->workgroup_size();
                               vkCmdDispatch(pc.cmd(), group_count(d.width, local[0]),
                                             group_count(d.height, local[1]), 1);
                           });
    ImageHandle with_energy;
    graph.add_compute_pass("brdf lut energy", [&](PassBuilder& b) { with_energy = b.read_write_storage(scale_bias); },
                           [p = *energy, lut](PassContext& pc) {
                               p->bind(pc.cmd());
                               const DescriptorWrite writes[] = {DescriptorWrite::storage_image(pc.view(lut))};
                               p->push_descriptors(pc.cmd(), writes);
                               // One invocation per row of the LUT.
                               vkCmdDispatch(pc.cmd(), group_count(pc.desc(lut).height, p->workgroup_size()[0]), 1, 1);
                           });
    return with_energy;
}

}  // namespace facet
