#include "render_options.h"
#include "light_spec.h"
#include "shader_cache.h"

#include <cstdlib>

#include <facet/cache/directory_cache.h>

#include <cmath>
#include <cstdio>

#include <facet/io/environment_image.h>
#include <facet/scene/builtin_scenes.h>
#include <facet/scene/gltf_loader.h>
#include <facet/scene/material_presets.h>

namespace facet {

uint32_t samples_option(const cli::Parsed& a, uint32_t fallback) {
    if (!a.has("--samples")) return fallback;
    const int n = cli::parse_int(a.get("--samples"), "--samples", 1, 8);
    if (n != 1 && n != 2 && n != 4 && n != 8) throw std::invalid_argument("--samples must be 1, 2, 4 or 8");
    return uint32_t(n);
}

ShadingMethod shading_option(const cli::Parsed& a, ShadingMethod fallback) {
    if (!a.has("--shading")) return fallback;
    const auto method = parse_shading_method(a.get("--shading"));
    if (!method)
        throw std::invalid_argument("--shading: expected one of " + std::string(shading_method_names()) + ", got '" +
                                    a.get("--shading") + "'");
    return *method;
}

float number_option(const cli::Parsed& a, const char* name, float min, float max) {
    const double v = cli::parse_double(a.get(name), name);
    if (v < min || v > max)
        throw std::invalid_argument(std::string(name) + ": " + a.get(name) + " is outside " + std::to_string(min) +
                                    ".." + std::to_string(max));
    return float(v);
}

void add_render_options(cli::Parser& p) {
    p.option("--model", "PATH|builtin:NAME", "model to render (default builtin:spheres)")
        .option("--scene", "N", "the glTF file's scene N (default: the file's default scene, else scene 0)")
        .option("--env", "PATH|builtin:NAME|none", "environment for image-based lighting (default builtin:sky)")
        .option("--width", "W", "image width (default 1280)")
        .option("--height", "H", "image height (default 720)")
        .option("--camera", "orbit:THETA,PHI,RADIUS|gltf",
                "orbit the target (degrees, metres) or use the file's first camera (default: frame the bounds)")
        .option("--target", "X,Y,Z", "point the camera looks at (default: centre of the bounds)")
        .option("--fov", "DEG", "vertical field of view (default 45)")
        .option("--exposure", "E", "exposure multiplier (default 1)")
        .option("--tonemap", "OP", "reinhard (default), exposure, aces, neutral, none")
        .option("--gamma", "G", "encode with x^(1/G) instead of the sRGB curve")
        .option("--preset", "NAME", "override every material: " + material_preset_names())
        .repeatable("--light", "SPEC",
                    "add a light (repeatable): 'directional dir=X,Y,Z [color=R,G,B] [intensity=LUX]',\n"
                    "                          'point pos=X,Y,Z [intensity=CD] [range=M]', 'spot pos=... dir=...\n"
                    "                          [inner=DEG] [outer=DEG]'")
        .flag("--no-skybox", "black background instead of the environment")
        .option("--samples", "N", "MSAA samples: 1, 2, 4 (default) or 8")
        .option("--brdf", "gltf|thesis",
                "BRDF model: glTF 2.0's (default) or the thesis' Cook-Torrance (Schlick-GGX,\n"
                "                          kd = (1 - F)(1 - metalness)); the bake's LUT must be for the same one")
        .option("--shading", "METHOD",
                "environment lighting: auto (default: chosen per environment, see NAME.json), split-sum,\n"
                "                          dominant, lights, lights+dominant")
        .option("--target-error", "E",
                "the automatic shading's bound on every group's predicted error, a fraction\n"
                "                          (default 0.03 = 3%; NAME.json records the choice and its prediction)")
        .flag("--extract-lights", "take suns and lamps out of the environment and shade them as disk lights\n"
                                  "                          with the full BRDF (the rest goes through the split sum)")
        .flag("--multiscatter", "energy compensation for multiple scattering (Kulla-Conty; needs --env)")
        .option("--specular-dir", "mirror|dominant",
                "IBL specular lookup along R (default) or three lookups fitted to the true lobe (render/specular_lobes.h)")
        .option("--ibl-intensity", "S", "scale of the image-based lighting (default 1)")
        .option("--env-width", "N", "width of a built-in environment (default 1024)")
        .option("--max-env-width", "N", "downsample wider environment files to N x N/2 while reading them (default " +
                                            std::to_string(kDefaultMaxEnvironmentWidth) + ")")
        .option("--max-texture-size", "N", "downsample larger model textures to fit N x N while decoding them (default " +
                                               std::to_string(GltfLimits{}.max_texture_size) + ")")
        .option("--ibl-size", "N", "cube face size of the bake (default: environment height / 2)")
        .option("--ibl-samples", "N", "GGX samples per texel for smooth specular levels (default 1024)")
        .flag("--sanitize", "replace NaN, Inf and negative environment texels with 0 instead of failing")
        .option("--ibl", "DIR", "render with the bake facet-bake saved in DIR instead of baking")
        .option("--bake-cache", "DIR", "keep bakes in DIR, keyed by environment and settings, so the same\n"
                                       "                          environment is baked once (default $XDG_CACHE_HOME/facet/bakes,\n"
                                       "                          else ~/.cache/facet/bakes; at most 4 GiB, least recently used first)")
        .flag("--no-bake-cache", "bake every run; keep nothing");
}

void parse_render_options(const cli::Parsed& a, RenderJob& j) {
    j.model = a.get("--model", j.model);
    if (a.has("--scene")) j.model_scene = cli::parse_int(a.get("--scene"), "--scene", 0, 1 << 30);
    j.env = a.get("--env", j.env);
    if (a.has("--width")) j.frame.width = uint32_t(cli::parse_int(a.get("--width"), "--width", 1, 16384));
    if (a.has("--height")) j.frame.height = uint32_t(cli::parse_int(a.get("--height"), "--height", 1, 16384));
    if (a.has("--camera")) {
        const std::string c = a.get("--camera");
        std::array<float, 3> orbit{};
        char extra;
        if (c == "gltf") j.gltf_camera = true;
        else if (std::sscanf(c.c_str(), "orbit:%f,%f,%f%c", &orbit[0], &orbit[1], &orbit[2], &extra) == 3 &&
                 std::isfinite(orbit[0]) && std::isfinite(orbit[1]) && orbit[2] > 0 && std::isfinite(orbit[2]))
            j.orbit = orbit;
        else
            throw std::invalid_argument("--camera: expected orbit:THETA,PHI,RADIUS (radius > 0) or gltf, got '" + c + "'");
    }
    if (a.has("--target")) {
        glm::vec3 t;
        char extra;
        if (std::sscanf(a.get("--target").c_str(), "%f,%f,%f%c", &t.x, &t.y, &t.z, &extra) != 3 ||
            !std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z))
            throw std::invalid_argument("--target: expected X,Y,Z (finite), got '" + a.get("--target") + "'");
        j.target = t;
    }
    if (a.has("--fov")) j.fov_deg = number_option(a, "--fov", 1.0f, 170.0f);
    if (a.has("--exposure")) j.frame.display.exposure = number_option(a, "--exposure", 1e-6f, 1e6f);
    if (a.has("--tonemap")) {
        auto t = parse_tonemap(a.get("--tonemap"));
        if (!t) throw std::invalid_argument("--tonemap: unknown operator '" + a.get("--tonemap") +
                                            "' (reinhard, exposure, aces, neutral, none)");
        j.frame.display.tonemap = *t;
    }
    if (a.has("--gamma")) j.frame.display.gamma = number_option(a, "--gamma", 0.1f, 10.0f);
    if (a.has("--preset")) {
        if (!find_material_preset(a.get("--preset")))
            throw std::invalid_argument("--preset: unknown preset '" + a.get("--preset") + "' (" +
                                        material_preset_names() + ")");
        j.preset = a.get("--preset");
    }
    for (const std::string& spec : a.all("--light")) {
        auto light = parse_light(spec);
        if (!light) throw std::invalid_argument(light.error().message);
        j.extra_lights.push_back(*light);
    }
    j.frame.skybox = !a.has("--no-skybox");
    j.frame.samples = samples_option(a, j.frame.samples);
    j.frame.brdf = cli::brdf_option(a, j.frame.brdf);
    j.frame.multiscatter = a.has("--multiscatter");
    j.extract_lights = a.has("--extract-lights");
    if (a.has("--specular-dir")) {
        const std::string d = a.get("--specular-dir");
        if (d != "mirror" && d != "dominant")
            throw std::invalid_argument("--specular-dir: expected mirror or dominant, got '" + d + "'");
        j.frame.dominant_direction = d == "dominant";
        // Alone, --specular-dir names a method (mirror: the plain split sum).
        if (!j.extract_lights) j.shading = d == "dominant" ? ShadingMethod::dominant : ShadingMethod::split_sum;
    }
    if (a.has("--shading")) {
        if (a.has("--extract-lights") || a.has("--specular-dir"))
            throw std::invalid_argument("--shading names the whole method: leave out --extract-lights and --specular-dir");
        j.shading = shading_option(a, j.shading);
    }
    if (a.has("--target-error")) {
        const double e = cli::parse_double(a.get("--target-error"), "--target-error");
        if (!(e > 0 && e < 1))
            throw std::invalid_argument("--target-error: " + a.get("--target-error") +
                                        " is outside (0, 1): a fraction of the exact value (0.03 = 3%)");
        j.target_error = e;
    }
    if (a.has("--ibl-intensity")) j.ibl_intensity = number_option(a, "--ibl-intensity", 0.0f, 1e6f);
    if (a.has("--max-env-width"))
        j.max_env_width = uint32_t(cli::parse_int(a.get("--max-env-width"), "--max-env-width", 1, 16384));
    if (a.has("--env-width")) {
        j.env_width = uint32_t(cli::parse_int(a.get("--env-width"), "--env-width", 2, 16384));
        if (j.env_width % 2) throw std::invalid_argument("--env-width must be even");
        if (j.env_width > j.max_env_width)
            throw std::invalid_argument("--env-width " + std::to_string(j.env_width) + " is above --max-env-width " +
                                        std::to_string(j.max_env_width) + " (raise both for a wider built-in environment)");
    } else {
        j.env_width = std::min(j.env_width, std::max(2u, j.max_env_width & ~1u));
    }
    if (a.has("--max-texture-size"))
        j.model_limits.max_texture_size =
            uint32_t(cli::parse_int(a.get("--max-texture-size"), "--max-texture-size", 1, 16384));
    if (a.has("--ibl-size")) j.ibl.cube_size = uint32_t(cli::parse_int(a.get("--ibl-size"), "--ibl-size", 1, 8192));
    if (a.has("--ibl-samples"))
        j.ibl.specular.sample_count = uint32_t(cli::parse_int(a.get("--ibl-samples"), "--ibl-samples", 1, 1 << 20));
    j.sanitize = a.has("--sanitize");
    if (a.has("--ibl")) {
        if (a.get("--ibl").empty()) throw std::invalid_argument("--ibl needs a directory");
        j.ibl_dir = a.get("--ibl");
        // The bake in DIR fixes the environment and everything baked from it: an option
        // that would choose them again would be silently ignored, so it is an error.
        for (const char* baking : {"--env", "--env-width", "--max-env-width", "--sanitize", "--ibl-size", "--ibl-samples",
                                   "--extract-lights", "--bake-cache"})
            if (a.has(baking))
                throw std::invalid_argument(std::string(baking) + " and --ibl exclude each other: the environment is " +
                                            "the one baked in " + j.ibl_dir + " (its bake.json names it)");
    }
    j.bake_cache_dir = cache_dir_option(a, "--bake-cache", "--no-bake-cache", user_cache_dir("bakes"));
}

}  // namespace facet
