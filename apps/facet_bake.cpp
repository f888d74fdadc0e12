// facet-bake: environment -> image-based-lighting data. Today it brings the environment
// into the render graph (generated on the GPU for builtin:sky and builtin:white, or
// loaded from a file and uploaded), bakes the split-sum BRDF LUT, and writes the
// environment as linear EXR and HDR, an sRGB preview PNG, the LUT and bake.json.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <filesystem>
#include <vector>

#include "cli.h"
#include "core/result.h"
#include "gpu/context.h"
#include "gpu/transfer.h"
#include "graph/compiled_graph.h"
#include "graph/graph_run.h"
#include "graph/transfer_passes.h"
#include "ibl/brdf_lut.h"
#include "ibl/procedural_sky.h"
#include "io/environment_image.h"
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
    bool sanitize = false;
    BrdfLutSettings lut;
};

cli::Parser make_parser() {
    cli::Parser p(program, "ENV|builtin:NAME --out DIR [options]",
                  "Bakes image-based-lighting data for an environment: an equirectangular image\n"
                  "(.hdr, .exr, any size) or a built-in one:\n"
                  "  builtin:sky    procedural sky with a sun ~4e4 times brighter than the sky\n"
                  "  builtin:white  uniform radiance 1 (the white furnace)\n"
                  "Writes DIR/environment.exr (linear), environment.hdr, environment.png\n"
                  "(Reinhard, sRGB), brdf_lut.exr (R = A, G = B, B = E_avg), brdf_lut.png and\n"
                  "DIR/bake.json"
                  "(passes, GPU times, device, version).");
    p.option("--out", "DIR", "output directory (created if missing; earlier outputs are replaced)")
        .option("--width", "N", "equirectangular width in texels, height is N/2 (default 1024)")
        .option("--exposure", "E", "exposure of the preview PNG (default 1)")
        .option("--device", "NAME|INDEX", "Vulkan device (default: FACET_DEVICE, a GPU, else lavapipe)")
        .flag("--validation", "enable the Khronos validation layer")
        .flag("--sanitize", "replace NaN, Inf and negative texels of ENV with 0 instead of failing")
        .option("--lut-size", "N", "BRDF LUT width and height (default 128)")
        .option("--lut-samples", "N", "GGX samples per LUT texel (default 2048)")
        .flag("--lut-height-correlated", "LUT with the height-correlated Smith term instead of Schlick-GGX")
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
    o.sanitize = a.has("--sanitize");
    if (a.has("--lut-size")) o.lut.size = static_cast<uint32_t>(cli::parse_int(a.get("--lut-size"), "--lut-size", 1, 4096));
    if (a.has("--lut-samples"))
        o.lut.sample_count = static_cast<uint32_t>(cli::parse_int(a.get("--lut-samples"), "--lut-samples", 1, 1 << 20));
    if (a.has("--lut-height-correlated")) o.lut.visibility = LutVisibility::height_correlated;
    return o;
}

// The environment: a procedural one (generated on the GPU) or a file's texels.
struct Source {
    std::optional<ProceduralSky> sky;
    EnvironmentImage image;
    std::string content_hash;
};

Result<Source> resolve_environment(const Options& o) {
    Source source;
    if (o.env == "builtin:sky") source.sky = ProceduralSky{};
    else if (o.env == "builtin:white") source.sky = ProceduralSky::white();
    else if (o.env.rfind("builtin:", 0) == 0)
        return Error{o.env + ": unknown built-in environment (builtin:sky, builtin:white)"};
    if (source.sky) {
        source.content_hash = source.sky->content_hash();
        return source;
    }
    auto image = load_environment(o.env, {o.sanitize});
    if (!image) return image.error();
    source.image = std::move(image).value();
    source.content_hash = source.image.content_hash;
    if (source.image.sanitized_texels)
        std::fprintf(stderr, "%s: %s: replaced %llu NaN, Inf or negative texels with 0\n", program, o.env.c_str(),
                     static_cast<unsigned long long>(source.image.sanitized_texels));
    return source;
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
    auto source = resolve_environment(o);
    if (!source) throw std::runtime_error(source.error().message);
    if (Status s = ensure_directory(o.out_dir); !s) throw std::runtime_error(s.error().message);

    ContextOptions context_options;
    context_options.device = o.device;
    if (o.validation) context_options.validation = true;
    auto created = Context::create(context_options);
    if (!created) throw std::runtime_error("cannot start Vulkan: " + created.error().message);
    Context& context = *created.value();
    const uint32_t width = source->sky ? o.width : source->image.width;
    const uint32_t height = source->sky ? o.width / 2 : source->image.height;
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
    std::optional<Buffer> staging;
    ImageHandle env_out;
    if (source->sky) {
        auto generated = add_procedural_sky_pass(graph, programs, *source->sky, environment);
        if (!generated) throw std::runtime_error(generated.error().message);
        env_out = *generated;
    } else {
        const std::vector<float>& texels = source->image.rgba;
        staging.emplace(context, texels.size() * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload,
                        "environment upload");
        std::memcpy(staging->mapped(), texels.data(), texels.size() * sizeof(float));
        staging->flush();
        auto staged = graph.import_buffer("environment texels", {staging->handle(), staging->size(),
                                                                 {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_HOST_BIT,
                                                                  VK_ACCESS_2_HOST_WRITE_BIT},
                                                                 {}});
        env_out = add_upload_pass(graph, "upload environment", staged, environment);
    }
    auto preview_out = add_tonemap_preview_pass(graph, programs, env_out, preview, o.exposure);
    if (!preview_out) throw std::runtime_error(preview_out.error().message);
    ImageDesc lut_desc;
    lut_desc.width = lut_desc.height = o.lut.size;
    auto lut = graph.create_image("brdf lut", lut_desc);
    auto lut_out = add_brdf_lut_passes(graph, programs, o.lut, lut);
    if (!lut_out) throw std::runtime_error(lut_out.error().message);
    const ResourceState readable{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                 VK_ACCESS_2_TRANSFER_READ_BIT};
    graph.export_image(env_out, readable);
    graph.export_image(*preview_out, readable);
    graph.export_image(*lut_out, readable);
    CompiledGraph compiled = graph.compile();
    if (!o.graph_dot.empty())
        if (Status s = write_text_file(o.graph_dot, compiled.to_dot()); !s) throw std::runtime_error(s.error().message);

    auto run = run_graph(context, compiled);
    const auto timings = run->timings();
    auto hdr = read_texels<float>(context, *run, environment);
    auto ldr = read_texels<uint8_t>(context, *run, preview);
    auto lut_texels = read_texels<float>(context, *run, lut);
    size_t bad = 0;
    for (float v : hdr) bad += !std::isfinite(v) || v < 0;
    for (float v : lut_texels) bad += !std::isfinite(v);
    if (bad) throw std::runtime_error(std::to_string(bad) + " values of the bake are NaN, Inf or negative");

    namespace fs = std::filesystem;
    const std::string names[] = {"environment.exr", "environment.hdr", "environment.png",
                                 "brdf_lut.exr",    "brdf_lut.png",    "bake.json"};
    for (const std::string& name : names)
        if (fs::exists(fs::path(o.out_dir) / name))
            std::fprintf(stderr, "%s: replacing %s\n", program, (fs::path(o.out_dir) / name).c_str());
    auto path = [&](const std::string& name) { return (fs::path(o.out_dir) / name).string(); };
    for (const char* name : {"environment.exr", "environment.hdr"})
        if (Status s = write_hdr_image(path(name), width, height, hdr); !s) throw std::runtime_error(s.error().message);
    if (Status s = write_ldr_image(path("environment.png"), width, height, ldr); !s)
        throw std::runtime_error(s.error().message);
    if (Status s = write_hdr_image(path("brdf_lut.exr"), o.lut.size, o.lut.size, lut_texels); !s)
        throw std::runtime_error(s.error().message);
    // Preview: A, B and E_avg are within [0, 1]; shown linearly, roughness 0 on the top row.
    std::vector<uint8_t> lut_preview(lut_texels.size());
    for (uint32_t y = 0; y < o.lut.size; ++y)
        for (uint32_t x = 0; x < o.lut.size * 4; ++x) {
            const float v = lut_texels[size_t(y) * o.lut.size * 4 + x];
            lut_preview[size_t(y) * o.lut.size * 4 + x] =
                x % 4 == 3 ? 255 : static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
        }
    if (Status s = write_ldr_image(path("brdf_lut.png"), o.lut.size, o.lut.size, lut_preview); !s)
        throw std::runtime_error(s.error().message);

    const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    JsonWriter json;
    json.begin_object()
        .value("program", program)
        .value("version", FACET_VERSION)
        .value("device", context.device_name())
        .begin_object("input")
        .value("name", o.env)
        .value("content_hash", source->content_hash)
        .value("sanitized_texels", int64_t(source->image.sanitized_texels))
        .end_object()
        .begin_object("environment")
        .value("width", width)
        .value("height", height)
        .value("format", "R32G32B32A32_SFLOAT")
        .value("mapping", "equirectangular: u = atan2(z, x) / 2pi + 0.5, v = asin(y) / pi + 0.5, v = 1 top row")
        .end_object()
        .value("preview_exposure", double(o.exposure))
        .begin_object("brdf_lut")
        .value("size", o.lut.size)
        .value("samples", o.lut.sample_count)
        .value("visibility", o.lut.visibility == LutVisibility::height_correlated ? "smith height-correlated"
                                                                                : "smith schlick-ggx k = r^2/2")
        .value("channels", "R = A (scale), G = B (bias), B = E_avg (multiscatter)")
        .end_object()
        .begin_array("passes");
    for (const PassTiming& t : timings) json.begin_object().value("name", t.name).value("gpu_time_ms", std::round(t.time_ms * 1e3) / 1e3).end_object();
    json.end_array().begin_array("outputs");
    for (const std::string& name : names)
        if (name != "bake.json") json.value("", name);
    json.end_array().value("wall_time_ms", std::round(wall_ms * 1e3) / 1e3).end_object();
    if (Status s = write_text_file(path("bake.json"), json.str()); !s) throw std::runtime_error(s.error().message);

    for (const PassTiming& t : timings) std::fprintf(stderr, "%s:   pass %-16s %8.2f ms GPU\n", program, t.name.c_str(), t.time_ms);
    std::fprintf(stderr, "%s: wrote %s/{environment.exr,.hdr,.png, brdf_lut.exr,.png, bake.json} in %.0f ms\n",
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
