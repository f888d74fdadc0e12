// facet-render: a model under an environment and lights, rendered offscreen with the
// forward PBR pass (split-sum image-based lighting baked in the same run) to a PNG
// (tone-mapped, sRGB) or an EXR (linear, exposure applied), with NAME.json beside it
// and, on request, one EXR per view (normal, position, D, F, G, diffuse, ...). The files
// appear together or not at all; SIGINT and SIGTERM stop it at the next safe point with
// nothing written (apps/interrupt.h).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli.h"
#include "interrupt.h"
#include "facet_render_options.h"
#include <facet/core/result.h>
#include <facet/gpu/context.h>
#include <facet/ibl/baked_environment.h>
#include <facet/io/atomic_file.h>
#include <facet/io/image_io.h>
#include <facet/io/json_writer.h>
#include <facet/io/output_set.h>
#include <facet/render/render_job.h>
#include "render_options.h"
#include <facet/scene/builtin_scenes.h>
#include <facet/scene/material_presets.h>
#include "shader_cache.h"

namespace {

using namespace facet;
namespace fs = std::filesystem;

constexpr const char* program = "facet-render";

using Options = RenderOptions;

void write_vec3(JsonWriter& j, const char* key, glm::vec3 v) {
    j.begin_array(key).value({}, double(v.x)).value({}, double(v.y)).value({}, double(v.z)).end_array();
}

std::string describe(const Options& o, const RenderSession& session, const RenderedImages& images,
                     const std::string& context_device, const std::vector<std::string>& view_files,
                     const ReferenceStats& stats) {
    const CameraView& c = session.camera();
    const FrameSettings& f = session.frame();
    JsonWriter j;
    j.begin_object();
    j.value("program", program).value("version", FACET_VERSION).value("device", context_device);
    j.value("image", fs::path(o.out).filename().string()).value("width", images.width).value("height", images.height);
    j.value("encoding", fs::path(o.out).extension() == ".exr" ? "linear radiance x exposure" : "tone-mapped, gamma-encoded");
    j.begin_object("camera");
    write_vec3(j, "position", c.position);
    write_vec3(j, "target", c.target);
    write_vec3(j, "up", c.up);
    j.value("yfov_deg", double(glm::degrees(c.yfov))).value("znear", double(c.znear));
    j.value("projection", "perspective, infinite far plane, reversed Z");
    j.end_object();
    j.begin_object("model").value("source", session.scene().source).value("content_hash", session.scene().content_hash);
    if (o.job.preset) j.value("preset", *o.job.preset);
    j.end_object();
    j.begin_object("environment");
    const BakedEnvironment* baked = session.baked();
    if (const EnvironmentSource* env = session.environment())
        j.value("source", env->name).value("content_hash", env->content_hash).value("width", env->width)
            .value("height", env->height).value("source_width", env->source_width)
            .value("source_height", env->source_height).value("ibl_intensity", double(o.job.ibl_intensity));
    else if (baked)  // --ibl DIR: the bake's input
        j.value("bake", o.job.ibl_dir).value("source", baked->metadata().input)
            .value("content_hash", baked->metadata().content_hash).value("width", baked->metadata().width)
            .value("height", baked->metadata().height).value("source_width", baked->metadata().source_width)
            .value("source_height", baked->metadata().source_height).value("bake_key", baked->metadata().bake_key)
            .value("ibl_intensity", double(o.job.ibl_intensity));
    else
        j.value("source", "none");
    j.end_object();
    j.value("exposure", double(f.display.exposure)).value("tonemap", tonemap_name(f.display.tonemap));
    j.value("gamma", f.display.gamma > 0 ? std::to_string(f.display.gamma) : std::string("sRGB"));
    j.value("msaa_samples", f.samples).value("skybox", f.skybox && baked != nullptr);
    j.value("brdf", brdf_model_name(f.brdf));
    j.begin_array("environment_lights");
    for (const DiskLight& d : f.environment_lights) {
        j.begin_object();
        write_vec3(j, "direction", d.direction);
        write_vec3(j, "radiance", d.radiance);
        j.value("angular_radius_deg", double(glm::degrees(d.angular_radius))).value("power_fraction", d.power_fraction);
        j.end_object();
    }
    j.end_array();
    j.value("multiscatter", f.multiscatter).value("specular_lookup", f.dominant_direction ? "dominant" : "mirror");
    const ShadingChoice& shading = session.shading();
    j.begin_object("shading")
        .value("requested", shading_method_name(shading.requested))
        .value("method", shading_method_name(shading.method))
        .value("reason", shading.reason)
        .value("target_error", shading.target_error);
    // Fractions of the exact value (issue 13's measure on a probe), worst group first; absent
    // where nothing could be predicted (no environment, a saved bake).
    if (shading.predicted_error) {
        j.value("predicted_error", *shading.predicted_error).value("predicted_worst_group", shading.predicted_worst_group);
        j.begin_array("predicted_groups");
        for (const GroupErrorPrediction& g : shading.predicted_groups)
            j.begin_object().value("group", g.group).value("error", g.error).end_object();
        j.end_array();
    }
    // The groups whose materials read along R although the method bends the lookup.
    j.begin_array("unbent_groups");
    for (const std::string& g : shading.unbent_groups) j.value({}, g);
    j.end_array();
    // The groups below roughness 0.6 whose materials read two fitted lookups instead of three.
    j.begin_array("two_lookup_groups");
    for (const std::string& g : shading.two_lookup_groups) j.value({}, g);
    j.end_array();
    j.end_object();
    j.value("lights", uint32_t(f.lights.size()));
    j.begin_array("warnings");  // what the model's loader met but does not draw (Scene::warnings)
    for (const std::string& warning : session.scene().warnings) j.value({}, warning);
    j.end_array();
    if (o.reference)
        j.begin_object("reference").value("samples_per_pixel", stats.samples).value("noise", stats.noise)
            .value("noise_target", o.reference_settings.noise_target).value("converged", stats.converged).end_object();
    else
        j.value("renderer", "forward, split sum");
    j.begin_array("views");
    for (const std::string& name : view_files) j.value({}, name);
    j.end_array();
    j.begin_object("gpu_time_ms");
    for (const PassTiming& t : session.bake_timings()) j.value(t.name, t.time_ms);
    for (const PassTiming& t : images.timings) j.value(t.name, t.time_ms);
    j.end_object();
    j.end_object();
    return j.str();
}

std::string stem_path(const std::string& out) {
    fs::path p(out);
    return (p.parent_path() / p.stem()).string();
}

int render(const Options& o) {
    const std::unique_ptr<Context> vulkan = start_vulkan(o.device, o.validation);
    Context& context = *vulkan;
    const fs::path parent = fs::path(o.out).parent_path();
    if (!parent.empty() && !fs::is_directory(parent))
        throw std::runtime_error(o.out + ": the directory " + parent.string() + " does not exist");
    auto log = [](const std::string& line) { std::fprintf(stderr, "%s: %s\n", program, line.c_str()); };
    // Every progress line (one per bake pass) is a safe point.
    auto session = RenderSession::create(context, o.job, [&](const std::string& line) {
        log(line);
        check_interrupt();
    });
    if (!session) throw std::runtime_error(session.error().message);
    for (const std::string& warning : (*session)->scene().warnings) log("warning: " + warning);
    log("rendering " + std::to_string(o.job.frame.width) + "x" + std::to_string(o.job.frame.height) + " on " +
        context.device_name());
    ReferenceStats stats;
    auto images = o.reference ? (*session)->render_reference(o.reference_settings, [&](const ReferenceStats& st) {
        std::fprintf(stderr, "%s: reference: %u samples per pixel, noise %.4f (target %.4f)\n", program, st.samples,
                     st.noise, o.reference_settings.noise_target);
        pause_for_test("reference");
        check_interrupt();
    }, &stats) : (*session)->render_frame();
    if (!images) throw std::runtime_error(images.error().message);
    if (o.reference && !stats.converged)
        log("warning: the reference stopped at " + std::to_string(stats.samples) + " samples per pixel with noise " +
            std::to_string(stats.noise) + ", above the target");

    const std::string stem = stem_path(o.out);
    const float exposure = o.job.frame.display.exposure;
    std::vector<std::string> view_files;
    for (auto& [view, texels] : images->views) view_files.push_back(stem + "." + view_name(view) + ".exr");
    for (const std::string& f : view_files)
        if (fs::exists(f)) log("replacing " + f);
    if (fs::exists(o.out)) log("replacing " + o.out);
    // Every file to its temporary, NAME.json (the marker) last; then all move into place.
    OutputSet outputs;
    auto stage = [&](const std::string& path) {
        check_interrupt();
        return outputs.stage(path);
    };
    if (fs::path(o.out).extension() == ".exr") {
        std::vector<float> exposed = images->hdr;
        for (size_t i = 0; i < exposed.size(); ++i)
            if (i % 4 != 3) exposed[i] *= exposure;
        if (Status s = write_hdr_image(stage(o.out), images->width, images->height, exposed); !s)
            throw std::runtime_error(s.error().message);
    } else if (Status s = write_ldr_image(stage(o.out), images->width, images->height, images->ldr); !s) {
        throw std::runtime_error(s.error().message);
    }
    for (size_t v = 0; v < images->views.size(); ++v)
        if (Status s = write_hdr_image(stage(view_files[v]), images->width, images->height, images->views[v].second);
            !s)
            throw std::runtime_error(s.error().message);
    std::vector<std::string> view_names_written;
    for (const std::string& f : view_files) view_names_written.push_back(fs::path(f).filename().string());
    if (Status s = write_text_file(stage(stem + ".json"),
                                   describe(o, **session, *images, context.device_name(), view_names_written, stats));
        !s)
        throw std::runtime_error(s.error().message);
    if (Status s = commit_outputs(outputs); !s) throw std::runtime_error(s.error().message);
    double gpu_ms = 0;
    for (const PassTiming& t : images->timings) {
        log("  " + t.name + ": " + std::to_string(t.time_ms) + " ms GPU");
        gpu_ms += t.time_ms;
    }
    std::fprintf(stderr, "%s: wrote %s (frame %.1f ms GPU, %.0f ms wall)\n", program, o.out.c_str(), gpu_ms,
                 images->wall_ms);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return facet::run_interruptible(program, [&] { return parse_render_program_options(argc, argv); }, render);
}
