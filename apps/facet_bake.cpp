// facet-bake: an environment -> the image-based-lighting data of design.md: the
// prefiltered specular cube, the diffuse irradiance cube and the split-sum BRDF LUT
// (KTX2), previews, and bake.json. All work is compute passes of one render graph.
// The files appear together or not at all; SIGINT and SIGTERM stop it at the next safe
// point with nothing written (apps/interrupt.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <vector>

#include "bake_budget.h"
#include "bake_files.h"
#include "cli.h"
#include "interrupt.h"
#include "facet_bake_options.h"
#include "render_options.h"
#include "shader_cache.h"
#include <facet/core/hash.h>
#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/ibl/method_domain.h>
#include <facet/io/atomic_file.h>
#include <facet/io/environment_image.h>
#include <facet/io/output_set.h>
#include <facet/render/tonemap_preview.h>
#include <facet/shader/program_cache.h>

namespace {

using namespace facet;
namespace fs = std::filesystem;

constexpr const char* program = "facet-bake";

using Options = BakeOptions;

// Everything that decides the outputs, hashed: equal keys mean equal bakes.
std::string bake_key(const Options& o, const EnvironmentSource& s, uint32_t cube_size, uint32_t levels) {
    Hash64 h;
    h.add(FACET_VERSION).add(s.content_hash);
    const double values[] = {double(s.width), double(s.height), double(cube_size), double(levels),
                             double(o.exposure), double(int(o.irradiance.method)), double(o.irradiance.size),
                             double(o.irradiance.source_size), o.irradiance.riemann_step, o.irradiance.blur_sigma,
                             double(o.irradiance.lowmip_size), double(o.irradiance.sh9_windowing), double(int(o.specular.method)),
                             double(o.specular.sample_count), o.specular.automatic_convolve_from,
                             double(o.lut.size), double(o.lut.sample_count), double(int(o.lut.visibility)),
                             o.target_error, double(o.roughness_min), double(o.roughness_max)};
    h.add(values, sizeof values);
    return h.hex();
}

bool up_to_date(const std::string& dir, const std::string& key) {
    for (const char* name : bake_output_names())
        if (!fs::exists(fs::path(dir) / name)) return false;
    std::ifstream in(fs::path(dir) / "bake.json");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    return text.find("\"bake_key\": \"" + key + "\"") != std::string::npos;
}

int bake(const Options& o) {
    const auto start = std::chrono::steady_clock::now();
    auto source = resolve_environment(o.env, o.sky_width, {o.sanitize, o.max_env_width});
    if (!source) throw std::runtime_error(source.error().message);
    if (source->source_width != source->width)
        std::fprintf(stderr, "%s: %s: %ux%u downsampled to %ux%u while reading (--max-env-width %u)\n", program,
                     o.env.c_str(), source->source_width, source->source_height, source->width, source->height,
                     o.max_env_width);
    if (source->image.sanitized_texels)
        std::fprintf(stderr, "%s: %s: replaced %llu NaN, Inf or negative texels with 0\n", program, o.env.c_str(),
                     static_cast<unsigned long long>(source->image.sanitized_texels));
    IblSettings requested;
    requested.cube_size = o.cube_size;
    requested.irradiance = o.irradiance;
    requested.specular = o.specular;
    requested.lut = o.lut;
    IblSettings settings = resolved_ibl_settings(requested, *source);
    const uint32_t cube_size = settings.cube_size;
    const SpecularSettings& specular = settings.specular;
    const std::string key = bake_key(o, *source, cube_size, specular.levels);
    if (!o.force && up_to_date(o.out_dir, key)) {
        std::fprintf(stderr, "%s: %s is up to date (same input and settings; --force bakes again)\n", program,
                     o.out_dir.c_str());
        return 0;
    }
    const std::unique_ptr<Context> vulkan = start_vulkan(o.device, o.validation);
    Context& context = *vulkan;
    // Sizes the device cannot hold fail before anything is created or written.
    if (Status fits = check_ibl_fits(context, *source, settings); !fits)
        throw std::runtime_error(fits.error().message + " (--size, --irradiance-size and --lut-size set these)");
    if (Status s = ensure_directory(o.out_dir); !s) throw std::runtime_error(s.error().message);
    std::fprintf(stderr, "%s: %s (%ux%u) -> cube %u^2, %u specular levels, on %s\n", program, o.env.c_str(),
                 source->width, source->height, cube_size, specular.levels, context.device_name().c_str());

    ShaderCompilerOptions compiler_options;
    compiler_options.disk_cache_dir = o.shader_cache;
    compiler_options.source_dir = shader_dir_from_environment();
    ShaderCompiler compiler(compiler_options);
    ProgramCache programs(context, compiler);
    // Methods used outside their domain say so (bake.json and here).
    // A file's texels are analysed where they are; only a procedural sky is rendered into a copy.
    std::optional<EnvironmentSource> sky_texels;
    if (source->sky) {
        sky_texels = *source;
        if (Status st = materialize_environment(context, programs, *sky_texels); !st)
            throw std::runtime_error(st.error().message);
    }
    const EnvironmentSource& analysed = sky_texels ? *sky_texels : *source;
    pause_for_test("shaders");
    check_interrupt();
    std::optional<Budget> budget;
    if (o.target_error > 0) {
        // The accuracy budget: the cheapest methods that meet the target, measured here.
        auto chosen = choose_within_budget(context, analysed, settings, o.target_error, o.roughness_min,
                                           o.roughness_max, [](const std::string& line) {
                                               std::fprintf(stderr, "%s: %s\n", program, line.c_str());
                                               check_interrupt();
                                           }, compiler_options);
        if (!chosen) throw std::runtime_error(chosen.error().message);
        budget = *chosen;
        settings = budget->settings;
        for (const BudgetChoice& c : budget->choices)
            std::fprintf(stderr, "%s: budget %.3g: %s %s (%s), predicted error %.4f%s\n", program, o.target_error,
                         c.stage.c_str(), c.method.c_str(), c.params.c_str(), c.predicted_error,
                         c.met ? "" : " (nothing met the target: the most accurate)");
    }
    const std::vector<std::string> warnings =
        method_warnings(environment_stats(analysed.image.rgba, analysed.width, analysed.height), settings);
    for (const std::string& w : warnings) std::fprintf(stderr, "%s: warning: %s\n", program, w.c_str());
    auto ibl = std::make_unique<IblBake>(context, programs);
    RenderGraph graph;
    auto check = [](auto result) {
        if (!result) throw std::runtime_error(result.error().message);
        return *result;
    };
    const IblImages images = check(ibl->add_passes(graph, *source, settings));
    // The staging buffer holds the texels now; the bake reads them back from the GPU.
    std::vector<float>().swap(source->image.rgba);
    sky_texels.reset();
    ImageDesc preview_desc;
    preview_desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    preview_desc.width = source->width;
    preview_desc.height = source->height;
    auto preview = check(add_tonemap_preview_pass(graph, programs, images.equirect,
                                                  graph.create_image("preview", preview_desc), o.exposure));
    const ImageHandle equirect = images.equirect, irradiance = images.irradiance, spec = images.specular,
                      lut = images.lut;
    const BufferHandle sh9 = images.sh9;
    const ResourceState readable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                 VK_ACCESS_2_TRANSFER_READ_BIT};
    for (ImageHandle h : {equirect, preview, irradiance, spec, lut}) graph.export_image(h, readable);
    if (sh9.valid())
        graph.export_buffer(sh9, {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                  VK_ACCESS_2_TRANSFER_READ_BIT});
    CompiledGraph compiled = graph.compile();
    OutputSet outputs;
    if (!o.graph_dot.empty())
        if (Status s = write_text_file(outputs.stage(o.graph_dot), compiled.to_dot()); !s)
            throw std::runtime_error(s.error().message);
    check_interrupt();

    std::fprintf(stderr, "%s: running %zu passes\n", program, compiled.passes.size());
    auto run = std::make_unique<GraphRun>(context, compiled);
    const auto passes_start = std::chrono::steady_clock::now();
    run->submit_and_wait([&](uint32_t done, uint32_t total, const std::string& pass) {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - passes_start).count();
        std::fprintf(stderr, "%s: [%u/%u] %-40s %6.2f s\n", program, done, total, pass.c_str(), s);
        if (done == 1) pause_for_test("bake");
        check_interrupt();
    });
    BakeResults results;
    results.timings = run->timings();
    results.environment = read_all(context, *run->transient_image(equirect));
    results.preview = read_all(context, *run->transient_image(preview));
    results.irradiance = read_all(context, *run->transient_image(irradiance));
    results.specular = read_all(context, *run->transient_image(spec));
    results.lut = read_all(context, *run->transient_image(lut));
    if (sh9.valid()) {
        auto bytes = read_buffer(context, *run->transient_buffer(sh9));
        results.sh9.resize(bytes.size() / sizeof(float));
        std::memcpy(results.sh9.data(), bytes.data(), bytes.size());
    }
    // Everything is read back: the GPU's copies and the upload go before the files are written.
    run.reset();
    ibl.reset();

    BakeDescription d;
    d.input = o.env;
    d.content_hash = source->content_hash;
    d.sanitized_texels = source->image.sanitized_texels;
    d.source_width = source->source_width;
    d.source_height = source->source_height;
    d.max_env_width = o.max_env_width;
    d.bake_key = key;
    d.device = context.device_name();
    d.version = FACET_VERSION;
    d.irradiance = settings.irradiance;
    d.specular = settings.specular;
    d.lut = settings.lut;
    if (budget) {
        d.budget_target = budget->target;
        d.budget_roughness_min = budget->roughness_min;
        d.budget_roughness_max = budget->roughness_max;
        for (const BudgetChoice& c : budget->choices)
            d.budget.push_back({c.stage, c.method, c.params, c.predicted_error, c.time_ms, c.met});
    }
    d.warnings = warnings;
    d.cube_size = cube_size;
    d.exposure = o.exposure;
    d.wall_time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (Status s = stage_bake_files(outputs, o.out_dir, d, results); !s) throw std::runtime_error(s.error().message);
    if (Status s = commit_outputs(outputs); !s) throw std::runtime_error(s.error().message);

    double gpu_ms = 0;
    for (const PassTiming& t : results.timings) {
        std::fprintf(stderr, "%s:   %-40s %9.2f ms GPU\n", program, t.name.c_str(), t.time_ms);
        gpu_ms += t.time_ms;
    }
    std::fprintf(stderr, "%s: wrote %s (%.0f ms GPU, %.0f ms wall)\n", program, o.out_dir.c_str(), gpu_ms,
                 d.wall_time_ms);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return facet::run_interruptible(program, [&] { return parse_bake_options(argc, argv); }, bake);
}
