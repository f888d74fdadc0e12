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
#include "render_options.h"
#include "shader_cache.h"
#include "core/hash.h"
#include "gpu/context.h"
#include "gpu/transfer.h"
#include "graph/compiled_graph.h"
#include "graph/graph_run.h"
#include "ibl/ibl_bake.h"
#include "ibl/method_domain.h"
#include "io/atomic_file.h"
#include "io/environment_image.h"
#include "io/output_set.h"
#include "render/tonemap_preview.h"
#include "shader/program_cache.h"

namespace {

using namespace facet;
namespace fs = std::filesystem;

constexpr const char* program = "facet-bake";

struct Options {
    std::string env, out_dir, device, graph_dot;
    std::string shader_cache;  // empty: no on-disk shader cache
    uint32_t sky_width = 1024;
    uint32_t max_env_width = kDefaultMaxEnvironmentWidth;  // wider files are downsampled while read
    uint32_t cube_size = 0;  // 0: input height / 2
    float exposure = 1.0f;
    bool validation = false, sanitize = false, force = false;
    double target_error = 0;  // 0: no accuracy budget
    float roughness_min = 0.0f, roughness_max = 1.0f;
    IrradianceSettings irradiance;
    SpecularSettings specular;
    BrdfLutSettings lut;
};

cli::Parser make_parser() {
    cli::Parser p(program, "ENV|builtin:NAME --out DIR [options]",
                  "Bakes image-based lighting for an equirectangular environment (.hdr, .exr, any\n"
                  "size) or a built-in one (builtin:sky: a sun ~4e4 times the sky; builtin:white:\n"
                  "radiance 1). Writes into DIR: specular.ktx2 (GGX prefiltered cube, one roughness\n"
                  "per level), irradiance.ktx2 (E/pi cube), brdf_lut.ktx2 (R = A, G = B, B = E_avg),\n"
                  "brdf_lut.png, environment.exr/.hdr/.png and bake.json. A bake whose bake.json\n"
                  "records the same input and settings is skipped (--force redoes it).");
    p.option("--out", "DIR", "output directory (created if missing)")
        .option("--irradiance", "METHOD", "convolve (default), riemann, sh9, blur, lowmip")
        .flag("--sh9-no-window", "sh9: keep the raw coefficients (may ring below 0 on a sun)")
        .option("--specular", "METHOD", "automatic (default), importance, filtered, convolve, mips")
        .option("--samples", "N", "GGX samples per texel for importance/filtered levels (default 1024)")
        .option("--size", "N", "cube face size (default: input height / 2)")
        .option("--levels", "N", "specular levels, roughness m/(N-1) (default 6)")
        .option("--irradiance-size", "N", "irradiance face size (default 32)")
        .option("--lut-size", "N", "BRDF LUT width and height (default 128)")
        .option("--lut-samples", "N", "GGX samples per LUT texel (default 2048)")
        .flag("--lut-height-correlated", "LUT with the height-correlated Smith term instead of Schlick-GGX")
        .option("--width", "N", "width of a built-in environment (default 1024, height N/2)")
        .option("--max-env-width", "N", "downsample wider environment files to N x N/2 while reading them\n"
                                         "                          (default " + std::to_string(kDefaultMaxEnvironmentWidth) +
                                             "; a built-in's --width may not exceed it)")
        .option("--exposure", "E", "exposure of environment.png (default 1)")
        .flag("--sanitize", "replace NaN, Inf and negative texels of ENV with 0 instead of failing")
        .option("--target-error", "E", "accuracy budget: the cheapest methods whose measured relative RMS error\n"
                                        "                          against the brute-force truth is at most E (e.g. 0.02)")
        .option("--roughness", "A,B", "budget: the scene's roughness range; specular is judged on it (default 0,1)")
        .flag("--force", "bake even if DIR holds a bake of the same input and settings")
        .option("--device", "NAME|INDEX", "Vulkan device (default: FACET_DEVICE, a GPU, else lavapipe)")
        .flag("--validation", "enable the Khronos validation layer")
        .option("--graph-dot", "FILE", "also write the compiled render graph as Graphviz dot");
    add_shader_cache_option(p);
    return p;
}

uint32_t positive(const cli::Parsed& a, const char* name, int max) {
    return static_cast<uint32_t>(cli::parse_int(a.get(name), name, 1, max));
}

std::optional<Options> parse(int argc, char** argv) {
    cli::Parser parser = make_parser();
    cli::Parsed a = parser.parse(argc, argv);
    if (parser.answered_help_or_version(a, FACET_VERSION)) return std::nullopt;
    if (a.positional.size() != 1)
        throw std::invalid_argument("expected exactly one environment (a file or builtin:NAME), got " +
                                    std::to_string(a.positional.size()));
    if (!a.has("--out")) throw std::invalid_argument("--out DIR is required");
    Options o;
    o.env = a.positional[0];
    o.out_dir = a.get("--out");
    if (a.has("--irradiance")) {
        auto m = parse_irradiance_method(a.get("--irradiance"));
        if (!m) throw std::invalid_argument("--irradiance: unknown method '" + a.get("--irradiance") + "'");
        o.irradiance.method = *m;
    }
    if (a.has("--specular")) {
        auto m = parse_specular_method(a.get("--specular"));
        if (!m) throw std::invalid_argument("--specular: unknown method '" + a.get("--specular") + "'");
        o.specular.method = *m;
    }
    if (a.has("--samples")) o.specular.sample_count = positive(a, "--samples", 1 << 20);
    if (a.has("--size")) o.cube_size = positive(a, "--size", 8192);
    if (a.has("--levels")) o.specular.levels = positive(a, "--levels", 16);
    if (a.has("--irradiance-size")) o.irradiance.size = positive(a, "--irradiance-size", 1024);
    if (a.has("--lut-size")) o.lut.size = positive(a, "--lut-size", 4096);
    if (a.has("--lut-samples")) o.lut.sample_count = positive(a, "--lut-samples", 1 << 20);
    if (a.has("--lut-height-correlated")) o.lut.visibility = LutVisibility::height_correlated;
    if (a.has("--max-env-width")) o.max_env_width = positive(a, "--max-env-width", int(kMaxEnvironmentSide) / 4);
    if (a.has("--width")) o.sky_width = positive(a, "--width", 16384);
    else o.sky_width = std::min(o.sky_width, std::max(2u, o.max_env_width & ~1u));
    if (o.sky_width % 2) throw std::invalid_argument("--width must be even (the height is width / 2)");
    if (o.sky_width > o.max_env_width)
        throw std::invalid_argument("--width " + std::to_string(o.sky_width) + " is above --max-env-width " +
                                    std::to_string(o.max_env_width) + " (raise both for a wider built-in environment)");
    if (a.has("--exposure")) {
        o.exposure = static_cast<float>(cli::parse_double(a.get("--exposure"), "--exposure"));
        if (o.exposure <= 0) throw std::invalid_argument("--exposure must be positive");
    }
    if (a.has("--sh9-no-window")) o.irradiance.sh9_windowing = false;
    o.sanitize = a.has("--sanitize");
    if (a.has("--target-error")) {
        o.target_error = cli::parse_double(a.get("--target-error"), "--target-error");
        if (!(o.target_error > 0 && o.target_error < 10)) throw std::invalid_argument("--target-error must be in (0, 10)");
    }
    if (a.has("--roughness")) {
        char extra;
        if (std::sscanf(a.get("--roughness").c_str(), "%f,%f%c", &o.roughness_min, &o.roughness_max, &extra) != 2 ||
            !(o.roughness_min >= 0 && o.roughness_min <= o.roughness_max && o.roughness_max <= 1))
            throw std::invalid_argument("--roughness: expected A,B with 0 <= A <= B <= 1, got '" + a.get("--roughness") + "'");
    }
    o.force = a.has("--force");
    o.device = a.get("--device");
    o.validation = a.has("--validation");
    o.graph_dot = a.get("--graph-dot");
    o.shader_cache = shader_cache_dir(a);
    return o;
}

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
    return facet::run_interruptible(program, [&] { return parse(argc, argv); }, bake);
}
