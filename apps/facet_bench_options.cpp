#include "facet_bench_options.h"

#include <stdexcept>

#include "light_spec.h"
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
        .repeatable("--light", "SPEC", "render: a light, as facet-render's --light (repeatable)");
}

void add_sweep_options(cli::Parser& parser) {
    parser.option("--out", "DIR", "sweep: where sweep.csv and sweep.json go (default bench-out)")
        .option("--env-width", "N", "sweep: environments are downsampled to this width (default 256)")
        .option("--stages", "LIST", "sweep: irradiance,specular,lut,image (default all)");
}

}  // namespace

std::optional<BenchOptions> parse_bench_options(int argc, char** argv) {
    cli::Parser parser(program, "bake [ENV...] [options] | render [options] | sweep [ENV...] [options]",
                       "bake: benchmarks facet-bake with its default settings: every ENV (default:\n"
                       "builtin:sky) is baked --runs times; medians of per-pass GPU time\n"
                       "(timestamp queries) and wall time are printed. Extra facet-bake options\n"
                       "can be passed with --bake-args.\n"
                       "render: renders --frames frames of a model (IBL baked once) and prints the\n"
                       "median GPU time of every pass and of the frame, and the wall time per frame.\n"
                       "sweep: every IBL method and parameter and the final image against the\n"
                       "reference mode, on each ENV (default builtin:sky): time and error against\n"
                       "brute-force truth, to sweep.csv/json; scripts/chart.py draws the charts.");
    parser.option("--runs", "N", "bakes per environment (default 5)")
        .option("--bake", "PATH", "the facet-bake program (default: next to facet-bench)")
        .option("--bake-args", "ARGS", "more arguments for facet-bake, e.g. \"--specular filtered\"")
        .option("--csv", "FILE", "also write the medians as CSV");
    add_render_bench_options(parser);
    add_sweep_options(parser);
    BenchOptions o;
    o.args = parser.parse(argc, argv);
    const cli::Parsed& a = o.args;
    if (parser.answered_help_or_version(a, FACET_VERSION)) return std::nullopt;
    if (a.positional.empty() ||
        (a.positional[0] != "bake" && a.positional[0] != "render" && a.positional[0] != "sweep"))
        throw std::invalid_argument("the first argument must be the benchmark: bake, render or sweep");
    if (a.positional[0] == "render" && a.positional.size() > 1)
        throw std::invalid_argument("render takes no positional arguments (use --model and --env)");
    o.benchmark = a.positional[0];
    if (a.has("--runs")) o.runs = cli::parse_int(a.get("--runs"), "--runs", 1, 1000);
    return o;
}

RenderBenchOptions parse_render_bench_options(const cli::Parsed& a) {
    RenderBenchOptions o;
    RenderJob& job = o.job;
    job.model = a.get("--model", job.model);
    job.env = a.get("--env", job.env);
    job.shader_dir = shader_dir_from_environment();
    if (a.has("--width")) job.frame.width = uint32_t(cli::parse_int(a.get("--width"), "--width", 1, 16384));
    if (a.has("--height")) job.frame.height = uint32_t(cli::parse_int(a.get("--height"), "--height", 1, 16384));
    if (a.has("--frames")) o.frames = cli::parse_int(a.get("--frames"), "--frames", 1, 10000);
    for (const std::string& spec : a.all("--light")) {
        auto light = parse_light(spec);
        if (!light) throw std::invalid_argument(light.error().message);
        job.extra_lights.push_back(*light);
    }
    return o;
}

SweepOptions parse_sweep_options(const cli::Parsed& a) {
    SweepOptions o;
    o.envs.assign(a.positional.begin() + (a.positional.empty() ? 0 : 1), a.positional.end());
    if (o.envs.empty()) o.envs = {"builtin:sky"};
    o.stages = a.get("--stages", o.stages);
    o.out_dir = a.get("--out", o.out_dir);
    if (a.has("--env-width")) o.env_width = uint32_t(cli::parse_int(a.get("--env-width"), "--env-width", 8, 4096));
    if (a.has("--runs")) o.runs = cli::parse_int(a.get("--runs"), "--runs", 1, 100);
    return o;
}

}  // namespace facet
