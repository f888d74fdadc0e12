#include "ibl/irradiance.h"

#include <cmath>

#include "gpu/resources.h"
#include "ibl/cube_texel_list.h"
#include "graph/graph_run.h"
#include "shader/program_cache.h"

namespace facet {

namespace {

constexpr VkImageViewType array_view = cube_array_view;

// convolve and blur: list the texels of a small level, then convolve with the list.
Result<ImageHandle> add_texel_convolution(RenderGraph& graph, ProgramCache& programs, ImageHandle environment,
                                          ImageHandle irradiance, const IrradianceSettings& s) {
    const VkDescriptorType conv_bindings[] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    struct Params {
        uint32_t texel_count, gaussian;
        float sigma;
    };
    auto convolve = programs.compute("ibl/irradiance_convolve.comp", conv_bindings, sizeof(Params));
    if (!convolve) return convolve.error();
    const ImageDesc& env = graph.resource(environment).image_desc;
    auto list = add_cube_texel_list_pass(graph, programs, environment,
                                         level_at_most(env.width, env.mip_levels, s.source_size),
                                         "irradiance texel list");
    if (!list) return list.error();
    const bool blur = s.method == IrradianceMethod::blur;
    const Params params{list->count, blur ? 1u : 0u, s.blur_sigma};
    ImageHandle written;
    graph.add_compute_pass(blur ? "irradiance blur" : "irradiance convolve", [&](PassBuilder& b) {
        b.read(list->buffer);
        written = b.write_storage(irradiance);
    }, [p = *convolve, texels = list->buffer, irradiance, params, n = s.size](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(texels)),
                                          DescriptorWrite::storage_image(pc.view(irradiance, {}, array_view))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), params);
        dispatch_cube(pc, n);
    });
    return written;
}

// riemann and lowmip: sample the environment cube through a sampler.
Result<ImageHandle> add_cube_sampling(RenderGraph& graph, ProgramCache& programs, const Sampler& sampler,
                                      ImageHandle environment, ImageHandle irradiance, const IrradianceSettings& s) {
    const bool riemann = s.method == IrradianceMethod::riemann;
    const VkDescriptorType bindings[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    auto program =
        programs.compute(riemann ? "ibl/irradiance_riemann.comp" : "ibl/cube_sample_lod.comp", bindings, sizeof(float));
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
        dispatch_cube(pc, n);
    });
    return written;
}

}  // namespace

const char* irradiance_method_name(IrradianceMethod method) {
    switch (method) {
        case IrradianceMethod::convolve: return "convolve";
        case IrradianceMethod::riemann: return "riemann";
        case IrradianceMethod::blur: return "blur";
        case IrradianceMethod::lowmip: return "lowmip";
    }
    return "?";
}

std::optional<IrradianceMethod> parse_irradiance_method(const std::string& name) {
    for (auto m : {IrradianceMethod::convolve, IrradianceMethod::riemann, IrradianceMethod::blur, IrradianceMethod::lowmip})
        if (name == irradiance_method_name(m)) return m;
    return std::nullopt;
}

uint32_t level_at_most(uint32_t size, uint32_t mip_levels, uint32_t max_face) {
    uint32_t level = 0;
    while (level + 1 < mip_levels && (size >> level) > max_face) ++level;
    return level;
}

Result<ImageHandle> add_irradiance_passes(RenderGraph& graph, ProgramCache& programs, const Sampler& cube_sampler,
                                          ImageHandle environment, ImageHandle irradiance,
                                          const IrradianceSettings& settings) {
    const ImageDesc& out = graph.resource(irradiance).image_desc;
    if (!out.cube || out.width != settings.size)
        return Error{"irradiance: the output must be a cube of face size " + std::to_string(settings.size)};
    switch (settings.method) {
        case IrradianceMethod::convolve:
        case IrradianceMethod::blur:
            return add_texel_convolution(graph, programs, environment, irradiance, settings);
        case IrradianceMethod::riemann:
        case IrradianceMethod::lowmip:
            return add_cube_sampling(graph, programs, cube_sampler, environment, irradiance, settings);
    }
    return Error{"irradiance: unknown method"};
}

}  // namespace facet
