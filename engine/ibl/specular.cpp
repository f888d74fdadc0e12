#include <facet/ibl/specular.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <facet/core/shared_constants.h>
#include <facet/gpu/resources.h>
#include <facet/graph/graph_run.h>
#include "ibl/cube_texel_list.h"
#include "ibl/environment_cube.h"
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

// The hybrid method's split of the environment (shaders/ibl/specular_excess*.comp): the
// residual cube with its mips, and the excess per block of the finest size a level needs.
// Excess blocks span at most kExcessBlockPerAlpha x alpha radians (about 0.7 degrees at
// roughness 0.2): a sun sky's level 0.2 is then 0.3% off the truth, 0.02% with one texel
// per block, 2-3% with blocks twice as wide (the entries are points of the lobe).
constexpr double kExcessBlockPerAlpha = 0.31;
// A level whose list is longer (wide bright regions: a studio's softboxes, a warehouse's
// windows) reads the list of blocks twice as wide instead: each entry costs about half a
// filtered sample per texel, and wide regions are smooth where a sun is not.
constexpr uint32_t kMostExcessEntries = 256;

uint32_t excess_block(double texel_angle, float roughness) {
    const double alpha = std::max(double(roughness) * roughness, 1e-4);
    uint32_t block = 1;
    while (block < 64 && 2 * block * texel_angle <= kExcessBlockPerAlpha * alpha) block *= 2;
    return block;
}

double hybrid_samples(uint32_t count, float roughness, uint32_t source_size, std::vector<float>& out);

struct ExcessSplit {
    ImageHandle residual;
    uint32_t residual_size = 0;    // its face size (the environment's, or half of it)
    BufferHandle blocks;           // the finest grid: 2 vec4 per block
    uint32_t grid_x = 0, grid_y = 0;  // its blocks per row and column (the input's; 0: the cube's)
    uint32_t block = 1;            // its block size in texels
    double texel_angle = 0;        // the source's texel width at its widest, in radians
    std::vector<std::pair<uint32_t, BufferHandle>> lists;  // per merge factor
};

Result<ExcessSplit> add_excess_split(RenderGraph& graph, ProgramCache& programs, ImageHandle environment,
                                     ImageHandle equirect, const Sampler* equirect_sampler, const SpecularSettings& s,
                                     float smallest_roughness) {
    const ImageDesc env = graph.resource(environment).image_desc;
    const uint32_t top = env.mip_levels - 1;
    struct Params {
        uint32_t block;
        float factor;
    };
    ExcessSplit out;
    out.residual_size = env.width;
    if (equirect.valid() && equirect_sampler) {
        // The residual at half the face size when no sample of the smoothest hybrid level
        // reads the full-size level (lod >= 1 everywhere: at the default sample count from
        // roughness about 0.15 up); half the texels to resample and a smaller mip chain to read.
        std::vector<float> table;
        hybrid_samples(s.hybrid_sample_count, smallest_roughness, env.width, table);
        float lowest = 1e30f;
        for (size_t i = 3; i < table.size(); i += 4) lowest = std::min(lowest, table[i]);
        if (lowest >= 1.0f && env.width >= 2 && env.mip_levels >= 2) out.residual_size = env.width / 2;
    }
    ImageDesc residual_desc = env;
    if (out.residual_size != env.width) {
        residual_desc.width = residual_desc.height = out.residual_size;
        residual_desc.mip_levels = env.mip_levels - 1;
    }
    ImageHandle residual = graph.create_image("specular residual", residual_desc);
    if (equirect.valid() && equirect_sampler) {
        // Split the input itself, then resample the residual to a cube.
        auto split = programs.compute("ibl/specular_excess_equirect.comp");
        if (!split) return split.error();
        const ImageDesc& d = graph.resource(equirect).image_desc;
        out.texel_angle = 2.0 * pi / d.width;
        out.block = excess_block(out.texel_angle, smallest_roughness);
        const uint32_t bx = (d.width + out.block - 1) / out.block, by = (d.height + out.block - 1) / out.block;
        out.grid_x = bx;
        out.grid_y = by;
        out.blocks = graph.create_buffer("specular excess blocks", {VkDeviceSize(bx) * by * 32});
        ImageHandle flat = graph.create_image("specular residual (input)", d);
        const Params params{out.block, s.excess_factor};
        graph.add_compute_pass("specular excess", [&](PassBuilder& b) {
            b.read_storage(equirect, ImageRange::mip(0));
            b.read_storage(environment, ImageRange::mip(top));
            out.blocks = b.write(out.blocks);
            flat = b.write_storage(flat);
        }, [p = *split, equirect, environment, blocks = out.blocks, flat, params, top, bx, by](PassContext& pc) {
            p->bind(pc.cmd());
            const DescriptorWrite writes[] = {
                DescriptorWrite::storage_image(pc.view(equirect, ImageRange::mip(0))),
                DescriptorWrite::storage_image(pc.view(environment, ImageRange::mip(top), specular_array_view)),
                DescriptorWrite::storage_buffer(pc.buffer(blocks)),
                DescriptorWrite::storage_image(pc.view(flat, ImageRange::mip(0)))};
            p->push_descriptors(pc.cmd(), writes);
            p->push_constants(pc.cmd(), params);
            const auto local = p->workgroup_size();
            vkCmdDispatch(pc.cmd(), group_count(bx, local[0]), group_count(by, local[1]), 1);
        });
        // The residual is at most T: a 2 x 2 resampling keeps it (the sun's power is in the excess).
        auto cube = add_environment_cube_passes(graph, programs, *equirect_sampler, flat, residual, 2,
                                                "specular residual");
        if (!cube) return cube.error();
        out.residual = *cube;
    } else {
        // No input at hand: split the environment cube's level 0 (its blocks are not merged).
        auto split = programs.compute("ibl/specular_excess.comp");
        if (!split) return split.error();
        out.texel_angle = (pi / 2) / env.width;
        out.block = std::min(excess_block(out.texel_angle, smallest_roughness), env.width);
        const uint32_t per_side = std::max(env.width / out.block, 1u);
        out.blocks = graph.create_buffer("specular excess blocks", {VkDeviceSize(6) * per_side * per_side * 32});
        out.grid_x = 6 * per_side * per_side;
        out.grid_y = 0;
        const Params params{out.block, s.excess_factor};
        graph.add_compute_pass("specular excess", [&](PassBuilder& b) {
            b.read_storage(environment, ImageRange::mip(0));
            b.read_storage(environment, ImageRange::mip(top));
            residual = b.write_storage(residual, ImageRange::mip(0));
            out.blocks = b.write(out.blocks);
        }, [p = *split, environment, residual, blocks = out.blocks, params, top, per_side](PassContext& pc) {
            p->bind(pc.cmd());
            const DescriptorWrite writes[] = {
                DescriptorWrite::storage_image(pc.view(environment, ImageRange::mip(0), specular_array_view)),
                DescriptorWrite::storage_image(pc.view(environment, ImageRange::mip(top), specular_array_view)),
                DescriptorWrite::storage_image(pc.view(residual, ImageRange::mip(0), specular_array_view)),
                DescriptorWrite::storage_buffer(pc.buffer(blocks))};
            p->push_descriptors(pc.cmd(), writes);
            p->push_constants(pc.cmd(), params);
            dispatch_cube(pc, *p, per_side);
        });
        auto mips = add_cube_mip_passes(graph, programs, residual, "specular residual mip ");
        if (!mips) return mips.error();
        out.residual = *mips;
    }
    return out;
}

// The excess list for a level of roughness r: the finest blocks merged to the size the
// lobe allows (input grids only), then packed (shaders/ibl/specular_excess_compact.comp).
// `coarser`: blocks twice as wide as the lobe allows (the fallback of a long list).
Result<BufferHandle> excess_list(RenderGraph& graph, ProgramCache& programs, ExcessSplit& split, float roughness,
                                 bool coarser = false) {
    uint32_t factor = 1;
    if (split.grid_y > 0) {
        while (split.block * factor * 2 <= excess_block(split.texel_angle, roughness)) factor *= 2;
        if (coarser) factor *= 2;
    }
    for (const auto& [f, list] : split.lists)
        if (f == factor) return list;
    BufferHandle blocks = split.blocks;
    uint32_t count = split.grid_y > 0 ? split.grid_x * split.grid_y : split.grid_x;
    const std::string suffix = factor > 1 ? " (" + std::to_string(factor) + "x" + std::to_string(factor) + ")" : "";
    if (factor > 1) {
        auto merge = programs.compute("ibl/specular_excess_merge.comp");
        if (!merge) return merge.error();
        const uint32_t cx = (split.grid_x + factor - 1) / factor, cy = (split.grid_y + factor - 1) / factor;
        count = cx * cy;
        BufferHandle coarse = graph.create_buffer("specular excess blocks" + suffix, {VkDeviceSize(count) * 32});
        struct Params {
            uint32_t fine_x, fine_y, factor;
        };
        const Params params{split.grid_x, split.grid_y, factor};
        graph.add_compute_pass("specular excess blocks" + suffix, [&](PassBuilder& b) {
            b.read(split.blocks);
            coarse = b.write(coarse);
        }, [p = *merge, fine = split.blocks, coarse, params, cx, cy](PassContext& pc) {
            p->bind(pc.cmd());
            const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(fine)),
                                              DescriptorWrite::storage_buffer(pc.buffer(coarse))};
            p->push_descriptors(pc.cmd(), writes);
            p->push_constants(pc.cmd(), params);
            const auto local = p->workgroup_size();
            vkCmdDispatch(pc.cmd(), group_count(cx, local[0]), group_count(cy, local[1]), 1);
        });
        blocks = coarse;
    }
    auto compact = programs.compute("ibl/specular_excess_compact.comp");
    if (!compact) return compact.error();
    BufferHandle list = graph.create_buffer("specular excess list" + suffix, {16 + VkDeviceSize(count) * 32});
    graph.add_compute_pass("specular excess list" + suffix, [&](PassBuilder& b) {
        b.read(blocks);
        list = b.write(list);
    }, [p = *compact, blocks, list, count](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_buffer(pc.buffer(blocks)),
                                          DescriptorWrite::storage_buffer(pc.buffer(list))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), count);
        vkCmdDispatch(pc.cmd(), 1, 1, 1);
    });
    split.lists.push_back({factor, list});
    return list;
}

// The hybrid method's filtered samples for one roughness (what specular_importance.comp
// computes per sample, made once): Hammersley points, h ~ D(h) (n.h), l = reflect(-n, h)
// in the tangent frame of n, and the lod 0.5 log2(Omega_s / Omega_p) (Krivanek and
// Colbert 2008); samples below the horizon are left out. Returns the sum of their n.l.
double hybrid_samples(uint32_t count, float roughness, uint32_t source_size, std::vector<float>& out) {
    const double alpha = std::max(double(roughness) * roughness, 1e-4), a2 = alpha * alpha;
    const double texel_solid_angle = 4.0 * pi / (6.0 * double(source_size) * source_size);
    double weight = 0;
    for (uint32_t i = 0; i < count; ++i) {
        uint32_t bits = i;
        bits = (bits << 16u) | (bits >> 16u);
        bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
        bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
        bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
        bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
        const double u = (i + 0.5) / count, v = bits * 2.3283064365386963e-10;
        const double cos_h = std::sqrt((1 - u) / (1 + (a2 - 1) * u)), sin_h = std::sqrt(std::max(1 - cos_h * cos_h, 0.0));
        const double phi = 2 * pi * v;
        const double h[3] = {std::cos(phi) * sin_h, std::sin(phi) * sin_h, cos_h};
        const double l[3] = {2 * cos_h * h[0], 2 * cos_h * h[1], 2 * cos_h * h[2] - 1};
        if (l[2] <= 0) continue;
        const double d = cos_h * cos_h * (a2 - 1) + 1, D = a2 / (pi * d * d);
        const double sample_solid_angle = 1.0 / (count * D / 4 + 1e-6);
        // No +1 bias (the reference's): at a few samples it blurs the residual too much (on
        // venice_sunset at 64 samples, level 0.2 was 3.0% off with it, 0.9% without).
        const double lod = std::max(0.5 * std::log2(sample_solid_angle / texel_solid_angle), 0.0);
        out.insert(out.end(), {float(l[0]), float(l[1]), float(l[2]), float(lod)});
        weight += l[2];
    }
    if (out.empty()) {  // every sample below the horizon (one or two samples, rough): read along n
        const double lod = std::max(0.5 * std::log2(2 * pi / texel_solid_angle), 0.0);
        out.insert(out.end(), {0.0f, 0.0f, 1.0f, float(lod)});
        weight = 1;
    }
    return weight;
}

// specular_hybrid.comp's bindings: the residual cube, the excess list, `output` (a level, or
// part 1's half-size cube), the samples, the coarser list, and `half` (part 1's cube where
// the level reads it; the residual, unread, elsewhere).
std::array<DescriptorWrite, 6> hybrid_writes(PassContext& pc, ImageHandle residual, BufferHandle list, BufferHandle coarse,
                                             BufferHandle samples, VkImageView output, ImageHandle half, VkSampler sampler) {
    return {DescriptorWrite::sampled_image(pc.view(residual), sampler), DescriptorWrite::storage_buffer(pc.buffer(list)),
            DescriptorWrite::storage_image(output), DescriptorWrite::storage_buffer(pc.buffer(samples)),
            DescriptorWrite::storage_buffer(pc.buffer(coarse)), DescriptorWrite::sampled_image(pc.view(half), sampler)};
}

}  // namespace

double specular_lobe_weight(float roughness) {
    // W = integral over the hemisphere of l of D(h) (n.l), n = v: with x = (n.h)^2, dl = 4 (n.h) dh,
    // W = 4 alpha^2 integral_{1/2}^{1} (2x - 1) / (1 - b x)^2 dx, b = 1 - alpha^2, in closed form.
    const double alpha = std::max(double(roughness) * roughness, 1e-4);
    const double a2 = alpha * alpha, b = 1.0 - a2;
    if (b < 1e-6) return 1.0;  // alpha = 1: D = 1 / pi, W = 4 integral (2x - 1) dx = 1
    const double y0 = 1.0 - b / 2.0;
    return 4.0 * a2 / (b * b) * ((2.0 - b) * (1.0 / a2 - 1.0 / y0) - 2.0 * std::log(y0 / a2));
}

std::vector<float> specular_level_roughness(uint32_t levels) {
    std::vector<float> r(levels, 0.0f);
    for (uint32_t m = 1; m < levels; ++m) r[m] = float(m) / float(levels - 1);
    return r;
}

SpecularMethod specular_level_method(const SpecularSettings& s, float roughness) {
    if (s.method != SpecularMethod::automatic) return s.method;
    return roughness >= s.automatic_convolve_from ? SpecularMethod::convolve : SpecularMethod::hybrid;
}

bool hybrid_residual_at_half_size(const SpecularSettings& s, float roughness, uint32_t face) {
    const double alpha = double(roughness) * roughness;
    return s.hybrid_half_size_residual && face >= 16 && alpha * face >= 3.9;
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
                                        ImageHandle equirect, const Sampler* equirect_sampler,
                                        bool level0_written) {
    const ImageDesc env = graph.resource(environment).image_desc;
    const ImageDesc out = graph.resource(specular).image_desc;
    if (!out.cube || out.width != env.width || out.mip_levels != s.levels)
        return Error{"specular: the output must be a cube of the environment's face size with " +
                     std::to_string(s.levels) + " levels"};
    if (s.levels > env.mip_levels) return Error{"specular: more levels than the environment cube has"};
    if (s.sample_count == 0) return Error{"specular: sample count must be at least 1"};
    // The hybrid table goes in with vkCmdUpdateBuffer (at most 65536 bytes, 16 per sample).
    if (s.hybrid_sample_count == 0 || s.hybrid_sample_count > 4096)
        return Error{"specular: hybrid sample count must be 1 to 4096, not " + std::to_string(s.hybrid_sample_count)};
    if (!(s.excess_factor >= 1.0f) || !std::isfinite(s.excess_factor))
        return Error{"specular: excess factor must be a finite number of at least 1"};

    auto copy = programs.compute("ibl/cube_copy_level.comp");
    if (!copy) return copy.error();

    ImageHandle current = specular;
    const uint32_t first = first_needed_specular_level(s);
    const uint32_t end = s.end_level ? std::min(s.end_level, s.levels) : s.levels;
    if (first == 0 && end > 0 && !level0_written) {
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
    std::optional<ExcessSplit> split;
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
            const uint32_t per_invocation = texels_per_invocation(programs.context());
            const std::vector<ShaderDefine> defines = list_shader_defines(programs.context(), "FACET_CONVOLVE_TEXELS");
            auto conv = programs.compute("ibl/specular_convolve.comp", defines);
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
                }, [p = *conv, texels, specular, m, n, params, f, per_invocation](PassContext& pc) {
                    p->bind(pc.cmd());
                    const DescriptorWrite writes[] = {
                        DescriptorWrite::storage_buffer(pc.buffer(texels)),
                        DescriptorWrite::storage_image(pc.view(specular, ImageRange::mip(m), specular_array_view))};
                    p->push_descriptors(pc.cmd(), writes);
                    p->push_constants(pc.cmd(), params);
                    dispatch_cube_faces(pc, *p, n, f.first, f.count, per_invocation);
                });
            continue;
        }
        if (method == SpecularMethod::hybrid) {
            if (!split) {
                auto made = add_excess_split(graph, programs, environment, equirect, equirect_sampler, s, r);
                if (!made) return made.error();
                split = *made;
            }
            auto list = excess_list(graph, programs, *split, r);
            if (!list) return list.error();
            auto coarse = excess_list(graph, programs, *split, r, true);
            if (!coarse) return coarse.error();
            struct Params {
                uint32_t sample_count;
                float roughness;
                float inverse_sample_weight;
                float inverse_weight;
                uint32_t most_entries;
                uint32_t part;  // 0 whole, 1 the residual's part (half size), 2 the excess's + part 1's
            };
            const uint32_t per_invocation = texels_per_invocation(programs.context());
            const std::vector<ShaderDefine> defines = list_shader_defines(programs.context(), "FACET_HYBRID_TEXELS");
            auto hybrid = programs.compute("ibl/specular_hybrid.comp", defines);
            if (!hybrid) return hybrid.error();
            std::vector<float> table;
            const double sample_weight = hybrid_samples(s.hybrid_sample_count, r, split->residual_size, table);
            const bool half = hybrid_residual_at_half_size(s, r, n);
            const Params params{uint32_t(table.size() / 4), r, float(1.0 / sample_weight),
                                float(1.0 / specular_lobe_weight(r)), kMostExcessEntries, half ? 2u : 0u};
            BufferHandle samples = graph.create_buffer(name + " samples", {VkDeviceSize(table.size() * sizeof(float))});
            graph.add_transfer_pass(name + " samples", [&](PassBuilder& b) { samples = b.write(samples, Access::transfer_dst); },
                                    [samples, table](PassContext& pc) {
                                        vkCmdUpdateBuffer(pc.cmd(), pc.buffer(samples), 0, table.size() * sizeof(float),
                                                          table.data());
                                    });
            // The residual's part at half size first (hybrid_residual_at_half_size), read by
            // the level's passes; without it they read the residual itself in its place
            // (a valid binding, not read).
            ImageHandle half_residual = split->residual;
            if (half) {
                ImageDesc d = graph.resource(specular).image_desc;
                d.width = d.height = n / 2;
                d.mip_levels = 1;
                d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
                half_residual = graph.create_image(name + " residual", d);
                Params part = params;
                part.part = 1;
                graph.add_compute_pass(name + " residual", [&](PassBuilder& b) {
                    b.sample(split->residual);
                    b.read(*list);
                    if (coarse->index != list->index) b.read(*coarse);
                    b.read(samples);
                    half_residual = b.write_storage(half_residual, ImageRange::mip(0));
                }, [p = *hybrid, residual = split->residual, list = *list, coarse = *coarse, samples, half_residual, n,
                    part, per_invocation, sampler = cube_sampler.handle()](PassContext& pc) {
                    p->bind(pc.cmd());
                    p->push_descriptors(pc.cmd(), hybrid_writes(pc, residual, list, coarse, samples,
                                                                pc.view(half_residual, ImageRange::mip(0), specular_array_view),
                                                                residual, sampler));
                    p->push_constants(pc.cmd(), part);
                    dispatch_cube_faces(pc, *p, n / 2, 0, 6, per_invocation);
                });
            }
            for (const FacePass& f : face_passes(name, n))
                graph.add_compute_pass(f.name, [&](PassBuilder& b) {
                    b.sample(split->residual);
                    if (half) b.sample(half_residual);
                    b.read(*list);
                    if (coarse->index != list->index) b.read(*coarse);
                    b.read(samples);
                    current = b.write_storage(current, ImageRange::mip(m));
                }, [p = *hybrid, residual = split->residual, half_residual, list = *list, coarse = *coarse, samples, specular,
                    m, n, params, f, per_invocation, sampler = cube_sampler.handle()](PassContext& pc) {
                    p->bind(pc.cmd());
                    p->push_descriptors(pc.cmd(), hybrid_writes(pc, residual, list, coarse, samples,
                                                                pc.view(specular, ImageRange::mip(m), specular_array_view),
                                                                half_residual, sampler));
                    p->push_constants(pc.cmd(), params);
                    dispatch_cube_faces(pc, *p, n, f.first, f.count, per_invocation);
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
