// bake_environment: the whole bake in one graph, whose outputs are checked and measured
// by passes of the same graph (ibl/baked_environment_finish.h) and then taken out of the
// run (GraphRun::detach_image): the run, its intermediates and the upload are freed, and
// no output passes through the host. Outputs that fit RGBA16F are converted on the GPU.
#include <facet/ibl/baked_environment.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <future>
#include <memory>
#include <new>

#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/ibl/bake_rules.h>
#include <facet/ibl/method_domain.h>
#include <facet/render/tonemap_preview.h>
#include <facet/shader/program_cache.h>
#include "ibl/bake_cancel.h"
#include "ibl/baked_environment_finish.h"
#include "ibl/baked_outputs.h"
#include "ibl/lut_cache.h"
#include "core/guarded.h"

namespace facet {

BakedEnvironment::BakedEnvironment(BakedEnvironment&&) noexcept = default;
BakedEnvironment& BakedEnvironment::operator=(BakedEnvironment&&) noexcept = default;
BakedEnvironment::~BakedEnvironment() = default;

namespace {

using A = BakedEnvironmentAccess;

// Where the outputs are left: readable by any shader (the frame's passes) and by copies.
const ResourceState kKept{kBakedLayout, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT};

// The largest finite RGBA16F value; larger ones round to infinity (from 65520 on) or
// down to it, either way not the value baked.
constexpr float kHalfMax = 65504.0f;

// The graph's results, owned (RGBA32F) after the run, with what their check found.
struct Outputs {
    Image environment, cube, specular, irradiance, lut, preview;
    std::vector<OutputRange> ranges;  // environment, cube, specular, irradiance, lut (those present)
    std::vector<float> sh9;
    std::vector<PassTiming> timings;
};

// The largest sound value and the count of NaN, Inf and negative values, as
// shaders/ibl/output_range.comp finds them on the GPU.
OutputRange host_range(const std::vector<float>& texels) {
    // Branch-free, so that it vectorises: NaN fails v >= 0, +Inf fails v <= FLT_MAX.
    OutputRange r;
    for (size_t at = 0; at < texels.size();) {
        const size_t end = std::min(texels.size(), at + (size_t(1) << 24));
        uint32_t bad = 0;
        float peak = r.peak;
        for (; at < end; ++at) {
            const float v = texels[at];
            const bool sound = v >= 0.0f && v <= FLT_MAX;
            bad += sound ? 0u : 1u;
            peak = std::max(peak, sound ? v : 0.0f);
        }
        r.bad += bad;
        r.peak = peak;
    }
    return r;
}

Outputs run_bake_graph(Context& context, ProgramCache& programs, const EnvironmentSource& source,
                       const BakeSettings& settings, const SpecularSplit& split, const BakeCallbacks& cb,
                       BakeMetadata& meta) {
    auto check = [](auto result) {
        if (!result) throw result.error();
        return *result;
    };
    IblBake ibl(context, programs);
    // The BRDF LUT from the cache when it holds one made with the same model, size, samples
    // and shaders; otherwise computed here and kept there after the run.
    std::string lut_key;
    bool lut_cached = false;
    if (settings.ibl.want_lut && !settings.lut_cache.directory.empty()) {
        lut_key = check(brdf_lut_cache_key(programs, settings.ibl.lut));
        std::string note;
        std::vector<float> texels = find_cached_lut(settings.lut_cache, lut_key, settings.ibl.lut.size, note);
        if (!note.empty() && cb.progress) cb.progress("BRDF LUT cache: " + note);
        if (!texels.empty()) {
            ibl.use_lut(std::move(texels));
            lut_cached = true;
            if (cb.progress) cb.progress("BRDF LUT from the cache in " + settings.lut_cache.directory);
        }
    }
    RenderGraph graph;
    // The driver compiles the passes' pipelines on every core while the graph is built.
    ProgramCache::Batch pipelines(programs);
    IblImages images = check(ibl.add_passes(graph, source, settings.ibl, split));
    ImageHandle preview;
    if (settings.preview) {
        ImageDesc preview_desc;
        preview_desc.format = VK_FORMAT_R8G8B8A8_UNORM;
        preview_desc.width = source.width;
        preview_desc.height = source.height;
        preview = check(add_tonemap_preview_pass(graph, programs, images.equirect,
                                                 graph.create_image("preview", preview_desc), settings.preview_exposure));
    }
    // Specular levels below the first needed one are computed by nothing: zeros, so that
    // the files are the same from run to run.
    if (images.specular.valid() && meta.first_specular_level > 0)
        images.specular = add_clear_levels_pass(graph, images.specular, meta.first_specular_level);
    // The outputs' ranges are checked on the GPU; an uploaded environment's texels on the
    // host instead, where they are (one pass over memory against a pass of ~5 ms on lavapipe).
    const bool uploaded = !source.sky;
    ImageHandle* const outputs[] = {uploaded ? nullptr : &images.equirect, &images.cube, &images.specular,
                                    &images.irradiance, &images.lut};
    std::vector<CheckedOutput> checked;
    for (ImageHandle* h : outputs)
        if (h && h->valid()) checked.push_back({*h, h == &images.specular ? meta.first_specular_level : 0});
    const BufferHandle ranges = check(add_output_range_passes(graph, programs, checked));
    {
        size_t i = 0;
        for (ImageHandle* h : outputs)
            if (h && h->valid()) *h = checked[i++].image;
    }
    for (ImageHandle h : {images.equirect, images.cube, images.irradiance, images.specular, images.lut, preview})
        if (h.valid()) graph.export_image(h, kKept);
    const ResourceState read_back{VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                  VK_ACCESS_2_TRANSFER_READ_BIT};
    graph.export_buffer(ranges, read_back);
    if (images.sh9.valid()) graph.export_buffer(images.sh9, read_back);
    // The conversion of the outputs to RGBA16F after the run, compiled with the others.
    if (settings.format == VK_FORMAT_R16G16B16A16_SFLOAT) check(half_conversion_program(programs));
    if (Status made = pipelines.finish(); !made) throw made.error();
    CompiledGraph compiled = graph.compile();
    if (cb.graph_dot) cb.graph_dot(compiled.to_dot());
    bake_safe_point(cb.stop, "graph");
    meta.passes = uint32_t(compiled.passes.size());
    if (cb.progress) cb.progress("running " + std::to_string(compiled.passes.size()) + " passes");
    GraphRun run(context, compiled);
    // An uploaded environment's range, checked on the host while the passes run.
    std::future<OutputRange> host_checked;
    if (uploaded) host_checked = std::async(std::launch::async, [&] { return host_range(source.image.rgba); });
    or_throw(run.submit_and_wait([&](uint32_t done, uint32_t total, const std::string& pass) {
        if (cb.pass_done) cb.pass_done(done, total, pass);
        bake_safe_point(cb.stop, "pass");
    }));
    Outputs r;
    r.timings = run.timings();
    r.ranges = read_output_ranges(context, *run.transient_buffer(ranges), checked.size());
    if (uploaded) r.ranges.insert(r.ranges.begin(), host_checked.get());
    auto take = [&](ImageHandle h) { return h.valid() ? run.detach_image(h) : Image{}; };
    r.environment = take(images.equirect);
    r.cube = take(images.cube);
    r.specular = take(images.specular);
    r.irradiance = take(images.irradiance);
    r.lut = take(images.lut);
    if (!lut_key.empty() && !lut_cached && r.lut) {
        const Levels levels = read_levels(context, r.lut, kBakedLayout);
        Status kept = store_cached_lut(settings.lut_cache, lut_key, levels.front());
        if (!kept && cb.progress) cb.progress("BRDF LUT cache: " + kept.error().message + " (the LUT is not kept)");
    }
    r.preview = take(preview);
    if (images.sh9.valid()) {
        auto bytes = or_throw(read_buffer(context, *run.transient_buffer(images.sh9)));
        r.sh9.resize(bytes.size() / sizeof(float));
        std::memcpy(r.sh9.data(), bytes.data(), r.sh9.size() * sizeof(float));
    }
    return r;  // the run, the graph's other images and the upload go here
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

    // A procedural sky is rendered into texels for the analyses that read them (light
    // extraction, the budget, the warnings of methods whose domain depends on the content);
    // the bake itself still renders it in its own graph.
    std::optional<EnvironmentSource> materialized;
    if (input.sky && (settings.extract_lights || settings.target_error > 0 || method_warnings_read_content(settings.ibl))) {
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
            residual->sky_model.reset();  // the sky without its sun: its own texels
            meta.light_split_level = light_split_level(A::lights(out), settings.ibl.specular.levels);
            split = {&analysed, meta.light_split_level};
        }
    }
    const EnvironmentSource& baked_source = residual ? *residual : input;
    // The caller's encoded environment files, kept when the environment baked is the
    // input's texels (save() checks their content hash and size against it).
    if (!residual && !input.sky) A::encoded(out) = settings.encoded_environment;

    if (settings.target_error > 0) {
        auto budget = choose_within_budget(context, programs, residual ? *residual : analysed, settings.ibl,
                                           settings.target_error, settings.roughness_min, settings.roughness_max,
                                           cb.progress, cb.stop, residual ? &analysed : nullptr);
        if (!budget) return budget.error();
        settings.ibl = budget->settings;
        meta.budget = *budget;
    }
    meta.settings = settings.ibl;
    meta.roughness = specular_level_roughness(settings.ibl.specular.levels);
    meta.first_specular_level = first_needed_specular_level(settings.ibl.specular);
    meta.warnings = bake_warnings(analysed, settings.ibl);

    Outputs r = run_bake_graph(context, programs, baked_source, settings, split, cb, meta);
    materialized.reset();
    residual.reset();
    meta.timings = std::move(r.timings);

    uint64_t bad = 0;
    for (const OutputRange& range : r.ranges) bad += range.bad;
    if (bad) return Error{std::to_string(bad) + " baked values are NaN, Inf or negative"};

    // Each output in the format asked for when its values fit it, else in RGBA32F, said;
    // the conversions to RGBA16F in one submission.
    struct Kept {
        Image* image;
        const char* what;
    };
    std::vector<Kept> kept;
    size_t next_range = 1;  // ranges[0] is the environment's, which stays RGBA32F
    auto keep = [&](Image& image, const char* what, VkFormat& format) {
        const float peak = r.ranges[next_range++].peak;
        format = VK_FORMAT_R32G32B32A32_SFLOAT;
        if (settings.format != VK_FORMAT_R16G16B16A16_SFLOAT) return;
        if (peak > kHalfMax) {
            char text[200];
            std::snprintf(text, sizeof text,
                          "%s kept in R32G32B32A32_SFLOAT: its largest value, %.4g, exceeds R16G16B16A16_SFLOAT's "
                          "65504",
                          what, double(peak));
            meta.format_notes.push_back(text);
            return;
        }
        format = VK_FORMAT_R16G16B16A16_SFLOAT;
        kept.push_back({&image, what});
    };
    keep(r.cube, "environment cube", meta.cube_format);
    if (r.specular) keep(r.specular, "specular", meta.specular_format);
    if (r.irradiance) keep(r.irradiance, "irradiance", meta.irradiance_format);
    if (r.lut) keep(r.lut, "brdf lut", meta.lut_format);
    if (!kept.empty()) {
        std::vector<Image*> images;
        std::vector<std::string> names;
        for (const Kept& k : kept) {
            images.push_back(k.image);
            names.push_back(std::string("baked ") + k.what);
        }
        std::vector<Image> halves = convert_to_half(programs, images, kBakedLayout, names);
        for (size_t i = 0; i < kept.size(); ++i) *kept[i].image = std::move(halves[i]);
    }
    A::environment(out) = std::move(r.environment);
    A::cube(out) = std::move(r.cube);
    if (r.specular) A::specular(out) = std::move(r.specular);
    if (r.irradiance) A::irradiance(out) = std::move(r.irradiance);
    if (r.lut) A::lut(out) = std::move(r.lut);
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
