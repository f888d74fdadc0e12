// facet-bake: environment -> image-based-lighting data. Today it produces the
// environment itself on the GPU through the render graph (builtin:sky, builtin:white)
// and writes it as linear EXR and HDR, an sRGB preview PNG and bake.json.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "cli.h"
#include "core/result.h"
#include "gpu/context.h"
#include "gpu/transfer.h"
#include "graph/compiled_graph.h"
#include "graph/graph_run.h"
#include "ibl/procedural_sky.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/json_writer.h"
#include "render/tonemap_preview.h"
#include "shader/program_cache.h"

namespace {

using namespace facet;

constexpr const char* program = "facet-bake";

struct Options {
    std::string env;
    std::string out_dir;
    uint32_t width = 1024;
    float exposure = 1.0f;
    std::string device;
    bool validation = false;
    std::string graph_dot;
};

cli::Parser make_parser() {
    cli::Parser p(program, "ENV|builtin:NAME --out DIR [options]",
                  "Bakes image-based-lighting data for an environment. Built-in environments:\n"
                  "  builtin:sky    procedural sky with a sun ~4e4 times brighter than the sky\n"
                  "  builtin:white  uniform radiance 1 (the white furnace)\n"
                  "Writes DIR/environment.exr (linear), environment.hdr, environment.png\n"
                  "(Reinhard, sRGB) and DIR/bake.json (passes, GPU times, device, version).");
    p.option("--out", "DIR", "output directory (created if missing; earlier outputs are replaced)")
        .option("--width", "N", "equirectangular width in texels, height is N/2 (default 1024)")
        .option("--exposure", "E", "exposure of the preview PNG (default 1)")
        .option("--device", "NAME|INDEX", "Vulkan device (default: FACET_DEVICE, a GPU, else lavapipe)")
        .flag("--validation", "enable the Khronos validation layer")
        .option("--graph-dot", "FILE", "also write the compiled render graph as Graphviz dot");
    return p;
}

Options parse(int argc, char** argv, bool& exit_now) {
    cli::Parser parser = make_parser();
    cli::Parsed a = parser.parse(argc, argv);
    exit_now = false;
    if (a.has("--help")) {
        std::fputs(parser.help_text().c_str(), stdout);
        exit_now = true;
        return {};
    }
    if (a.has("--version")) {
        std::printf("%s %s\n", program, FACET_VERSION);
        exit_now = true;
        return {};
    }
    if (a.positional.size() != 1)
        throw std::invalid_argument("expected exactly one environment (a file or builtin:NAME), got " +
                                    std::to_string(a.positional.size()));
    if (!a.has("--out")) throw std::invalid_argument("--out DIR is required");
    Options o;
    o.env = a.positional[0];
    o.out_dir = a.get("--out");
    if (a.has("--width")) o.width = static_cast<uint32_t>(cli::parse_int(a.get("--width"), "--width", 2, 16384));
    if (o.width % 2) throw std::invalid_argument("--width must be even (the height is width / 2)");
    if (a.has("--exposure")) {
        o.exposure = static_cast<float>(cli::parse_double(a.get("--exposure"), "--exposure"));
        if (o.exposure <= 0) throw std::invalid_argument("--exposure must be positive");
    }
    o.device = a.get("--device");
    o.validation = a.has("--validation");
    o.graph_dot = a.get("--graph-dot");
    return o;
}

Result<ProceduralSky> resolve_environment(const std::string& env) {
    if (env == "builtin:sky") return ProceduralSky{};
    if (env == "builtin:white") return ProceduralSky::white();
    if (env.rfind("builtin:", 0) == 0)
        return Error{env + ": unknown built-in environment (builtin:sky, builtin:white)"};
    if (!std::filesystem::exists(env)) return Error{env + ": no such file"};
    return Error{env + ": environment files are not baked yet; this version bakes builtin:sky and builtin:white"};
}

template <class T>
std::vector<T> read_texels(Context& context, GraphRun& run, ImageHandle image) {
    auto bytes = read_image(context, *run.transient_image(image), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    std::vector<T> texels(bytes.size() / sizeof(T));
    std::memcpy(texels.data(), bytes.data(), bytes.size());
    return texels;
}

int bake(const Options& o) {
    const auto start = std::chrono::steady_clock::now();
    auto sky = resolve_environment(o.env);
    if (!sky) throw std::runtime_error(sky.error().message);
    if (Status s = ensure_directory(o.out_dir); !s) throw std::runtime_error(s.error().message);

    ContextOptions context_options;
    context_options.device = o.device;
    if (o.validation) context_options.validation = true;
    auto created = Context::create(context_options);
    if (!created) throw std::runtime_error("cannot start Vulkan: " + created.error().message);
    Context& context = *created.value();
    const uint32_t width = o.width, height = o.width / 2;
    std::fprintf(stderr, "%s: %s, %ux%u, on %s\n", program, o.env.c_str(), width, height,
                 context.device_name().c_str());

    ShaderCompiler compiler;
    ProgramCache programs(context, compiler);
    RenderGraph graph;
    ImageDesc hdr_desc;
    hdr_desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    hdr_desc.width = width;
    hdr_desc.height = height;
    ImageDesc ldr_desc = hdr_desc;
    ldr_desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    auto environment = graph.create_image("environment", hdr_desc);
    auto preview = graph.create_image("preview", ldr_desc);
    auto sky_out = add_procedural_sky_pass(graph, programs, sky.value(), environment);
    if (!sky_out) throw std::runtime_error(sky_out.error().message);
    auto preview_out = add_tonemap_preview_pass(graph, programs, *sky_out, preview, o.exposure);
    if (!preview_out) throw std::runtime_error(preview_out.error().message);
    const ResourceState readable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                 VK_ACCESS_2_TRANSFER_READ_BIT};
    graph.export_image(*sky_out, readable);
    graph.export_image(*preview_out, readable);
    CompiledGraph compiled = graph.compile();
    if (!o.graph_dot.empty())
        if (Status s = write_text_file(o.graph_dot, compiled.to_dot()); !s) throw std::runtime_error(s.error().message);

    auto run = run_graph(context, compiled);
    const auto timings = run->timings();
    auto hdr = read_texels<float>(context, *run, environment);
    auto ldr = read_texels<uint8_t>(context, *run, preview);
    size_t bad = 0;
    for (float v : hdr) bad += !std::isfinite(v) || v < 0;
    if (bad) throw std::runtime_error(std::to_string(bad) + " texels of the generated environment are NaN, Inf or negative");

    namespace fs = std::filesystem;
    const std::string names[] = {"environment.exr", "environment.hdr", "environment.png", "bake.json"};
    for (const std::string& name : names)
        if (fs::exists(fs::path(o.out_dir) / name))
            std::fprintf(stderr, "%s: replacing %s\n", program, (fs::path(o.out_dir) / name).c_str());
    auto path = [&](const std::string& name) { return (fs::path(o.out_dir) / name).string(); };
    for (const char* name : {"environment.exr", "environment.hdr"})
        if (Status s = write_hdr_image(path(name), width, height, hdr); !s) throw std::runtime_error(s.error().message);
    if (Status s = write_ldr_image(path("environment.png"), width, height, ldr); !s)
        throw std::runtime_error(s.error().message);

    const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    JsonWriter json;
    json.begin_object()
        .value("program", program)
        .value("version", FACET_VERSION)
        .value("device", context.device_name())
        .begin_object("input")
        .value("name", o.env)
        .value("content_hash", sky->content_hash())
        .end_object()
        .begin_object("environment")
        .value("width", width)
        .value("height", height)
        .value("format", "R32G32B32A32_SFLOAT")
        .value("mapping", "equirectangular: u = atan2(z, x) / 2pi + 0.5, v = asin(y) / pi + 0.5, v = 1 top row")
        .end_object()
        .value("preview_exposure", double(o.exposure))
        .begin_array("passes");
    for (const PassTiming& t : timings) json.begin_object().value("name", t.name).value("gpu_time_ms", std::round(t.time_ms * 1e3) / 1e3).end_object();
    json.end_array().begin_array("outputs");
    for (const char* name : {"environment.exr", "environment.hdr", "environment.png"}) json.value("", name);
    json.end_array().value("wall_time_ms", std::round(wall_ms * 1e3) / 1e3).end_object();
    if (Status s = write_text_file(path("bake.json"), json.str()); !s) throw std::runtime_error(s.error().message);

    for (const PassTiming& t : timings) std::fprintf(stderr, "%s:   pass %-16s %8.2f ms GPU\n", program, t.name.c_str(), t.time_ms);
    std::fprintf(stderr, "%s: wrote %s/{environment.exr,environment.hdr,environment.png,bake.json} in %.0f ms\n",
                 program, o.out_dir.c_str(), wall_ms);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    try {
        bool exit_now = false;
        options = parse(argc, argv, exit_now);
        if (exit_now) return 0;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
        return 2;
    }
    try {
        return bake(options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
        return 1;
    }
}
