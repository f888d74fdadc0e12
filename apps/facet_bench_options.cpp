#include "facet_bench_options.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "light_spec.h"
#include "render_options.h"
#include "shader_cache.h"

namespace facet {

namespace {

constexpr const char* program = "facet-bench";

void add_render_bench_options(cli::Parser& parser) {
    parser.option("--model", "PATH|builtin:NAME", "render: the model (default builtin:spheres)")
        .option("--env", "PATH|builtin:NAME|none", "render: the environment (default builtin:sky)")
        .option("--width", "W", "render: image width (default 1280)")
        .option("--height", "H", "render: image height (default 720)")
        .option("--frames", "N", "render: frames measured after one warm-up (default 10)")
        .option("--samples", "N", "render: MSAA samples, 1, 2, 4 (default) or 8")
        .option("--shading", "METHOD", "render: environment lighting, as facet-render's --shading (default auto)")
        .flag("--floor", "render: the rasterizer's floor instead of the shading: the same draws, depth and MSAA,\n"
                         "each fragment writing its material's base colour (no texture, no light)")
        .repeatable("--light", "SPEC", "render: a light, as facet-render's --light (repeatable)");
}

void add_sweep_options(cli::Parser& parser) {
    parser.option("--out", "DIR", "sweep: where sweep.csv and sweep.json go (default bench-out)")
        .option("--env-width", "N", "sweep: environments are downsampled to this width (default 256)")
        .option("--stages", "LIST", "sweep: irradiance,specular,lut,image (default all)")
        .option("--size", "WxH", "sweep: the final image's size (default 320x320)")
        .option("--brdf-models", "LIST", "sweep: gltf,thesis: the final image's BRDF models (default gltf)")
        .option("--pixels", "N", "sweep: pixels of the final image the truth is computed for (default 4000)")
        .option("--spp", "LIST", "sweep: the reference mode's samples per pixel (default 1,4,16,64)");
}

}  // namespace

std::optional<BenchOptions> parse_bench_options(int argc, char** argv) {
    cli::Parser parser(program,
                       "bake [ENV...] [options] | render [options] | sweep [ENV...] [options] | accuracy [options]",
                       "bake: benchmarks facet-bake with its default settings: every ENV (default:\n"
                       "builtin:sky) is baked --runs times; medians of per-pass GPU time\n"
                       "(timestamp queries) and wall time are printed. Extra facet-bake options\n"
                       "can be passed with --bake-args.\n"
                       "render: renders --frames frames of a model (IBL baked once) and prints the\n"
                       "median GPU time of every pass and of the frame, and the wall time per frame.\n"
                       "sweep: every IBL method and parameter, and the final image with every shading\n"
                       "method and the reference mode at 1-64 samples per pixel, on each ENV (default\n"
                       "builtin:sky): time and error against brute-force truth (the image per\n"
                       "roughness x metalness group), to sweep.csv/json; scripts/chart.py draws the charts.\n"
                       "accuracy: the final image against the exact integral of its BRDF model, per\n"
                       "roughness x metalness group (see facet-bench accuracy --help).");
    parser.option("--runs", "N", "bakes per environment (default 5)")
        .option("--bake", "PATH", "the facet-bake program (default: next to facet-bench)")
        .option("--bake-args", "ARGS", "more arguments for facet-bake, e.g. \"--specular filtered\"")
        .option("--csv", "FILE", "also write the medians as CSV");
    add_render_bench_options(parser);
    add_sweep_options(parser);
    add_shader_cache_option(parser);
    BenchOptions o;
    o.args = parser.parse(argc, argv);
    const cli::Parsed& a = o.args;
    if (parser.answered_help_or_version(a, FACET_VERSION)) return std::nullopt;
    if (a.positional.empty() ||
        (a.positional[0] != "bake" && a.positional[0] != "render" && a.positional[0] != "sweep"))
        throw std::invalid_argument("the first argument must be the benchmark: bake, render, sweep or accuracy");
    if (a.positional[0] == "render" && a.positional.size() > 1)
        throw std::invalid_argument("render takes no positional arguments (use --model and --env)");
    o.benchmark = a.positional[0];
    o.shader_cache = shader_cache_dir(a);
    if (a.has("--runs")) o.runs = cli::parse_int(a.get("--runs"), "--runs", 1, 1000);
    return o;
}

RenderBenchOptions parse_render_bench_options(const cli::Parsed& a) {
    RenderBenchOptions o;
    RenderJob& job = o.job;
    job.model = a.get("--model", job.model);
    job.env = a.get("--env", job.env);
    job.shader_dir = shader_dir_from_environment();
    job.shader_cache_dir = shader_cache_dir(a);
    if (a.has("--width")) job.frame.width = uint32_t(cli::parse_int(a.get("--width"), "--width", 1, 16384));
    if (a.has("--height")) job.frame.height = uint32_t(cli::parse_int(a.get("--height"), "--height", 1, 16384));
    if (a.has("--frames")) o.frames = cli::parse_int(a.get("--frames"), "--frames", 1, 10000);
    job.frame.samples = samples_option(a, job.frame.samples);
    job.shading = shading_option(a, job.shading);
    job.frame.flat_floor = a.has("--floor");
    for (const std::string& spec : a.all("--light")) {
        auto light = parse_light(spec);
        if (!light) throw std::invalid_argument(light.error().message);
        job.extra_lights.push_back(*light);
    }
    return o;
}

std::optional<AccuracyOptions> parse_accuracy_options(int argc, char** argv) {
    cli::Parser parser(program, "accuracy [options]",
                       "Renders the model (default builtin:spheres, default camera, no skybox) under each\n"
                       "--env (comma-separated; default builtin:sky) and compares every group of pixels\n"
                       "(n.v > 0.3, roughness >= 0.2; roughness bands [0.2,0.4) [0.4,0.6) [0.6,0.8)\n"
                       "[0.8,1] x dielectric/metal) with the double-precision sum of the frame's BRDF\n"
                       "model (--brdf) over every environment texel: mean and max of |lum(render) -\n"
                       "lum(truth)| / lum(truth), the signed mean, the worst group and the forward\n"
                       "pass's wall time (median). Renderer and truth read the same texels: files are\n"
                       "box-filtered to --env-width (a power-of-two factor; default 512 here) and\n"
                       "built-in environments are computed at that width.");
    add_render_options(parser);
    add_shader_cache_option(parser);
    parser.option("--size", "WxH", "accuracy: image size (default 1280x720; same as --width/--height)")
        .option("--pixels", "N", "accuracy: pixels the truth is computed for, spread evenly (default 4000)")
        .option("--runs", "N", "accuracy: frames timed, median (default 3)")
        .option("--json", "FILE", "accuracy: also write the tables as JSON")
        .flag("--reference", "accuracy: measure the reference mode's image (Monte Carlo, 1% noise)")
        .option("--truth-brdf", "gltf|thesis[,...]",
                "accuracy: the BRDF model(s) of the truth (default: the frame's, --brdf)")
        .option("--compare", "METHOD",
                "accuracy: also render each environment with this shading method (e.g. split-sum) and\n"
                "measure it against the same truth");
    const cli::Parsed a = parser.parse(argc, argv);
    if (parser.answered_help_or_version(a, FACET_VERSION)) return std::nullopt;
    if (a.positional.size() != 1 || a.positional[0] != "accuracy")
        throw std::invalid_argument("accuracy takes no positional arguments (use --env E1,E2,...)");
    AccuracyOptions o;
    parse_render_options(a, o.job);
    o.job.shader_dir = shader_dir_from_environment();
    o.job.shader_cache_dir = shader_cache_dir(a);
    if (a.has("--size")) {
        unsigned w = 0, h = 0;
        char extra;
        if (std::sscanf(a.get("--size").c_str(), "%ux%u%c", &w, &h, &extra) != 2 || w < 1 || h < 1 || w > 16384 ||
            h > 16384)
            throw std::invalid_argument("--size: expected WxH (1..16384 each), got '" + a.get("--size") + "'");
        o.job.frame.width = w;
        o.job.frame.height = h;
    }
    // --env-width is the render options' (checked there); its default here is 512.
    o.env_width = a.has("--env-width") ? o.job.env_width : 512;
    o.job.env_width = o.env_width;
    if (a.has("--pixels")) o.max_pixels = uint32_t(cli::parse_int(a.get("--pixels"), "--pixels", 1, 1 << 24));
    if (a.has("--runs")) o.runs = cli::parse_int(a.get("--runs"), "--runs", 1, 100);
    o.json = a.get("--json");
    o.reference = a.has("--reference");
    if (a.has("--json") && o.json.empty()) throw std::invalid_argument("--json needs a file name");
    size_t start = 0;
    const std::string list = a.get("--env", "builtin:sky");
    while (start <= list.size()) {
        const size_t comma = std::min(list.find(',', start), list.size());
        const std::string name = list.substr(start, comma - start);
        if (name.empty()) throw std::invalid_argument("--env: empty entry in '" + list + "'");
        if (name == "none") throw std::invalid_argument("--env: accuracy needs an environment, not 'none'");
        o.envs.push_back(name);
        start = comma + 1;
    }
    for (size_t begin = 0, end; a.has("--truth-brdf") && begin <= a.get("--truth-brdf").size(); begin = end + 1) {
        const std::string list = a.get("--truth-brdf");
        end = std::min(list.find(',', begin), list.size());
        const auto model = parse_brdf_model(list.substr(begin, end - begin));
        if (!model) throw std::invalid_argument("--truth-brdf: expected gltf or thesis (comma-separated), got '" + list + "'");
        o.truth_models.push_back(*model);
    }
    if (o.truth_models.empty()) o.truth_models = {o.job.frame.brdf};
    if (!o.job.ibl_dir.empty()) throw std::invalid_argument("--ibl: accuracy bakes each --env itself");
    if (a.has("--compare")) {
        o.compare = parse_shading_method(a.get("--compare"));
        if (!o.compare)
            throw std::invalid_argument("--compare: expected one of " + std::string(shading_method_names()) + ", got '" +
                                        a.get("--compare") + "'");
        if (o.reference) throw std::invalid_argument("--compare measures frames: leave out --reference");
    }
    return o;
}

namespace {

// "a,b,c" -> {"a", "b", "c"}; an empty entry is an error naming the option.
std::vector<std::string> split_list(const std::string& list, const char* option) {
    std::vector<std::string> items;
    for (size_t begin = 0, end; begin <= list.size(); begin = end + 1) {
        end = std::min(list.find(',', begin), list.size());
        items.push_back(list.substr(begin, end - begin));
        if (items.back().empty()) throw std::invalid_argument(std::string(option) + ": empty entry in '" + list + "'");
    }
    return items;
}

}  // namespace

SweepOptions parse_sweep_options(const cli::Parsed& a) {
    SweepOptions o;
    o.shader_cache = shader_cache_dir(a);
    if (a.has("--size")) {
        unsigned w = 0, h = 0;
        char extra;
        if (std::sscanf(a.get("--size").c_str(), "%ux%u%c", &w, &h, &extra) != 2 || w < 8 || h < 8 || w > 8192 ||
            h > 8192)
            throw std::invalid_argument("--size: expected WxH (8..8192 each), got '" + a.get("--size") + "'");
        o.image_width = w;
        o.image_height = h;
    }
    if (a.has("--brdf-models")) {
        o.brdf_models.clear();
        for (const std::string& name : split_list(a.get("--brdf-models"), "--brdf-models")) {
            const auto model = parse_brdf_model(name);
            if (!model) throw std::invalid_argument("--brdf-models: expected gltf or thesis, got '" + name + "'");
            o.brdf_models.push_back(*model);
        }
    }
    if (a.has("--pixels")) o.max_pixels = uint32_t(cli::parse_int(a.get("--pixels"), "--pixels", 1, 1 << 24));
    if (a.has("--spp")) {
        o.reference_spp.clear();
        for (const std::string& n : split_list(a.get("--spp"), "--spp"))
            o.reference_spp.push_back(uint32_t(cli::parse_int(n, "--spp", 1, 65536)));
    }
    o.envs.assign(a.positional.begin() + (a.positional.empty() ? 0 : 1), a.positional.end());
    if (o.envs.empty()) o.envs = {"builtin:sky"};
    o.stages = a.get("--stages", o.stages);
    o.out_dir = a.get("--out", o.out_dir);
    if (a.has("--env-width")) o.env_width = uint32_t(cli::parse_int(a.get("--env-width"), "--env-width", 8, 4096));
    if (a.has("--runs")) o.runs = cli::parse_int(a.get("--runs"), "--runs", 1, 100);
    return o;
}

}  // namespace facet
