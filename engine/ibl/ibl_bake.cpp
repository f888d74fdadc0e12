#include <facet/ibl/ibl_bake.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <span>

#include <facet/gpu/context.h>
#include <facet/gpu/device_limits.h>
#include <facet/gpu/resources.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/graph/transfer_passes.h>
#include <facet/gpu/transfer.h>
#include "ibl/environment_cube.h"
#include <facet/shader/program_cache.h>

namespace facet {

Result<EnvironmentSource> resolve_environment(const std::string& name, uint32_t builtin_width,
                                              const EnvironmentLoadOptions& file_options) {
    EnvironmentSource source;
    source.name = name;
    source.max_width = file_options.max_width;
    if (name == "builtin:sky") source.sky = ProceduralSky{};
    else if (name == "builtin:white") source.sky = ProceduralSky::white();
    else if (name.rfind("builtin:", 0) == 0)
        return Error{name + ": unknown built-in environment (" + builtin_environment_names() + ")"};
    if (source.sky) {
        if (builtin_width < 2 || builtin_width % 2)
            return Error{name + ": the width of a built-in environment must be even and at least 2"};
        if (builtin_width > file_options.max_width)
            return Error{name + ": a width of " + std::to_string(builtin_width) +
                         " is above the largest environment width allowed, " + std::to_string(file_options.max_width)};
        source.content_hash = source.sky->content_hash();
        source.width = builtin_width;
        source.height = builtin_width / 2;
        source.source_width = source.width;
        source.source_height = source.height;
        return source;
    }
    auto image = load_environment(name, file_options);
    if (!image) return image.error();
    source.image = std::move(image).value();
    source.content_hash = source.image.content_hash;
    source.width = source.image.width;
    source.height = source.image.height;
    source.source_width = source.image.source_width;
    source.source_height = source.image.source_height;
    return source;
}

Status materialize_environment(Context& context, ProgramCache& programs, EnvironmentSource& source) {
    if (!source.sky) return Ok{};
    RenderGraph graph;
    ImageDesc desc;
    desc.width = source.width;
    desc.height = source.height;
    auto sky = add_procedural_sky_pass(graph, programs, *source.sky, graph.create_image("environment", desc));
    if (!sky) return sky.error();
    graph.export_image(*sky, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                              VK_ACCESS_2_TRANSFER_READ_BIT});
    CompiledGraph compiled = graph.compile();
    GraphRun run(context, compiled);
    if (Status done = run.submit_and_wait(); !done) return done;
    auto bytes = read_image(context, *run.transient_image(*sky), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    if (!bytes) return bytes.error();
    source.image.width = source.width;
    source.image.height = source.height;
    source.image.rgba.resize(bytes->size() / sizeof(float));
    std::memcpy(source.image.rgba.data(), bytes->data(), source.image.rgba.size() * sizeof(float));
    source.image.content_hash = source.content_hash;
    source.sky_model = source.sky;
    source.sky.reset();
    return Ok{};
}

IblSettings resolved_ibl_settings(const IblSettings& settings, const EnvironmentSource& source) {
    IblSettings s = settings;
    if (!s.cube_size) s.cube_size = cube_size_for(source.height);
    s.specular.levels = std::min(s.specular.levels, full_mip_count(s.cube_size));
    return s;
}

Status check_ibl_fits(const Context& context, const EnvironmentSource& source, const IblSettings& s, bool whole_copy) {
    ImageDesc equirect;
    equirect.width = source.width;
    equirect.height = source.height;
    ImageDesc lut;
    lut.width = lut.height = s.lut.size;
    const std::string face = std::to_string(s.cube_size);
    std::vector<NamedImage> images = {
        {"the environment (" + std::to_string(source.width) + " wide)", equirect},
        {"the environment cube (faces of " + face + ")", environment_cube_desc(s.cube_size, full_mip_count(s.cube_size))}};
    if (whole_copy) {
        const std::vector<NamedImage> whole = images;
        images.insert(images.end(), whole.begin(), whole.end());
    }
    if (s.want_irradiance)
        images.push_back({"the irradiance cube (faces of " + std::to_string(s.irradiance.size) + ")",
                          environment_cube_desc(s.irradiance.size, 1)});
    if (s.want_specular)
        images.push_back({"the specular cube (faces of " + face + ")", environment_cube_desc(s.cube_size, s.specular.levels)});
    if (s.want_lut) images.push_back({"the BRDF LUT (" + std::to_string(s.lut.size) + " square)", lut});
    Status fits = check_images_fit(device_limits(context), images);
    if (!fits) return Error{"image-based lighting: " + fits.error().message};
    return Ok{};
}

// The samplers are made by the first add_passes, which can return their failure.
IblBake::IblBake(Context& context, ProgramCache& programs) : context_(context), programs_(programs) {}

IblBake::~IblBake() = default;

namespace {

// The environment's texels (or its procedural sky) as an image of the graph, and its cube.
struct Uploaded {
    ImageHandle equirect, cube;
};

// `texels` (RGBA32F, tightly packed) into `image` by the pass "upload NAME", through a new
// host-visible buffer left in `staging` (which must outlive the graph's run).
Result<ImageHandle> add_texel_upload(RenderGraph& graph, Context& context, std::span<const float> texels,
                                     std::unique_ptr<Buffer>& staging, const std::string& name, ImageHandle image) {
    auto made = Buffer::create(context, texels.size() * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               MemoryUsage::upload, name + " upload");
    if (!made) return made.error();
    staging = std::make_unique<Buffer>(std::move(*made));
    std::memcpy(staging->mapped(), texels.data(), texels.size() * sizeof(float));
    if (Status flushed = staging->flush(); !flushed) return flushed.error();
    auto staged = graph.import_buffer(
        name + " texels",
        {staging->handle(), staging->size(), {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_WRITE_BIT}, {}});
    return add_upload_pass(graph, "upload " + name, staged, image);
}

Result<Uploaded> add_environment(RenderGraph& graph, Context& context, ProgramCache& programs,
                                 const Sampler& equirect_sampler, const EnvironmentSource& source, uint32_t cube_size,
                                 std::unique_ptr<Buffer>& staging, const std::string& prefix,
                                 ImageHandle cube_target = {}, ImageHandle* mirror = nullptr) {
    Uploaded out;
    ImageDesc equirect_desc;
    equirect_desc.width = source.width;
    equirect_desc.height = source.height;
    out.equirect = graph.create_image(prefix + "environment", equirect_desc);
    if (source.sky) {
        auto sky = add_procedural_sky_pass(graph, programs, *source.sky, out.equirect);
        if (!sky) return sky.error();
        out.equirect = *sky;
    } else {
        auto uploaded = add_texel_upload(graph, context, source.image.rgba, staging, prefix + "environment", out.equirect);
        if (!uploaded) return uploaded.error();
        out.equirect = *uploaded;
    }
    const ImageHandle cube_image =
        cube_target.valid() ? cube_target
                            : graph.create_image(prefix + "environment cube",
                                                 environment_cube_desc(cube_size, full_mip_count(cube_size)));
    // The sky's cube from the sky itself (16 evaluations a texel, not 16 lookups of its
    // equirect, which the lists and the files still use); a file's from its equirect.
    const std::optional<ProceduralSky>& sky = source.sky ? source.sky : source.sky_model;
    auto cube = [&]() -> Result<ImageHandle> {
        if (!sky) return add_environment_cube_passes(graph, programs, equirect_sampler, out.equirect, cube_image, 4, "", mirror);
        auto level0 = add_procedural_sky_cube_pass(graph, programs, *sky, cube_image, mirror);
        if (!level0) return level0.error();
        return add_cube_mip_passes(graph, programs, *level0, "cube mip ");
    }();
    if (!cube) return cube.error();
    out.cube = *cube;
    return out;
}

// The caller's image `target` (if valid) instead of a new one of `desc`, when it has that description.
Result<ImageHandle> target_or_new(RenderGraph& graph, ImageHandle target, const std::string& name,
                                  const ImageDesc& desc) {
    if (!target.valid()) return graph.create_image(name, desc);
    const ImageDesc& have = graph.resource(target).image_desc;
    if (!(have == desc))
        return Error{"image-based lighting: the caller's " + name + " image is " + std::to_string(have.width) + "x" +
                     std::to_string(have.height) + ", " + std::to_string(have.mip_levels) + " level(s), " +
                     std::to_string(have.array_layers) + " layer(s), format " + std::to_string(int(have.format)) +
                     "; the bake writes " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + ", " +
                     std::to_string(desc.mip_levels) + " level(s), " + std::to_string(desc.array_layers) +
                     " layer(s), format " + std::to_string(int(desc.format)) + " (R32G32B32A32_SFLOAT)"};
    return target;
}

}  // namespace

Result<IblImages> IblBake::add_passes(RenderGraph& graph, const EnvironmentSource& source, const IblSettings& s,
                                      const SpecularSplit& split, const IblTargets& targets) {
    if (Status fits = check_ibl_fits(context_, source, s, split.whole != nullptr); !fits) return fits.error();
    if (!cube_sampler_) {
        auto equirect = Sampler::create(context_, VK_FILTER_LINEAR, false, true, "equirect sampler");
        if (!equirect) return equirect.error();
        auto cube = Sampler::create(context_, VK_FILTER_LINEAR, true, false, "cube sampler");
        if (!cube) return cube.error();
        equirect_sampler_ = std::make_unique<Sampler>(std::move(*equirect));
        cube_sampler_ = std::make_unique<Sampler>(std::move(*cube));
    }
    IblImages out;
    auto cube_target = target_or_new(graph, targets.cube, "environment cube",
                                     environment_cube_desc(s.cube_size, full_mip_count(s.cube_size)));
    if (!cube_target) return cube_target.error();
    // Specular level 0 (a mirror) is the environment's level 0: the pass that makes the
    // latter writes it too, for whichever environment the smooth levels come from.
    const bool extracted = split.whole && split.level > 0;
    ImageHandle specular;
    bool level0_written = false;
    if (s.want_specular) {
        auto target = target_or_new(graph, targets.specular, "specular", environment_cube_desc(s.cube_size, s.specular.levels));
        if (!target) return target.error();
        specular = *target;
        level0_written = s.specular.levels > 0 && first_needed_specular_level(s.specular) == 0;
    }
    auto main = add_environment(graph, context_, programs_, *equirect_sampler_, source, s.cube_size, staging_, "",
                                *cube_target, level0_written && !extracted ? &specular : nullptr);
    if (!main) return main.error();
    out.equirect = main->equirect;
    out.cube = main->cube;
    // The whole environment, where lights were taken out: the irradiance and the smooth
    // specular levels come from it (the diffuse lobe integrates the lights exactly; the
    // renderers shade the disks' specular alone).
    std::optional<Uploaded> whole;
    if (split.whole) {
        if (split.whole->width != source.width || split.whole->height != source.height)
            return Error{"light extraction: the whole environment and the map without lights differ in size"};
        auto added = add_environment(graph, context_, programs_, *equirect_sampler_, *split.whole, s.cube_size,
                                     whole_staging_, "whole ", {}, level0_written && extracted ? &specular : nullptr);
        if (!added) return added.error();
        whole = *added;
    }
    if (s.want_irradiance) {
        auto target = target_or_new(graph, targets.irradiance, "irradiance", environment_cube_desc(s.irradiance.size, 1));
        if (!target) return target.error();
        auto irradiance = add_irradiance_passes(graph, programs_, *cube_sampler_, whole ? whole->cube : out.cube,
                                                *target, s.irradiance, &out.sh9,
                                                whole ? whole->equirect : out.equirect);
        if (!irradiance) return irradiance.error();
        out.irradiance = *irradiance;
    }
    if (s.want_specular) {
        SpecularSettings rough = s.specular;
        if (extracted) {
            SpecularSettings smooth = s.specular;
            smooth.end_level = split.level;
            auto written = add_specular_passes(graph, programs_, *cube_sampler_, whole->cube, specular, smooth,
                                               whole->equirect, equirect_sampler_.get(), level0_written);
            if (!written) return written.error();
            specular = *written;
            rough.first_level = std::max(rough.first_level, split.level);
        }
        auto written = add_specular_passes(graph, programs_, *cube_sampler_, out.cube, specular, rough, out.equirect,
                                           equirect_sampler_.get(), level0_written && !extracted);
        if (!written) return written.error();
        out.specular = *written;
    }
    if (s.want_lut) {
        ImageDesc lut_desc;
        lut_desc.width = lut_desc.height = s.lut.size;
        auto target = target_or_new(graph, targets.lut, "brdf lut", lut_desc);
        if (!target) return target.error();
        if (cached_lut_.size() == size_t(s.lut.size) * s.lut.size * 4) {
            auto uploaded = add_texel_upload(graph, context_, cached_lut_, lut_staging_, "brdf lut (cached)", *target);
            if (!uploaded) return uploaded.error();
            out.lut = *uploaded;
        } else {
            auto lut = add_brdf_lut_passes(graph, programs_, s.lut, *target);
            if (!lut) return lut.error();
            out.lut = *lut;
        }
    }
    return out;
}

}  // namespace facet
