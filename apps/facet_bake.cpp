// facet-bake: an environment -> the image-based-lighting data of design.md: the
// prefiltered specular cube, the diffuse irradiance cube and the split-sum BRDF LUT
// (KTX2), previews, and bake.json. All work is compute passes of one render graph.
// The files appear together or not at all; SIGINT and SIGTERM stop it at the next safe
// point with nothing written (apps/interrupt.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <vector>

#include "cli.h"
#include "interrupt.h"
#include "facet_bake_options.h"
#include "render_options.h"
#include "shader_cache.h"
#include <facet/gpu/context.h>
#include <facet/ibl/bake_rules.h>
#include <facet/ibl/baked_environment.h>
#include <facet/io/atomic_file.h>
#include <facet/io/environment_image.h>
#include <facet/io/output_set.h>
#include <facet/shader/program_cache.h>

namespace {

using namespace facet;
namespace fs = std::filesystem;

constexpr const char* program = "facet-bake";

using Options = BakeOptions;

BakeSettings bake_settings(const Options& o) {
    BakeSettings b;
    b.ibl.cube_size = o.cube_size;
    b.ibl.irradiance = o.irradiance;
    b.ibl.specular = o.specular;
    b.ibl.lut = o.lut;
    b.format = o.float32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
    b.extract_lights = o.extract_lights;
    b.target_error = o.target_error;
    b.roughness_min = o.roughness_min;
    b.roughness_max = o.roughness_max;
    b.preview_exposure = o.exposure;
    b.lut_cache.directory = o.lut_cache;
    return b;
}

bool up_to_date(const std::string& dir, const std::string& key) {
    for (const char* name : baked_environment_files())
        if (!fs::exists(fs::path(dir) / name)) return false;
    auto saved = saved_bake_key(dir);
    return saved && *saved == key;
}

int bake(const Options& o) {
    // The environment's float files are encoded on a thread of their own, made before the
    // device's (a thread made while the Vulkan loader opens the drivers waits for it,
    // ~40 ms), which gets the texels once they are read. `to_encode` goes before `encoded`
    // (an early return breaks the promise and the encoder ends).
    EncodedEnvironment encoded;
    std::promise<std::shared_ptr<const EnvironmentSource>> to_encode;
    encoded = encode_environment_files_in_background(to_encode.get_future().share());
    // Vulkan starts on a second thread (the loader's drivers, LLVM and the device: ~0.1 s
    // on lavapipe) while this one reads the input. A bake that runs whatever the input
    // holds (--force, or no bake in DIR to compare with) starts it first thing; an
    // up-to-date check reads the input first and, when the bake is up to date, needs no
    // device at all.
    std::future<std::unique_ptr<Context>> starting;
    auto start = [&] { starting = std::async(std::launch::async, [&] { return start_vulkan(o.device, o.validation); }); };
    if (o.force || !fs::exists(fs::path(o.out_dir) / "bake.json")) start();
    auto resolved_source = resolve_environment(o.env, o.sky_width, {o.sanitize, o.max_env_width});
    if (!resolved_source) throw std::runtime_error(resolved_source.error().message);
    const auto source = std::make_shared<const EnvironmentSource>(std::move(*resolved_source));
    if (source->source_width != source->width)
        std::fprintf(stderr, "%s: %s: %ux%u downsampled to %ux%u while reading (--max-env-width %u)\n", program,
                     o.env.c_str(), source->source_width, source->source_height, source->width, source->height,
                     o.max_env_width);
    if (source->image.sanitized_texels)
        std::fprintf(stderr, "%s: %s: replaced %llu NaN, Inf or negative texels with 0\n", program, o.env.c_str(),
                     static_cast<unsigned long long>(source->image.sanitized_texels));
    BakeSettings requested = bake_settings(o);
    BakeSettings resolved = requested;
    resolved.ibl = resolved_ibl_settings(requested.ibl, *source);
    const std::string key = bake_key(*source, resolved);
    if (!o.force && up_to_date(o.out_dir, key)) {
        std::fprintf(stderr, "%s: %s is up to date (same input and settings; --force bakes again)\n", program,
                     o.out_dir.c_str());
        return 0;
    }
    if (!starting.valid()) start();
    // A file's environment.exr and .hdr (the bake's own texels unless lights are taken out).
    const bool own_texels = !source->sky && !o.extract_lights;
    to_encode.set_value(own_texels ? source : nullptr);
    if (own_texels) requested.encoded_environment = encoded;
    const std::unique_ptr<Context> vulkan = starting.get();
    Context& context = *vulkan;
    // Sizes the device cannot hold fail before anything is created or written.
    if (Status fits = check_ibl_fits(context, *source, resolved.ibl, resolved.extract_lights); !fits)
        throw std::runtime_error(fits.error().message + " (--size, --irradiance-size and --lut-size set these)");
    if (Status s = ensure_directory(o.out_dir); !s) throw std::runtime_error(s.error().message);
    std::fprintf(stderr, "%s: %s (%ux%u) -> cube %u^2, %u specular levels, on %s\n", program, o.env.c_str(),
                 source->width, source->height, resolved.ibl.cube_size, resolved.ibl.specular.levels,
                 context.device_name().c_str());

    ShaderCompilerOptions compiler_options;
    compiler_options.disk_cache_dir = o.shader_cache;
    compiler_options.source_dir = shader_dir_from_environment();
    ShaderCompiler compiler(compiler_options);
    ProgramCache programs(context, compiler);
    OutputSet outputs;
    BakeCallbacks callbacks;
    callbacks.progress = [&](const std::string& line) { std::fprintf(stderr, "%s: %s\n", program, line.c_str()); };
    const auto passes_start = std::chrono::steady_clock::now();
    callbacks.pass_done = [&](uint32_t done, uint32_t total, const std::string& pass) {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - passes_start).count();
        std::fprintf(stderr, "%s: [%u/%u] %-40s %6.2f s\n", program, done, total, pass.c_str(), s);
        if (done == 1) pause_for_test("bake");
    };
    // Safe points: a signal stops the bake there (interrupt.h); the test hook pauses
    // between the first shaders and the bake's.
    callbacks.stop = [](const char* point) {
        if (std::strcmp(point, "shaders") == 0) pause_for_test("shaders");
        return interrupt_signal() != 0;
    };
    if (!o.graph_dot.empty())
        callbacks.graph_dot = [&](const std::string& dot) {
            if (Status s = write_text_file(outputs.stage(o.graph_dot), dot); !s)
                throw std::runtime_error(s.error().message);
        };
    auto baked = bake_environment(context, programs, *source, requested, callbacks);
    check_interrupt();
    if (!baked) throw std::runtime_error(baked.error().message);
    const BakeMetadata& meta = baked->metadata();
    if (meta.budget)
        for (const BudgetChoice& c : meta.budget->choices)
            std::fprintf(stderr, "%s: budget %.3g: %s %s (%s), predicted error %.4f%s\n", program, o.target_error,
                         c.stage.c_str(), c.method.c_str(), c.params.c_str(), c.predicted_error,
                         c.met ? "" : " (nothing met the target: the most accurate)");
    for (const std::string& n : meta.extraction_notes) std::fprintf(stderr, "%s: light extraction: %s\n", program, n.c_str());
    for (const std::string& w : meta.warnings) std::fprintf(stderr, "%s: warning: %s\n", program, w.c_str());
    for (const std::string& n : meta.format_notes) std::fprintf(stderr, "%s: %s\n", program, n.c_str());
    std::vector<std::string> notes;
    Status staged = baked->stage(outputs, o.out_dir, callbacks.stop, &notes);
    for (const std::string& n : notes) std::fprintf(stderr, "%s: %s\n", program, n.c_str());
    check_interrupt();
    if (!staged) throw std::runtime_error(staged.error().message);
    if (Status s = commit_outputs(outputs); !s) throw std::runtime_error(s.error().message);

    double gpu_ms = 0;
    for (const PassTiming& t : meta.timings) {
        std::fprintf(stderr, "%s:   %-40s %9.2f ms GPU\n", program, t.name.c_str(), t.time_ms);
        gpu_ms += t.time_ms;
    }
    std::fprintf(stderr, "%s: wrote %s (%.0f ms GPU, %.0f ms wall)\n", program, o.out_dir.c_str(), gpu_ms,
                 meta.wall_time_ms);
    // Every file is written and committed: without validation the process ends here rather
    // than tear the device down (lavapipe's threads and JIT code, LLVM's exit handlers:
    // ~7 ms of a bake of 0.5 s), as compilers end; with it the teardown stays, for the layer
    // to check.
    if (!context.validation_enabled()) {
        std::fflush(nullptr);
        std::_Exit(0);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return facet::run_interruptible(program, [&] { return parse_bake_options(argc, argv); }, bake);
}
