#include "facet_render_options.h"

#include <filesystem>
#include <stdexcept>

#include "cli.h"
#include <facet/ibl/ibl_bake.h>
#include <facet/render/views.h>
#include "render_options.h"
#include <facet/scene/builtin_scenes.h>
#include <facet/scene/gltf_loader.h>
#include "shader_cache.h"

namespace facet {

namespace {

namespace fs = std::filesystem;

constexpr const char* program = "facet-render";

std::string extension_list() {
    std::string out;
    for (const std::string& name : gltf_supported_extensions()) out += (out.empty() ? "" : ", ") + name;
    return out;
}

cli::Parser make_parser() {
    cli::Parser p(program, "--out FILE.png|FILE.exr [--model PATH|builtin:NAME] [--env PATH|builtin:NAME|none] [options]",
                  "Renders a glTF model (.gltf, .glb) or a built-in scene (" + builtin_scene_names() +
                      ")\nunder an environment (.hdr, .exr; " + builtin_environment_names() +
                      "; none) with the forward PBR pass:\nglTF 2.0's BRDF (or the thesis' Cook-Torrance, --brdf), "
                      "image-based lighting baked on the\nfly (or from the bake cache), 4x MSAA. A .png is tone-mapped and "
                      "gamma-encoded; a .exr is\nlinear radiance with the exposure applied. NAME.json beside it records the "
                      "camera,\ninputs and their hashes so the image can be reproduced.\nglTF extensions read: " +
                      extension_list() +
                      ";\nanother in extensionsRequired is an error naming it, one only in extensionsUsed a warning.");
    p.option("--out", "FILE", "output image, .png or .exr (required)")
        .option("--aov", "LIST", "also write NAME.<view>.exr for each view: all or " + view_names());
    add_render_options(p);
    p.flag("--reference", "ground truth instead of the split sum: Monte Carlo over the whole environment\n"
                          "                          (BRDF + environment sampling, MIS) until the noise target")
        .option("--reference-noise", "X", "relative standard error to reach (default 0.01)")
        .option("--reference-samples", "N", "most samples per pixel (default 4096)")
        .option("--device", "NAME|INDEX", "Vulkan device (default: FACET_DEVICE, a GPU, else lavapipe)")
        .flag("--validation", "enable the Khronos validation layer");
    add_shader_cache_option(p);
    return p;
}

}  // namespace

std::optional<RenderOptions> parse_render_program_options(int argc, char** argv) {
    cli::Parser parser = make_parser();
    cli::Parsed a = parser.parse(argc, argv);
    if (parser.answered_help_or_version(a, FACET_VERSION)) return std::nullopt;
    if (!a.positional.empty()) throw std::invalid_argument("unexpected argument '" + a.positional[0] + "'");
    if (!a.has("--out")) throw std::invalid_argument("--out FILE.png|FILE.exr is required");
    RenderOptions o;
    RenderJob& j = o.job;
    o.out = a.get("--out");
    const std::string ext = fs::path(o.out).extension().string();
    if (ext != ".png" && ext != ".exr")
        throw std::invalid_argument("--out " + o.out + ": the name must end in .png or .exr");
    if (a.has("--aov")) {
        std::string error;
        auto views = parse_view_list(a.get("--aov"), &error);
        if (!views) throw std::invalid_argument("--aov: " + error);
        j.frame.views = *views;
    }
    parse_render_options(a, j);
    o.reference = a.has("--reference");
    if (a.has("--reference-noise")) o.reference_settings.noise_target = number_option(a, "--reference-noise", 1e-4f, 1.0f);
    if (a.has("--reference-samples"))
        o.reference_settings.max_samples =
            uint32_t(cli::parse_int(a.get("--reference-samples"), "--reference-samples", 1, 1 << 20));
    o.device = a.get("--device");
    o.validation = a.has("--validation");
    o.job.shader_cache_dir = shader_cache_dir(a);
    o.job.shader_dir = shader_dir_from_environment();
    return o;
}

}  // namespace facet
