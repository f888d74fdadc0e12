#include <facet/ibl/specular.h>

#include <algorithm>
#include <cmath>

#include <facet/core/shared_constants.h>
#include <facet/gpu/resources.h>
#include <facet/graph/graph_run.h>
#include "ibl/cube_texel_list.h"
#include <facet/ibl/irradiance.h>
#include <facet/shader/program_cache.h>

namespace facet {

namespace {

constexpr VkImageViewType specular_array_view = cube_array_view;

// The large sampled levels run face by face, a pass each: lavapipe runs one submission at a time,
// and a viewer's frame queued behind a level's whole cube (0.6-1 s for the first level of a
// sun sky) waited that long (docs: README "The viewer never stops drawing").
// Levels of faces under 64^2 take a few milliseconds: one pass for the cube.
constexpr uint32_t kSmallestSplitFace = 64;

// The passes of a level of face size n: (first face, face count, name) each.
struct FacePass {
    uint32_t first, count;
    std::string name;
};
std::vector<FacePass> face_passes(const std::string& level, uint32_t n) {
    if (n < kSmallestSplitFace) return {{0, 6, level}};
    std::vector<FacePass> passes;
    for (uint32_t face = 0; face < 6; ++face) passes.push_back({face, 1, level + " face " + std::to_string(face)});
    return passes;
}

}  // namespace

std::vector<float> specular_level_roughness(uint32_t levels) {
    std::vector<float> r(levels, 0.0f);
    for (uint32_t m = 1; m < levels; ++m) r[m] = float(m) / float(levels - 1);
    return r;
}

SpecularMethod specular_level_method(const SpecularSettings& s, float roughness) {
    if (s.method != SpecularMethod::automatic) return s.method;
    return roughness >= s.automatic_convolve_from ? SpecularMethod::convolve : SpecularMethod::filtered;
}

uint32_t convolve_source_size(float roughness) {
    // The lobe's full width at half maximum in l is about 2.6 alpha radians.
    const double alpha = std::max(double(roughness) * roughness, 1e-4);
    const double wanted = 4.0 * (pi / 2) / (2.6 * alpha);
    uint32_t size = 8;
    while (size < 64 && size < wanted) size *= 2;
    return size;
}

uint32_t first_needed_specular_level(const SpecularSettings& settings) {
    if (settings.levels <= 1 || settings.min_roughness <= 0.0f) return settings.first_level;
    const float lod = std::min(settings.min_roughness, 1.0f) * float(settings.levels - 1);
    return std::max(settings.first_level, std::min(uint32_t(std::floor(lod + 1e-5f)), settings.levels - 1));
}

Result<ImageHandle> add_specular_passes(RenderGraph& graph, ProgramCache& programs, const Sampler& cube_sampler,
                                        ImageHandle environment, ImageHandle specular, const SpecularSettings& s,
                                        ImageHandle equirect) {
    const ImageDesc env = graph.resource(environment).image_desc;
    const ImageDesc out = graph.resource(specular).image_desc;
    if (!out.cube || out.width != env.width || out.mip_levels != s.levels)
        return Error{"specular: the output must be a cube of the environment's face size with " +
                     std::to_string(s.levels) + " levels"};
    if (s.levels > env.mip_levels) return Error{"specular: more levels than the environment cube has"};
    if (s.sample_count == 0) return Error{"specular: sample count must be at least 1"};

    auto copy = programs.compute("ibl/cube_copy_level.comp");
    if (!copy) return copy.error();

    ImageHandle current = specular;
    const uint32_t first = first_needed_specular_level(s);
    const uint32_t end = s.end_level ? std::min(s.end_level, s.levels) : s.levels;
    if (first == 0 && end > 0) {
        graph.add_compute_pass("specular level 0 (copy)", [&](PassBuilder& b) {
            b.read_storage(environment, ImageRange::mip(0));
            current = b.write_storage(specular, ImageRange::mip(0));
        }, [p = *copy, environment, specular, n = env.width](PassContext& pc) {
            p->bind(pc.cmd());
            const DescriptorWrite writes[] = {
                DescriptorWrite::storage_image(pc.view(environment, ImageRange::mip(0), specular_array_view)),
                DescriptorWrite::storage_image(pc.view(specular, ImageRange::mip(0), specular_array_view))};
            p->push_descriptors(pc.cmd(), writes);
            dispatch_cube(pc, *p, n);
        });
    }

    const std::vector<float> roughness = specular_level_roughness(s.levels);
    for (uint32_t m = std::max(first, 1u); m < end; ++m) {
        const float r = roughness[m];
        const SpecularMethod method = specular_level_method(s, r);
        const uint32_t n = out.mip_width(m);
        const std::string name = "specular level " + std::to_string(m) + " (" + specular_method_name(method) + ")";
        if (method == SpecularMethod::convolve) {
            struct Params {
                uint32_t texel_count;
                float roughness;
            };
            auto conv = programs.compute("ibl/specular_convolve.comp");
            if (!conv) return conv.error();
            const uint32_t source = convolve_source_size(r);
            const bool from_equirect = equirect.valid() && graph.resource(equirect).image_desc.height >= 16;
            auto list = from_equirect
                            ? add_equirect_texel_list_pass(graph, programs, equirect, 6 * source * source, name + " texels")
                            : add_cube_texel_list_pass(graph, programs, environment,
                                                       level_at_most(env.width, env.mip_levels, source), name + " texels");
            if (!list) return list.error();
            const Params params{list->count, r};
            const BufferHandle texels = list->buffer;
            for (const FacePass& f : face_passes(name, n))
                graph.add_compute_pass(f.name, [&](PassBuilder& b) {
                    b.read(texels);
                    current = b.write_storage(current, ImageRange::mip(m));
                }, [p = *conv, texels, specular, m, n, params, f](PassContext& pc) {
                    p->bind(pc.cmd());
                    const DescriptorWrite writes[] = {
                        DescriptorWrite::storage_buffer(pc.buffer(texels)),
                        DescriptorWrite::storage_image(pc.view(specular, ImageRange::mip(m), specular_array_view))};
                    p->push_descriptors(pc.cmd(), writes);
                    p->push_constants(pc.cmd(), params);
                    dispatch_cube_faces(pc, *p, n, f.first, f.count);
                });
            continue;
        }
        if (method == SpecularMethod::mips) {
            auto sample = programs.compute("ibl/cube_sample_lod.comp");
            if (!sample) return sample.error();
            const float lod = r * float(env.mip_levels - 1);
            graph.add_compute_pass(name, [&](PassBuilder& b) {
                b.sample(environment);
                current = b.write_storage(current, ImageRange::mip(m));
            }, [p = *sample, environment, specular, m, n, lod, sampler = cube_sampler.handle()](PassContext& pc) {
                p->bind(pc.cmd());
                const DescriptorWrite writes[] = {
                    DescriptorWrite::sampled_image(pc.view(environment), sampler),
                    DescriptorWrite::storage_image(pc.view(specular, ImageRange::mip(m), specular_array_view))};
                p->push_descriptors(pc.cmd(), writes);
                p->push_constants(pc.cmd(), lod);
                dispatch_cube(pc, *p, n);
            });
            continue;
        }
        struct Params {
            uint32_t sample_count;
            float roughness;
            uint32_t filtered;
            float source_size;
        };
        auto sample = programs.compute("ibl/specular_importance.comp");
        if (!sample) return sample.error();
        const Params params{s.sample_count, r, method == SpecularMethod::filtered ? 1u : 0u, float(env.width)};
        for (const FacePass& f : face_passes(name, n))
            graph.add_compute_pass(f.name, [&](PassBuilder& b) {
                b.sample(environment);
                current = b.write_storage(current, ImageRange::mip(m));
            }, [p = *sample, environment, specular, m, n, params, f, sampler = cube_sampler.handle()](PassContext& pc) {
                p->bind(pc.cmd());
                const DescriptorWrite writes[] = {
                    DescriptorWrite::sampled_image(pc.view(environment), sampler),
                    DescriptorWrite::storage_image(pc.view(specular, ImageRange::mip(m), specular_array_view))};
                p->push_descriptors(pc.cmd(), writes);
                p->push_constants(pc.cmd(), params);
                dispatch_cube_faces(pc, *p, n, f.first, f.count);
            });
    }
    return current;
}

}  // namespace facet
