#pragma once
// facet-bench's command line (the benchmark, then the options of bake, render and
// sweep), apart from the programs so that it can be tested and fuzzed without a GPU.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cli.h"
#include <facet/render/render_job.h>

namespace facet {

struct BenchOptions {
    std::string benchmark;  // bake, render or sweep
    int runs = 5;           // bake: bakes per environment
    std::string shader_cache;  // bake: passed on to facet-bake (apps/shader_cache.h); empty: none
    cli::Parsed args;       // every option, for the benchmark's own parse below
};

// Nothing when --help or --version was answered; throws std::invalid_argument naming
// the option for bad usage.
std::optional<BenchOptions> parse_bench_options(int argc, char** argv);

struct RenderBenchOptions {
    RenderJob job;
    int frames = 10;
};
// Throws std::invalid_argument naming the option.
RenderBenchOptions parse_render_bench_options(const cli::Parsed& args);

struct SweepOptions {
    std::vector<std::string> envs;  // default builtin:sky
    uint32_t env_width = 256;
    int runs = 3;
    std::string stages = "irradiance,specular,lut,image";
    std::string out_dir = "bench-out";
    // Stage "image" (apps/bench_sweep_image.h): frame size, BRDF models, the truth's pixel
    // budget and the reference mode's samples per pixel.
    uint32_t image_width = 320, image_height = 320;
    std::vector<BrdfModel> brdf_models{BrdfModel::gltf};
    uint32_t max_pixels = 4000;
    std::vector<uint32_t> reference_spp{1, 4, 16, 64};
    std::string shader_cache;  // empty: none (apps/shader_cache.h)
};
// Throws std::invalid_argument naming the option.
SweepOptions parse_sweep_options(const cli::Parsed& args);

// facet-bench accuracy: the final image of a scene (default builtin:spheres) under each
// environment against the double-precision truth of the frame's BRDF model, per
// roughness x metalness group (reference/final_image_accuracy.h). The render options are
// facet-render's (apps/render_options.h); --env takes a comma-separated list.
struct AccuracyOptions {
    RenderJob job;                  // job.env: the first environment (each is set in turn)
    std::vector<std::string> envs;  // default builtin:sky
    uint32_t env_width = 512;       // renderer and truth both use the environment at this width
    uint32_t max_pixels = 4000;     // truth budget per environment
    int runs = 3;                   // frames timed (median)
    std::string json;               // also write the tables here
    bool reference = false;         // measure the reference mode's image instead of the frame's
    std::vector<BrdfModel> truth_models;  // default: the frame's (job.frame.brdf)
    std::optional<ShadingMethod> compare; // also render with this method, against the same truth
};
// Nothing when --help or --version was answered; throws std::invalid_argument naming
// the option. argv[1] is "accuracy".
std::optional<AccuracyOptions> parse_accuracy_options(int argc, char** argv);

}  // namespace facet
