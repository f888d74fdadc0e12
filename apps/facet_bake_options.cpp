#include "facet_bake_options.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "cli.h"
#include "render_options.h"
#include "shader_cache.h"

namespace facet {

namespace {

constexpr const char* program = "facet-bake";

cli::Parser make_parser() {
    cli::Parser p(program, "ENV|builtin:NAME --out DIR [options]",
                  "Bakes image-based lighting for an equirectangular environment (.hdr, .exr, any\n"
                  "size) or a built-in one (builtin:sky: a sun ~4e4 times the sky; builtin:white:\n"
                  "radiance 1). Writes into DIR: specular.ktx2 (GGX prefiltered cube, one roughness\n"
                  "per level), irradiance.ktx2 (E/pi cube), brdf_lut.ktx2 (R = A, G = B, B = E_avg),\n"
                  "brdf_lut.png, environment.ktx2 (the skybox's cube), environment.exr/.hdr/.png and\n"
                  "bake.json. Outputs are RGBA16F unless --float32, or unless their values exceed\n"
                  "RGBA16F's range (then RGBA32F, said here and in bake.json). A bake whose bake.json\n"
                  "records the same input and settings is skipped (--force redoes it).");
    p.option("--out", "DIR", "output directory (created if missing)")
        .option("--irradiance", "METHOD", "convolve (default), riemann, sh9, blur, lowmip")
        .flag("--sh9-no-window", "sh9: keep the raw coefficients (may ring below 0 on a sun)")
        .option("--specular", "METHOD", "automatic (default: hybrid below roughness 0.5, convolve above),\n"
                                        "                          importance, filtered, convolve, mips, hybrid")
        .option("--samples", "N", "GGX samples per texel for importance/filtered levels (default 1024)")
        .option("--hybrid-samples", "N", "filtered samples of the clamped environment per hybrid texel (default 128)")
        .flag("--hybrid-full-size", "hybrid: sample the clamped environment at each level's own size (default:\n"
                                    "                          at half size where the lobe spans several of its texels)")
        .option("--size", "N", "cube face size (default: input height / 2)")
        .option("--levels", "N", "specular levels, roughness m/(N-1) (default 6)")
        .option("--irradiance-size", "N", "irradiance face size (default 32)")
        .option("--lut-size", "N", "BRDF LUT width and height (default 128)")
        .option("--lut-samples", "N", "GGX samples per LUT texel (default 2048)")
        .option("--brdf", "gltf|thesis", "BRDF model of the LUT: glTF 2.0's (default) or the thesis' (renders must match)")
        .option("--width", "N", "width of a built-in environment (default 1024, height N/2)")
        .option("--max-env-width", "N", "downsample wider environment files to N x N/2 while reading them\n"
                                         "                          (default " + std::to_string(kDefaultMaxEnvironmentWidth) +
                                             "; a built-in's --width may not exceed it)")
        .option("--exposure", "E", "exposure of environment.png, 1e-6..1e6 (default 1)")
        .flag("--sanitize", "replace NaN, Inf and negative texels of ENV with 0 instead of failing")
        .option("--target-error", "E", "accuracy budget: the cheapest methods whose measured relative RMS error\n"
                                        "                          against the brute-force truth is at most E (e.g. 0.02)")
        .option("--roughness", "A,B", "budget: the scene's roughness range; specular is judged on it (default 0,1)")
        .flag("--float32", "store every output as RGBA32F (default RGBA16F)")
        .flag("--extract-lights", "take suns and lamps out of the map as disk lights (recorded in bake.json)")
        .flag("--force", "bake even if DIR holds a bake of the same input and settings")
        .option("--device", "NAME|INDEX", "Vulkan device (default: FACET_DEVICE, a GPU, else lavapipe)")
        .flag("--validation", "enable the Khronos validation layer")
        .option("--graph-dot", "FILE", "also write the compiled render graph as Graphviz dot")
        .option("--lut-cache", "DIR", "keep the BRDF LUT in DIR for later bakes: it does not depend on the environment\n"
                                      "                          (default: $XDG_CACHE_HOME/facet/bakes, facet-render's bake cache)")
        .flag("--no-lut-cache", "compute the BRDF LUT in every bake");
    add_shader_cache_option(p);
    return p;
}

uint32_t positive(const cli::Parsed& a, const char* name, int max) {
    return static_cast<uint32_t>(cli::parse_int(a.get(name), name, 1, max));
}

}  // namespace

std::optional<BakeOptions> parse_bake_options(int argc, char** argv) {
    cli::Parser parser = make_parser();
    cli::Parsed a = parser.parse(argc, argv);
    if (parser.answered_help_or_version(a, FACET_VERSION)) return std::nullopt;
    if (a.positional.size() != 1)
        throw std::invalid_argument("expected exactly one environment (a file or builtin:NAME), got " +
                                    std::to_string(a.positional.size()));
    if (!a.has("--out")) throw std::invalid_argument("--out DIR is required");
    BakeOptions o;
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
    if (a.has("--hybrid-samples")) o.specular.hybrid_sample_count = positive(a, "--hybrid-samples", 4096);
    if (a.has("--hybrid-full-size")) o.specular.hybrid_half_size_residual = false;
    if (a.has("--size")) o.cube_size = positive(a, "--size", 8192);
    if (a.has("--levels")) o.specular.levels = positive(a, "--levels", 16);
    if (a.has("--irradiance-size")) o.irradiance.size = positive(a, "--irradiance-size", 1024);
    if (a.has("--lut-size")) o.lut.size = positive(a, "--lut-size", 4096);
    if (a.has("--lut-samples")) o.lut.sample_count = positive(a, "--lut-samples", 1 << 20);
    o.lut.brdf = cli::brdf_option(a, o.lut.brdf);
    if (a.has("--max-env-width")) o.max_env_width = positive(a, "--max-env-width", int(kMaxEnvironmentSide) / 4);
    if (a.has("--width")) o.sky_width = positive(a, "--width", 16384);
    else o.sky_width = std::min(o.sky_width, std::max(2u, o.max_env_width & ~1u));
    if (o.sky_width % 2) throw std::invalid_argument("--width must be even (the height is width / 2)");
    if (o.sky_width > o.max_env_width)
        throw std::invalid_argument("--width " + std::to_string(o.sky_width) + " is above --max-env-width " +
                                    std::to_string(o.max_env_width) + " (raise both for a wider built-in environment)");
    // The range facet-render's --exposure and the viewer's take (1e300 overflowed the float
    // here once, 1e-300 rounded to 0 in it).
    if (a.has("--exposure")) o.exposure = number_option(a, "--exposure", 1e-6f, 1e6f);
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
    o.float32 = a.has("--float32");
    o.extract_lights = a.has("--extract-lights");
    o.device = a.get("--device");
    o.validation = a.has("--validation");
    o.graph_dot = a.get("--graph-dot");
    o.shader_cache = shader_cache_dir(a);
    o.lut_cache = cache_dir_option(a, "--lut-cache", "--no-lut-cache", user_cache_dir("bakes"));
    return o;
}

}  // namespace facet
