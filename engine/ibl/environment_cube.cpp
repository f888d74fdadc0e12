#include "ibl/environment_cube.h"

#include <string>

#include <facet/gpu/resources.h>
#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>
#include "ibl/cube_texel_list.h"

namespace facet {

uint32_t cube_size_for(uint32_t equirect_height) { return std::max(1u, equirect_height / 2); }

uint32_t full_mip_count(uint32_t size) {
    uint32_t mips = 1;
    while ((size >> mips) > 0) ++mips;
    return mips;
}

ImageDesc environment_cube_desc(uint32_t size, uint32_t mips) {
    ImageDesc d;
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = d.height = size;
    d.mip_levels = mips;
    d.array_layers = 6;
    d.cube = true;
    return d;
}

Status check_cube_mirror(const RenderGraph& graph, ImageHandle cube, const ImageHandle* mirror, const std::string& pass) {
    if (!mirror || !mirror->valid()) return Ok{};
    const ImageDesc& c = graph.resource(cube).image_desc;
    const ImageDesc& m = graph.resource(*mirror).image_desc;
    if (!m.cube || m.width != c.width || m.format != c.format)
        return Error{pass + ": the mirror image must be a cube of the same face size and format"};
    return Ok{};
}

Result<ImageHandle> add_environment_cube_passes(RenderGraph& graph, ProgramCache& programs,
                                                const Sampler& equirect_sampler, ImageHandle equirect,
                                                ImageHandle cube, uint32_t taps, const std::string& name,
                                                ImageHandle* mirror) {
    const bool with_mirror = mirror && mirror->valid();
    std::vector<ShaderDefine> defines;
    if (with_mirror) defines.push_back({"FACET_MIRROR", "1"});
    auto to_cube = programs.compute("ibl/equirect_to_cube.comp", defines);
    if (!to_cube) return to_cube.error();
    const ImageDesc desc = graph.resource(cube).image_desc;
    if (Status fits = check_cube_mirror(graph, cube, mirror, "equirect to cube"); !fits) return fits.error();
    const VkSampler sampler = equirect_sampler.handle();
    const VkImageViewType array = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    ImageHandle current, mirror_in = with_mirror ? *mirror : ImageHandle{}, mirror_out;
    graph.add_compute_pass(name.empty() ? "equirect to cube" : name, [&](PassBuilder& b) {
        b.sample(equirect, ImageRange::mip(0));
        current = b.write_storage(cube, ImageRange::mip(0));
        if (with_mirror) mirror_out = b.write_storage(mirror_in, ImageRange::mip(0));
    }, [p = *to_cube, equirect, cube, mirror_in, with_mirror, sampler, n = desc.width, array, taps](PassContext& pc) {
        p->bind(pc.cmd());
        std::vector<DescriptorWrite> writes = {
            DescriptorWrite::sampled_image(pc.view(equirect, ImageRange::mip(0)), sampler),
            DescriptorWrite::storage_image(pc.view(cube, ImageRange::mip(0), array))};
        if (with_mirror) writes.push_back(DescriptorWrite::storage_image(pc.view(mirror_in, ImageRange::mip(0), array)));
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), taps);
        dispatch_cube(pc, *p, n);
    });
    if (with_mirror) *mirror = mirror_out;
    return add_cube_mip_passes(graph, programs, current, name.empty() ? "cube mip " : name + " mip ");
}

Result<ImageHandle> add_cube_mip_passes(RenderGraph& graph, ProgramCache& programs, ImageHandle cube,
                                        const std::string& name) {
    auto downsample = programs.compute("ibl/cube_downsample.comp");
    if (!downsample) return downsample.error();
    const ImageDesc desc = graph.resource(cube).image_desc;
    const VkImageViewType array = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    ImageHandle current = cube;
    for (uint32_t m = 1; m < desc.mip_levels; ++m) {
        graph.add_compute_pass(name + std::to_string(m), [&](PassBuilder& b) {
            b.read_storage(current, ImageRange::mip(m - 1));
            current = b.write_storage(current, ImageRange::mip(m));
        }, [p = *downsample, cube, m, n = desc.mip_width(m), array](PassContext& pc) {
            p->bind(pc.cmd());
            const DescriptorWrite writes[] = {
                DescriptorWrite::storage_image(pc.view(cube, ImageRange::mip(m - 1), array)),
                DescriptorWrite::storage_image(pc.view(cube, ImageRange::mip(m), array))};
            p->push_descriptors(pc.cmd(), writes);
            dispatch_cube(pc, *p, n);
        });
    }
    return current;
}

}  // namespace facet
