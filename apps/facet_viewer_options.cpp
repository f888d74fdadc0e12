#include "facet_viewer_options.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "cli.h"
#include "shader_cache.h"
#include <facet/render/tonemap.h>
#include <facet/render/views.h>
#include "render_options.h"
#include <facet/scene/material_presets.h>

namespace facet {

namespace {

constexpr const char* program = "facet-viewer";

// Validates one script command before anything starts; throws naming it.
void check_command(const std::string& command) {
    const std::string verb = command.substr(0, command.find(' '));
    const std::string arg = command.find(' ') == std::string::npos ? "" : command.substr(command.find(' ') + 1);
    auto bad = [&](const std::string& why) { throw std::invalid_argument("--script: '" + command + "': " + why); };
    if (command == "wait" || command == "wait bake") return;  // see --script's help
    if (verb == "frames") cli::parse_int(arg, "--script frames", 1, 1000000);
    else if (verb == "view") {
        if (!parse_view(arg)) bad("unknown view (final," + view_names() + ")");
    } else if (verb == "size") {
        unsigned w = 0, h = 0;
        char extra;
        if (std::sscanf(arg.c_str(), "%ux%u%c", &w, &h, &extra) != 2 || !w || !h || w > 8192 || h > 8192)
            bad("expected WxH");
    } else if (verb == "tonemap") {
        if (!parse_tonemap(arg)) bad("unknown operator");
    } else if (verb == "exposure") {
        // The same range as --exposure: a float the display transform can use.
        const double exposure = cli::parse_double(arg, "--script exposure");
        if (!(exposure >= 1e-6 && exposure <= 1e6)) bad("expected an exposure in 1e-6..1e6");
    } else if (verb == "skybox") {
        if (arg != "on" && arg != "off") bad("expected on or off");
    } else if (verb == "preset") {
        if (!find_material_preset(arg)) bad("unknown preset (" + material_preset_names() + ")");
    } else if (verb == "material") {
        float v[6];
        char textures[8] = "", extra;
        const int n = std::sscanf(arg.c_str(), "%f,%f,%f,%f,%f,%f,%7[a-z]%c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                                  textures, &extra);
        if (n < 5 || n > 7 || (n == 7 && std::string(textures) != "on" && std::string(textures) != "off"))
            bad("expected R,G,B,METALNESS,ROUGHNESS[,AO[,on|off]]");
        // The material panel's ranges (its sliders and colour picker); NaN fails too.
        for (int i = 0; i < std::min(n, 6); ++i)
            if (!(v[i] >= 0.0f && v[i] <= 1.0f)) bad("material values must be in 0..1");
    } else if (verb == "screenshot") {
        if (arg.size() < 5) bad("expected a .png or .exr file name");
    } else if (verb != "model" && verb != "env") {
        bad("unknown command");
    }
    if (arg.empty()) bad("needs a value");
}

}  // namespace

std::optional<ViewerOptions> parse_viewer_options(int argc, char** argv) {
    cli::Parser p(program, "[--model PATH|builtin:NAME] [--env PATH|builtin:NAME|none] [options]",
                  "Shows a glTF model or a built-in scene under an environment with the forward PBR pass.\n"
                  "Keys: WASD move, mouse (left button) look, Tab fly/orbit, R reset the camera, F12 screenshot,\n"
                  "Esc quit. --frames N renders N frames and exits (with --screenshot FILE: the last one).");
    add_render_options(p);
    add_shader_cache_option(p);
    p.option("--frames", "N", "render N frames, then exit (default: until the window closes)")
        .option("--screenshot", "FILE", "save the last frame as FILE (.png tone-mapped, .exr linear)")
        .option("--script", "CMDS", "run commands separated by ';', then exit: model M, env E, preset P,\n"
                                    "                          view V, size WxH, exposure E, tonemap OP, skybox on|off,\n"
                                    "                          material R,G,B,METALNESS,ROUGHNESS[,AO[,on|off textures]],\n"
                                    "                          frames N, screenshot FILE (of the scene asked for: it\n"
                                    "                          waits for a load), wait (frames go on until a model or\n"
                                    "                          environment asked for is in use), wait bake (until its\n"
                                    "                          bake has run a pass)")
        .option("--shader-dir", "DIR", "read shaders from DIR and rebuild the pipelines when a file there changes\n"
                                       "                          (hot reload; default: FACET_SHADER_DIR, else the built-in copies)")
        .option("--device", "NAME|INDEX", "Vulkan device (default: FACET_DEVICE, a GPU, else lavapipe)");
    cli::Parsed a = p.parse(argc, argv);
    if (p.answered_help_or_version(a, FACET_VERSION)) return std::nullopt;
    if (!a.positional.empty()) throw std::invalid_argument("unexpected argument '" + a.positional[0] + "'");
    ViewerOptions o;
    o.job.frame.width = 960;
    o.job.frame.height = 540;
    parse_render_options(a, o.job);
    if (a.has("--script")) {
        std::string item;
        for (char ch : a.get("--script") + ";") {
            if (ch != ';') {
                item += ch;
                continue;
            }
            const size_t first = item.find_first_not_of(' '), last = item.find_last_not_of(' ');
            if (first != std::string::npos) o.script.push_back(item.substr(first, last - first + 1));
            item.clear();
        }
        for (const std::string& command : o.script) check_command(command);
    }
    if (a.has("--frames"))
        o.script.push_back("frames " + std::to_string(cli::parse_int(a.get("--frames"), "--frames", 1, 1000000)));
    if (a.has("--screenshot")) {
        if (o.script.empty()) o.script.push_back("frames 1");
        o.script.push_back("screenshot " + a.get("--screenshot"));
    }
    o.device = a.get("--device");
    o.job.shader_cache_dir = shader_cache_dir(a);
    o.job.shader_dir = a.get("--shader-dir", std::getenv("FACET_SHADER_DIR") ? std::getenv("FACET_SHADER_DIR") : "");
    // The error_code overload: the throwing one throws filesystem_error (name too long,
    // no permission), which is no usage error and would escape run_program.
    std::error_code ec;
    if (!o.job.shader_dir.empty() && !std::filesystem::is_directory(o.job.shader_dir, ec))
        throw std::invalid_argument("--shader-dir: " + o.job.shader_dir + " is not a directory");
    return o;
}

}  // namespace facet
