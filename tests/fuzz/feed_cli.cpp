#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "facet_bake_options.h"
#include "facet_bench_options.h"
#include "facet_render_options.h"
#include "facet_viewer_options.h"
#include "feed.h"
#include "light_spec.h"
#include <facet/render/views.h>

namespace facet::fuzz {

namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::vector<std::string> split_lines(Bytes input) {
    std::vector<std::string> lines(1);
    for (uint8_t byte : input) {
        if (byte == '\n') lines.emplace_back();
        else lines.back() += char(byte);
    }
    return lines;
}

// A light the renderer can shade: finite numbers, a unit direction where it is used.
void check_light(const Light& light) {
    FACET_FUZZ_EXPECT(finite(light.color) && finite(light.position) && finite(light.direction),
                      "a light has a non-finite colour, position or direction");
    FACET_FUZZ_EXPECT(std::isfinite(light.intensity) && light.intensity >= 0 && std::isfinite(light.range) &&
                          light.range >= 0,
                      "a light has a bad intensity or range");
    if (light.type != LightType::point)
        FACET_FUZZ_EXPECT(std::abs(glm::length(light.direction) - 1.0f) < 1e-3f, "a light direction is not unit length");
    if (light.type == LightType::spot)
        FACET_FUZZ_EXPECT(light.inner_cone >= 0 && light.inner_cone < light.outer_cone &&
                              light.outer_cone <= 1.5707964f,
                          "spot cone angles out of order");
}

void check_job(const RenderJob& job) {
    const FrameSettings& f = job.frame;
    FACET_FUZZ_EXPECT(f.width >= 1 && f.height >= 1 && f.width <= 16384 && f.height <= 16384, "bad image size");
    FACET_FUZZ_EXPECT(f.samples == 1 || f.samples == 2 || f.samples == 4 || f.samples == 8, "bad MSAA samples");
    FACET_FUZZ_EXPECT(std::isfinite(f.display.exposure) && f.display.exposure > 0, "bad exposure");
    FACET_FUZZ_EXPECT(f.display.gamma == 0 || (f.display.gamma >= 0.1f && f.display.gamma <= 10.0f), "bad gamma");
    FACET_FUZZ_EXPECT(job.fov_deg >= 1.0f && job.fov_deg <= 170.0f, "bad field of view");
    FACET_FUZZ_EXPECT(std::isfinite(job.ibl_intensity) && job.ibl_intensity >= 0, "bad IBL intensity");
    FACET_FUZZ_EXPECT(job.env_width >= 2 && job.env_width % 2 == 0, "bad built-in environment width");
    if (job.orbit)
        FACET_FUZZ_EXPECT(std::isfinite((*job.orbit)[0]) && std::isfinite((*job.orbit)[1]) &&
                              std::isfinite((*job.orbit)[2]) && (*job.orbit)[2] > 0,
                          "bad orbit camera");
    if (job.target) FACET_FUZZ_EXPECT(finite(*job.target), "the camera target is not finite");
    for (const Light& light : job.extra_lights) check_light(light);
}

// The viewer runs its script only after the window is up: each command must already be
// valid, with the values the viewer then reads (facet_viewer.cpp) in range.
void check_script_command(const std::string& command) {
    FACET_FUZZ_EXPECT(!command.empty(), "an empty script command");
    const size_t space = command.find(' ');
    const std::string verb = command.substr(0, space), arg = space == std::string::npos ? "" : command.substr(space + 1);
    if (verb == "exposure") {
        const float exposure = float(std::stod(arg));
        FACET_FUZZ_EXPECT(std::isfinite(exposure) && exposure > 0, "script exposure out of range: " + arg);
    } else if (verb == "material") {
        float v[6] = {1, 1, 1, 0, 0.5f, 1};
        std::sscanf(arg.c_str(), "%f,%f,%f,%f,%f,%f", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]);
        for (float value : v)
            FACET_FUZZ_EXPECT(std::isfinite(value) && value >= 0 && value <= 1, "script material out of range: " + arg);
    }
}

void check_bake(const BakeOptions& o) {
    FACET_FUZZ_EXPECT(o.sky_width >= 2 && o.sky_width % 2 == 0, "bad built-in environment width");
    FACET_FUZZ_EXPECT(std::isfinite(o.exposure) && o.exposure > 0, "bad exposure");
    FACET_FUZZ_EXPECT(o.target_error == 0 || (o.target_error > 0 && o.target_error < 10), "bad target error");
    FACET_FUZZ_EXPECT(o.roughness_min >= 0 && o.roughness_min <= o.roughness_max && o.roughness_max <= 1,
                      "bad roughness range");
    FACET_FUZZ_EXPECT(o.specular.levels >= 1 && o.specular.sample_count >= 1 && o.irradiance.size >= 1 &&
                          o.lut.size >= 1 && o.lut.sample_count >= 1,
                      "a zero size or count");
}

// Whether the parser accepted the command line (usage errors throw).
bool parse(const std::string& parser, std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    const int argc = int(args.size());
    if (parser == "facet-bake") {
        if (auto o = parse_bake_options(argc, argv.data())) check_bake(*o);
        return true;
    } else if (parser == "facet-render") {
        if (auto o = parse_render_program_options(argc, argv.data())) check_job(o->job);
        return true;
    } else if (parser == "facet-viewer") {
        if (auto o = parse_viewer_options(argc, argv.data())) {
            check_job(o->job);
            for (const std::string& command : o->script) check_script_command(command);
        }
        return true;
    } else if (parser == "facet-bench") {
        if (argc > 1 && std::string(argv[1]) == "accuracy") {  // facet_bench.cpp's dispatch
            auto accuracy = parse_accuracy_options(argc, argv.data());
            if (!accuracy) return true;
            check_job(accuracy->job);
            FACET_FUZZ_EXPECT(!accuracy->envs.empty() && !accuracy->truth_models.empty(), "bad accuracy options");
            return true;
        }
        auto o = parse_bench_options(argc, argv.data());
        if (!o) return true;
        if (o->benchmark == "render") check_job(parse_render_bench_options(o->args).job);
        if (o->benchmark == "sweep") {
            SweepOptions sweep = parse_sweep_options(o->args);
            FACET_FUZZ_EXPECT(!sweep.envs.empty() && sweep.env_width >= 8, "bad sweep options");
        }
        return true;
    } else if (parser == "light") {
        auto light = parse_light(args.size() > 1 ? args[1] : "");
        if (light) check_light(*light);
        else FACET_FUZZ_EXPECT(light.error().message.rfind("--light", 0) == 0, "the error does not name --light");
        return light.ok();
    } else if (parser == "views") {
        std::string error;
        auto views = parse_view_list(args.size() > 1 ? args[1] : "", &error);
        FACET_FUZZ_EXPECT(views.has_value() != !error.empty(), "a view list both failed and not");
        return views.has_value();
    }
    return false;
}

}  // namespace

bool feed_cli(Bytes input) {
    std::vector<std::string> args = split_lines(input);
    const std::string parser = args[0];
    try {
        return parse(parser, args);
    } catch (const std::invalid_argument& e) {
        // Usage errors: one message naming the option or argument (exit status 2).
        FACET_FUZZ_EXPECT(e.what()[0] != '\0', "an empty usage error");
        return false;
    }
}

}  // namespace facet::fuzz
