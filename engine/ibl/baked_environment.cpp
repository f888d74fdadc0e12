// bake_environment: the whole bake in one graph, then only its outputs kept (read back,
// checked, stored in the format that holds them, uploaded into images of their own)
// while the graph's run and every intermediate are freed.
#include <facet/ibl/baked_environment.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <new>

#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/ibl/bake_rules.h>
#include <facet/render/tonemap_preview.h>
#include <facet/shader/program_cache.h>
#include "ibl/bake_cancel.h"
#include "ibl/baked_outputs.h"
#include "core/guarded.h"

namespace facet {

BakedEnvironment::BakedEnvironment(BakedEnvironment&&) noexcept = default;
BakedEnvironment& BakedEnvironment::operator=(BakedEnvironment&&) noexcept = default;
BakedEnvironment::~BakedEnvironment() = default;

namespace {

using A = BakedEnvironmentAccess;

const ResourceState kReadable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                              VK_ACCESS_2_TRANSFER_READ_BIT};

// The graph's RGBA32F results, read back before the run is freed.
struct ReadBack {
    Levels environment, cube, specular, irradiance, lut;
    ImageDesc environment_desc, cube_desc, specular_desc, irradiance_desc, lut_desc;
    std::vector<uint8_t> preview;
    std::vector<float> sh9;
    std::vector<PassTiming> timings;
};

ReadBack run_bake_graph(Context& context, ProgramCache& programs, const EnvironmentSource& source,
                        const BakeSettings& settings, const SpecularSplit& split, const BakeCallbacks& cb,
                        BakeMetadata& meta) {
    auto check = [](auto result) {
        if (!result) throw result.error();
        return *result;
    };
    IblBake ibl(context, programs);
    RenderGraph graph;
    const IblImages images = check(ibl.add_passes(graph, source, settings.ibl, split));
    ImageDesc preview_desc;
    preview_desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    preview_desc.width = source.width;
    preview_desc.height = source.height;
    const ImageHandle preview = check(add_tonemap_preview_pass(
        graph, programs, images.equirect, graph.create_image("preview", preview_desc), settings.preview_exposure));
    for (ImageHandle h : {images.equirect, images.cube, images.irradiance, images.specular, images.lut, preview})
        if (h.valid()) graph.export_image(h, kReadable);
    if (images.sh9.valid())
        graph.export_buffer(images.sh9, {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                         VK_ACCESS_2_TRANSFER_READ_BIT});
    CompiledGraph compiled = graph.compile();
    if (cb.graph_dot) cb.graph_dot(compiled.to_dot());
    bake_safe_point(cb.stop, "graph");
    meta.passes = uint32_t(compiled.passes.size());
    if (cb.progress) cb.progress("running " + std::to_string(compiled.passes.size()) + " passes");
    GraphRun run(context, compiled);
    or_throw(run.submit_and_wait([&](uint32_t done, uint32_t total, const std::string& pass) {
        if (cb.pass_done) cb.pass_done(done, total, pass);
        bake_safe_point(cb.stop, "pass");
    }));
    ReadBack r;
    r.timings = run.timings();
    auto read = [&](ImageHandle h, Levels& levels, ImageDesc& desc) {
        if (!h.valid()) return;
        const Image& image = *run.transient_image(h);
        levels = read_levels(context, image, kReadable.layout);
        desc = image.desc();
    };
    read(images.equirect, r.environment, r.environment_desc);
    read(images.cube, r.cube, r.cube_desc);
    read(images.specular, r.specular, r.specular_desc);
    read(images.irradiance, r.irradiance, r.irradiance_desc);
    read(images.lut, r.lut, r.lut_desc);
    auto preview_bytes =
        or_throw(read_image(context, *run.transient_image(preview), 0, 0, kReadable.layout));
    r.preview.resize(preview_bytes.size());
    std::memcpy(r.preview.data(), preview_bytes.data(), preview_bytes.size());
    if (images.sh9.valid()) {
        auto bytes = or_throw(read_buffer(context, *run.transient_buffer(images.sh9)));
        r.sh9.resize(bytes.size() / sizeof(float));
        std::memcpy(r.sh9.data(), bytes.data(), r.sh9.size() * sizeof(float));
    }
    return r;  // the run, the graph's images and the upload go here
}

Result<BakedEnvironment> bake(Context& context, ProgramCache& programs, const EnvironmentSource& input,
                              const BakeSettings& requested, const BakeCallbacks& cb) {
    const auto start = std::chrono::steady_clock::now();
    auto say = [&](const std::string& line) {
        if (cb.progress) cb.progress(line);
    };
    if (requested.format != VK_FORMAT_R16G16B16A16_SFLOAT && requested.format != VK_FORMAT_R32G32B32A32_SFLOAT)
        return Error{"bake: the output format must be R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT"};
    BakeSettings settings = requested;
    settings.ibl = resolved_ibl_settings(requested.ibl, input);
    if (Status fits = check_ibl_fits(context, input, settings.ibl, settings.extract_lights); !fits) return fits.error();

    BakedEnvironment out = A::make(context);
    BakeMetadata& meta = A::metadata(out);
    meta.input = input.name;
    meta.content_hash = input.content_hash;
    meta.bake_key = bake_key(input, settings);
    meta.device = context.device_name();
    meta.version = FACET_VERSION;
    meta.sanitized_texels = input.image.sanitized_texels;
    meta.width = input.width;
    meta.height = input.height;
    meta.source_width = input.source_width;
    meta.source_height = input.source_height;
    meta.max_env_width = input.max_width;
    meta.preview_exposure = settings.preview_exposure;

    // A procedural sky is rendered into texels for the analyses (warnings, budget, lights);
    // the bake itself still renders it in its own graph.
    std::optional<EnvironmentSource> materialized;
    if (input.sky) {
        materialized = input;
        if (Status st = materialize_environment(context, programs, *materialized); !st) return st.error();
    }
    const EnvironmentSource& analysed = materialized ? *materialized : input;
    bake_safe_point(cb.stop, "shaders");

    // Light extraction: the bake sees the map without its lights, the smooth specular
    // levels the whole environment.
    std::optional<EnvironmentSource> residual;
    SpecularSplit split;
    if (settings.extract_lights) {
        LightExtraction extraction =
            extract_lights(analysed.image.rgba, analysed.width, analysed.height, settings.extraction);
        A::lights(out) = extraction.lights;
        meta.extracted_power_fraction = extraction.extracted_power_fraction;
        meta.extraction_notes = extraction.notes;
        say("extracted " + std::to_string(extraction.lights.size()) + " light(s) from " + input.name + ", " +
            std::to_string(int(std::lround(100 * extraction.extracted_power_fraction))) + "% of its power");
        if (!extraction.lights.empty()) {
            residual = analysed;
            residual->image.rgba = std::move(extraction.residual);
            meta.light_split_level = light_split_level(A::lights(out), settings.ibl.specular.levels);
            split = {&analysed, meta.light_split_level};
        }
    }
    const EnvironmentSource& baked_source = residual ? *residual : input;

    if (settings.target_error > 0) {
        auto budget = choose_within_budget(context, programs, residual ? *residual : analysed, settings.ibl,
                                           settings.target_error, settings.roughness_min, settings.roughness_max,
                                           cb.progress, cb.stop);
        if (!budget) return budget.error();
        settings.ibl = budget->settings;
        meta.budget = *budget;
    }
    meta.settings = settings.ibl;
    meta.roughness = specular_level_roughness(settings.ibl.specular.levels);
    meta.first_specular_level = first_needed_specular_level(settings.ibl.specular);
    meta.warnings = bake_warnings(analysed, settings.ibl);

    ReadBack r = run_bake_graph(context, programs, baked_source, settings, split, cb, meta);
    materialized.reset();
    residual.reset();
    meta.timings = std::move(r.timings);

    const size_t bad = count_bad_values(r.environment) + count_bad_values(r.cube) +
                       count_bad_values(r.specular, meta.first_specular_level) + count_bad_values(r.irradiance) +
                       count_bad_values(r.lut);
    if (bad) return Error{std::to_string(bad) + " baked values are NaN, Inf or negative"};

    A::environment(out) = make_baked_image(context, r.environment_desc, r.environment, "baked environment");
    auto keep = [&](const Levels& levels, ImageDesc desc, uint32_t first_level, const char* what, VkFormat& format) {
        Stored stored = store_levels(levels, settings.format, first_level, what);
        desc.format = format = stored.format;
        if (!stored.note.empty()) meta.format_notes.push_back(stored.note);
        return make_baked_image(context, desc, stored.levels, std::string("baked ") + what);
    };
    A::cube(out) = keep(r.cube, r.cube_desc, 0, "environment cube", meta.cube_format);
    if (!r.specular.empty())
        A::specular(out) = keep(r.specular, r.specular_desc, meta.first_specular_level, "specular", meta.specular_format);
    if (!r.irradiance.empty())
        A::irradiance(out) = keep(r.irradiance, r.irradiance_desc, 0, "irradiance", meta.irradiance_format);
    if (!r.lut.empty()) A::lut(out) = keep(r.lut, r.lut_desc, 0, "brdf lut", meta.lut_format);
    A::sh9(out) = std::move(r.sh9);
    A::preview(out) = std::move(r.preview);
    A::cube_sampler(out) = or_throw(Sampler::create(context, VK_FILTER_LINEAR, true, false, "baked cube sampler"));
    meta.wall_time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace

Result<BakedEnvironment> bake_environment(Context& context, ProgramCache& programs, const EnvironmentSource& source,
                                          const BakeSettings& settings, const BakeCallbacks& callbacks) {
    try {
        return bake(context, programs, source, settings, callbacks);
    } catch (const BakeCancelled&) {
        return Error{kBakeCancelled};
    } catch (const Error& error) {
        return error;
    } catch (const VulkanError& error) {
        return Error{error.what(), error.result()};
    } catch (const std::bad_alloc&) {
        return Error{"bake: out of host memory"};
    }
}

IblInputs import_baked_environment(RenderGraph& graph, const BakedEnvironment& baked, float intensity) {
    const ResourceState sampled{kBakedLayout, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    auto import = [&](const Image* image, const char* name) -> ImageHandle {
        if (!image || !*image) return {};
        return graph.import_image(name, {image->handle(), image->desc(), sampled, sampled});
    };
    IblInputs in;
    in.cube = import(&baked.cube(), "environment cube");
    in.irradiance = import(baked.irradiance(), "irradiance");
    in.specular = import(baked.specular(), "specular");
    in.lut = import(baked.lut(), "brdf lut");
    in.specular_levels = baked.metadata().settings.specular.levels;
    in.cube_sampler = baked.cube_sampler().handle();
    in.intensity = intensity;
    return in;
}

}  // namespace facet
