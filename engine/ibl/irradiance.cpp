#include <facet/ibl/irradiance.h>

#include <cmath>
#include <vector>

#include <facet/gpu/resources.h>
#include "ibl/cube_texel_list.h"
#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>

namespace facet {

namespace {

constexpr VkImageViewType array_view = cube_array_view;

// Caps up to this radius (radians) are taken as flat disks where a horizon cuts them
// (shaders/ibl/irradiance_convolve.comp): within 6e-4 of the exact clipped cosine.
constexpr double kNarrowCapSpread = 0.2;

// convolve and blur: list the texels of a small level, then convolve with the list.
// The list to convolve: the equirect's texels when given and fine enough that each
// texel is a small cap (entries model texels as caps, which a texel spanning more than
// a hemisphere is not), else a small cube level's.
Result<CubeTexelList> texel_list(RenderGraph& graph, ProgramCache& programs, ImageHandle environment,
                                 ImageHandle equirect, const IrradianceSettings& s, const std::string& name) {
    if (equirect.valid() && graph.resource(equirect).image_desc.height >= 16)
        return add_equirect_texel_list_pass(graph, programs, equirect, 6 * s.source_size * s.source_size, name);
    const ImageDesc& env = graph.resource(environment).image_desc;
    return add_cube_texel_list_pass(graph, programs, environment,
                                    level_at_most(env.width, env.mip_levels, s.source_size), name);
}

Result<ImageHandle> add_texel_convolution(RenderGraph& graph, ProgramCache& programs, ImageHandle environment,
                                          ImageHandle equirect, ImageHandle irradiance, const IrradianceSettings& s) {
    struct Params {
        uint32_t texel_count, gaussian;
        float sigma;
    };
    auto list = texel_list(graph, programs, environment, equirect, s, "irradiance texel list");
    if (!list) return list.error();
    const bool blur = s.method == IrradianceMethod::blur;
    // Narrow caps (every list but a tiny input's) cross a horizon as flat disks: lavapipe
    // pays for the exact form at every entry, whichever normal needs it.
    std::vector<ShaderDefine> defines = list_shader_defines(programs.context(), "FACET_IRRADIANCE_TEXELS");
    if (!blur && list->max_spread < kNarrowCapSpread) defines.push_back({"FACET_NARROW_CAPS", "1"});
    const uint32_t per_invocation = texels_per_invocation(programs.context());
    auto convolve = programs.compute("ibl/irradiance_convolve.comp", defines);
    if (!convolve) return convolve.error();
    const Params params{list->count, blur ? 1u : 0u, s.blur_sigma};
    ImageHandle written;
    graph.add_compute_pass(blur ? "irradiance blur" : "irradiance convolve", [&](PassBuilder& b) {
        b.read(list->buffer);
        written = b.write_storage(irradiance);
    }, [p = *convolve, texels = list->buffer, irradiance, params, n = s.size, per_invocation](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(texels)),
                                          DescriptorWrite::storage_image(pc.view(irradiance, {}, array_view))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), params);
        dispatch_cube_faces(pc, *p, n, 0, 6, per_invocation);
    });
    return written;
}

// sh9: project the texel list on 9 SH functions, reduce, choose the window, evaluate.
Result<ImageHandle> add_sh9(RenderGraph& graph, ProgramCache& programs, ImageHandle environment, ImageHandle equirect,
                            ImageHandle irradiance, const IrradianceSettings& s, BufferHandle* coefficients_out) {
    auto project = programs.compute("ibl/sh9_project.comp");
    if (!project) return project.error();
    struct ReduceParams {
        uint32_t group_count, windowing;
    };
    auto reduce = programs.compute("ibl/sh9_reduce.comp");
    if (!reduce) return reduce.error();
    auto evaluate = programs.compute("ibl/sh9_irradiance.comp");
    if (!evaluate) return evaluate.error();
    auto list = texel_list(graph, programs, environment, equirect, s, "sh9 texel list");
    if (!list) return list.error();
    // One partial sum per workgroup of the projection (sh9_reduce adds them).
    const uint32_t groups = group_count(list->count, (*project)->workgroup_size()[0]);
    auto partials = graph.create_buffer("sh9 partial sums", {VkDeviceSize(groups) * 9 * 16});
    auto coefficients = graph.create_buffer("sh9 coefficients", {10 * 16});
    graph.add_compute_pass("sh9 project", [&](PassBuilder& b) {
        b.read(list->buffer);
        partials = b.write(partials);
    }, [p = *project, texels = list->buffer, partials, count = list->count, groups](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(texels)),
                                          DescriptorWrite::storage_buffer(pc.buffer(partials))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), count);
        vkCmdDispatch(pc.cmd(), groups, 1, 1);
    });
    const ReduceParams params{groups, s.sh9_windowing ? 1u : 0u};
    graph.add_compute_pass("sh9 reduce and window", [&](PassBuilder& b) {
        b.read(partials);
        coefficients = b.write(coefficients);
    }, [p = *reduce, partials, coefficients, params](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(partials)),
                                          DescriptorWrite::storage_buffer(pc.buffer(coefficients))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), params);
        vkCmdDispatch(pc.cmd(), 1, 1, 1);
    });
    ImageHandle written;
    graph.add_compute_pass("sh9 irradiance", [&](PassBuilder& b) {
        b.read(coefficients);
        written = b.write_storage(irradiance);
    }, [p = *evaluate, coefficients, irradiance, n = s.size](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(coefficients)),
                                          DescriptorWrite::storage_image(pc.view(irradiance, {}, array_view))};
        p->push_descriptors(pc.cmd(), writes);
        dispatch_cube(pc, *p, n);
    });
    if (coefficients_out) *coefficients_out = coefficients;
    return written;
}

// riemann and lowmip: sample the environment cube through a sampler.
Result<ImageHandle> add_cube_sampling(RenderGraph& graph, ProgramCache& programs, const Sampler& sampler,
                                      ImageHandle environment, ImageHandle irradiance, const IrradianceSettings& s) {
    const bool riemann = s.method == IrradianceMethod::riemann;
    auto program = programs.compute(riemann ? "ibl/irradiance_riemann.comp" : "ibl/cube_sample_lod.comp");
    if (!program) return program.error();
    const ImageDesc& env = graph.resource(environment).image_desc;
    float parameter = s.riemann_step;
    if (!riemann) parameter = float(level_at_most(env.width, env.mip_levels, s.lowmip_size));
    if (riemann && !(s.riemann_step > 0.0f && s.riemann_step < 1.0f))
        return Error{"irradiance riemann: the step must be in (0, 1) radians"};
    ImageHandle written;
    graph.add_compute_pass(riemann ? "irradiance riemann" : "irradiance lowmip", [&](PassBuilder& b) {
        b.sample(environment);
        written = b.write_storage(irradiance);
    }, [p = *program, environment, irradiance, parameter, sampler = sampler.handle(), n = s.size](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::sampled_image(pc.view(environment), sampler),
                                          DescriptorWrite::storage_image(pc.view(irradiance, {}, array_view))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), parameter);
        dispatch_cube(pc, *p, n);
    });
    return written;
}

}  // namespace

uint32_t level_at_most(uint32_t size, uint32_t mip_levels, uint32_t max_face) {
    uint32_t level = 0;
    while (level + 1 < mip_levels && (size >> level) > max_face) ++level;
    return level;
}

Result<ImageHandle> add_irradiance_passes(RenderGraph& graph, ProgramCache& programs, const Sampler& cube_sampler,
                                          ImageHandle environment, ImageHandle irradiance,
                                          const IrradianceSettings& settings, BufferHandle* sh9_coefficients,
                                          ImageHandle equirect) {
    const ImageDesc& out = graph.resource(irradiance).image_desc;
    if (!out.cube || out.width != settings.size)
        return Error{"irradiance: the output must be a cube of face size " + std::to_string(settings.size)};
    switch (settings.method) {
        case IrradianceMethod::convolve:
        case IrradianceMethod::blur:
            return add_texel_convolution(graph, programs, environment, equirect, irradiance, settings);
        case IrradianceMethod::riemann:
        case IrradianceMethod::lowmip:
            return add_cube_sampling(graph, programs, cube_sampler, environment, irradiance, settings);
        case IrradianceMethod::sh9:
            return add_sh9(graph, programs, environment, equirect, irradiance, settings, sh9_coefficients);
    }
    return Error{"irradiance: unknown method"};
}

}  // namespace facet
