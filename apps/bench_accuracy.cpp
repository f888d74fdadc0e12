#include "bench_accuracy.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <facet/gpu/context.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/ibl/ibl_measure.h>
#include <facet/io/atomic_file.h>
#include <facet/io/image_io.h>
#include <facet/io/json_writer.h>
#include <facet/reference/final_image_accuracy.h>
#include <facet/render/render_job.h>
#include "facet_bench_options.h"
#include "shader_cache.h"
#include "start_vulkan.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
constexpr const char* program = "facet-bench";

int fail(const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", program, message.c_str());
    return 1;
}

// The view's pixels out of a frame; empty if the renderer did not write it.
const std::vector<float>& view_of(const RenderedImages& frame, View view) {
    static const std::vector<float> none;
    for (const auto& [v, pixels] : frame.views)
        if (v == view) return pixels;
    return none;
}

struct Measured {
    std::string env;
    BrdfModel model = BrdfModel::gltf;
    uint32_t env_w = 0, env_h = 0;
    test::FinalImageAccuracy accuracy;
    double forward_ms = 0;
    ShadingChoice shading;  // the session's method and its predicted errors (for the frame's model)
    std::optional<test::FinalImageAccuracy> compared;  // --compare's frame against the same truth
    double compared_forward_ms = 0;
};

// A session's frames for one job: the last frame and the forward pass's median wall time.
struct Frames {
    std::unique_ptr<RenderSession> session;
    RenderedImages frame;
    double forward_ms = 0;
};

// Each job's session and frames, a frame of each job in turn per run, the order reversed every
// other run (ABBA): the machine's drift over the runs (a shared host's load) falls on every
// job alike, where all runs of one job before the other's swung a ratio by up to 40% here.
// What this cannot remove (measured, lavapipe): the session created second reads 5-15%
// slower than the first with the same method, so a ratio against --compare reads low by
// that much; docs/accuracy.md's cost figures are medians of separate processes.
Result<std::vector<Frames>> render_frames(Context& context, const std::vector<RenderJob>& jobs, int runs) {
    std::vector<Frames> frames;
    for (const RenderJob& job : jobs) {
        auto session = RenderSession::create(context, job, [](const std::string& line) {
            std::fprintf(stderr, "%s:   %s\n", program, line.c_str());
        });
        if (!session) return session.error();
        frames.push_back(Frames{std::move(*session), {}, 0});
    }
    std::vector<std::vector<double>> forward_ms(jobs.size());
    for (int r = 0; r < runs; ++r)
        for (size_t k = 0; k < frames.size(); ++k) {
            const size_t j = r % 2 ? frames.size() - 1 - k : k;
            auto images = frames[j].session->render_frame(true);
            if (!images) return images.error();
            double ms = 0;
            for (const PassTiming& t : images->pass_wall)
                if (t.name == "forward") ms += t.time_ms;
            forward_ms[j].push_back(ms);
            frames[j].frame = std::move(images).value();
        }
    for (size_t j = 0; j < frames.size(); ++j) frames[j].forward_ms = median(forward_ms[j]);
    return frames;
}

// The session's predicted error of a group ("roughness [0.2,0.4) metal"); negative: none.
double predicted_of(const ShadingChoice& c, const std::string& group) {
    for (const GroupErrorPrediction& g : c.predicted_groups)
        if (g.group == group) return g.error;
    return -1;
}

std::string json_of(const std::vector<Measured>& results, const AccuracyOptions& o, const std::string& device) {
    JsonWriter j;
    j.begin_object().value("program", "facet-bench accuracy").value("version", FACET_VERSION).value("device", device);
    j.value("model", o.job.model).value("frame_brdf", brdf_model_name(o.job.frame.brdf));
    j.value("width", o.job.frame.width).value("height", o.job.frame.height).value("max_pixels", o.max_pixels);
    j.value("error", "per group: |lum(render) - lum(truth)| / lum(truth), fractions");
    j.value("forward_ms", "wall time of the forward pass, its own submission, median of the runs");
    j.begin_array("environments");
    for (const Measured& m : results) {
        j.begin_object().value("environment", m.env).value("truth_brdf", brdf_model_name(m.model));
        j.value("env_width", m.env_w).value("env_height", m.env_h);
        j.value("forward_ms", m.forward_ms).value("truth_seconds", m.accuracy.truth_seconds);
        j.value("pixels", uint32_t(m.accuracy.pixels)).value("worst_mean_rel", m.accuracy.worst_mean_rel);
        j.value("shading", shading_method_name(m.shading.method)).value("shading_reason", m.shading.reason);
        j.value("target_error", m.shading.target_error);
        if (m.shading.predicted_error && m.model == o.job.frame.brdf)
            j.value("predicted_worst_mean_rel", *m.shading.predicted_error)
                .value("predicted_worst_group", m.shading.predicted_worst_group);
        j.value("worst_group", m.accuracy.worst >= 0 ? test::group_name(m.accuracy.groups[size_t(m.accuracy.worst)])
                                                     : std::string("none"));
        j.begin_array("groups");
        for (const test::GroupError& g : m.accuracy.groups) {
            j.begin_object().value("group", test::group_name(g)).value("roughness_min", g.roughness_min);
            j.value("roughness_max", g.roughness_max).value("metal", g.metal).value("pixels", uint32_t(g.pixels));
            j.value("mean_rel", g.mean_rel).value("max_rel", g.max_rel).value("mean_signed", g.mean_signed);
            const double predicted = predicted_of(m.shading, test::group_name(g));
            if (predicted >= 0 && m.model == o.job.frame.brdf) j.value("predicted_mean_rel", predicted);
            j.end_object();
        }
        j.end_array();
        if (m.compared) {
            j.begin_object("compared").value("shading", shading_method_name(*o.compare));
            j.value("forward_ms", m.compared_forward_ms).value("worst_mean_rel", m.compared->worst_mean_rel);
            j.begin_array("groups");
            for (const test::GroupError& g : m.compared->groups)
                j.begin_object().value("group", test::group_name(g)).value("mean_rel", g.mean_rel).end_object();
            j.end_array().end_object();
        }
        j.end_object();
    }
    j.end_array().end_object();
    return j.str();
}

// Box-filters a file environment by the largest power of two that keeps it at least
// `width` wide (the renderer then bakes, and the truth sums, exactly these texels).
void downsample_to(EnvironmentSource& env, uint32_t width) {
    uint32_t factor = 1;
    while (env.width / (factor * 2) >= width && env.width % (factor * 2) == 0 && env.height % (factor * 2) == 0)
        factor *= 2;
    if (factor == 1) return;
    const test::Equirect e = test::downsample(test::Equirect{env.width, env.height, env.image.rgba}, factor);
    env.image.rgba = e.rgba;
    env.width = env.image.width = e.w;
    env.height = env.image.height = e.h;
}

}  // namespace

int run_accuracy(int argc, char** argv) {
    std::optional<AccuracyOptions> parsed;
    try {
        parsed = parse_accuracy_options(argc, argv);
        if (!parsed) return 0;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
        return 2;
    }
    const AccuracyOptions& o = *parsed;
    auto created = create_program_context();
    if (!created) return fail("cannot start Vulkan: " + created.error().message);
    Context& context = *created.value();
    // Programs for materialising procedural environments (IblMeasure owns a compiler), and
    // the pipelines every environment's sessions share (each created once, not per session).
    IblMeasure measure(context, 1, ShaderCompilerOptions{o.job.shader_dir, o.job.shader_cache_dir});
    std::vector<Measured> results;
    for (const std::string& name : o.envs) {
        EnvironmentLoadOptions load;
        load.max_width = o.job.max_env_width;
        load.sanitize = o.job.sanitize;
        auto resolved = resolve_environment(name, o.env_width, load);
        if (!resolved) return fail(resolved.error().message);
        EnvironmentSource env = std::move(resolved).value();
        if (Status s = materialize_environment(context, measure.programs(), env); !s)
            return fail(name + ": " + s.error().message);
        downsample_to(env, o.env_width);
        const test::Equirect texels{env.width, env.height, env.image.rgba};
        if (texels.rgba.size() != size_t(texels.w) * texels.h * 4)
            return fail(name + ": no texels to compare with (" + std::to_string(texels.w) + " x " +
                        std::to_string(texels.h) + ")");
        const std::string label = name.rfind("builtin:", 0) == 0 ? name : fs::path(name).filename().string();
        const fs::path file = fs::temp_directory_path() /
                              ("facet_accuracy_" + std::to_string(::getpid()) + "_" + fs::path(name).stem().string() + ".exr");
        if (Status s = write_hdr_image(file.string(), texels.w, texels.h, texels.rgba); !s) return fail(s.error().message);
        std::fprintf(stderr, "%s: accuracy %s (%ux%u texels, %ux%u pixels, brdf %s)\n", program, label.c_str(), texels.w,
                     texels.h, o.job.frame.width, o.job.frame.height, brdf_model_name(o.job.frame.brdf));
        RenderJob job = o.job;
        job.env = file.string();
        job.programs = &measure.programs();
        job.frame.skybox = false;
        job.frame.views = {View::normal, View::position, View::basecolor, View::metallic, View::roughness};
        std::vector<RenderJob> jobs{job};
        if (o.compare) {
            jobs.push_back(job);
            jobs.back().shading = *o.compare;
            // Its image alone is measured, against the truth of the first job's views: no
            // view passes (five more draws of the scene at the frame's size, about a third of
            // a 1280x720 environment's time on lavapipe).
            jobs.back().frame.views.clear();
            std::fprintf(stderr, "%s:   compared with %s, frames alternating\n", program,
                         shading_method_name(*o.compare));
        }
        auto all = render_frames(context, jobs, o.runs);
        std::error_code ec;
        if (!all) {
            fs::remove(file, ec);
            return fail(label + ": " + all.error().message);
        }
        Frames* rendered = &all->front();
        Frames* compared = o.compare ? &all->back() : nullptr;
        const auto& session = rendered->session;
        std::optional<RenderedImages> frame = std::move(rendered->frame);
        if (o.reference) {
            std::fprintf(stderr, "%s:   reference mode\n", program);
            auto reference = session->render_reference(ReferenceSettings{});
            if (!reference) {
                fs::remove(file, ec);
                return fail(label + ": reference mode: " + reference.error().message);
            }
            frame->hdr = std::move(reference->hdr);
        }
        fs::remove(file, ec);
        test::FinalImageViews views{frame->width,
                                    frame->height,
                                    frame->hdr,
                                    view_of(*frame, View::normal),
                                    view_of(*frame, View::position),
                                    view_of(*frame, View::basecolor),
                                    view_of(*frame, View::metallic),
                                    view_of(*frame, View::roughness)};
        const glm::vec3 eye = session->camera().position;
        test::AccuracySettings settings;
        settings.intensity = job.ibl_intensity;
        settings.max_pixels = o.max_pixels;
        const test::TexelLights lights = test::texel_lights(texels);
        for (BrdfModel model : o.truth_models) {
            std::fprintf(stderr, "%s:   truth: %s model, %u texels, up to %u pixels\n", program, brdf_model_name(model),
                         texels.w * texels.h, o.max_pixels);
            Measured m{label, model, texels.w, texels.h, {}, rendered->forward_ms, session->shading(), {}, 0};
            try {
                const test::FinalImageTruth truth =
                    test::final_image_truth(views, {eye.x, eye.y, eye.z}, lights, model, settings);
                m.accuracy = test::final_image_accuracy(truth, frame->hdr);
                if (compared) {
                    m.compared = test::final_image_accuracy(truth, compared->frame.hdr);
                    m.compared_forward_ms = compared->forward_ms;
                }
            } catch (const std::invalid_argument& e) {
                return fail(label + ": " + e.what());
            }
            std::printf("\n%s (%ux%u texels), %s %s BRDF, truth %s BRDF, %ux%u: %zu pixels, truth %.1f s, "
                        "forward pass %.2f ms\n",
                        label.c_str(), texels.w, texels.h, o.reference ? "reference mode" : "frame",
                        brdf_model_name(job.frame.brdf), brdf_model_name(model),
                        frame->width, frame->height, m.accuracy.pixels, m.accuracy.truth_seconds, m.forward_ms);
            std::printf("%s", test::format_accuracy_table(m.accuracy).c_str());
            // The prediction is for the frame's own model (the truth the automatic choice sums).
            if (m.shading.predicted_error && model == job.frame.brdf) {
                std::printf("  shading %s, predicted per group (probe):", shading_method_name(m.shading.method));
                for (const test::GroupError& g : m.accuracy.groups) {
                    const double predicted = predicted_of(m.shading, test::group_name(g));
                    if (predicted >= 0) std::printf(" %.2f", 100 * predicted);
                    else std::printf(" -");
                }
                std::printf("\n  predicted worst: %s, mean %.2f%% (target %.2f%%)\n",
                            m.shading.predicted_worst_group.c_str(), 100 * *m.shading.predicted_error,
                            100 * m.shading.target_error);
            }
            if (m.compared) {
                std::printf("  compared with %s (forward pass %.2f ms), mean err%% per group:",
                            shading_method_name(*o.compare), m.compared_forward_ms);
                for (const test::GroupError& g : m.compared->groups) std::printf(" %.2f", 100 * g.mean_rel);
                std::printf("\n");
            }
            std::fflush(stdout);
            results.push_back(std::move(m));
        }
    }
    if (!o.json.empty())
        if (Status s = write_text_file(o.json, json_of(results, o, context.device_name())); !s)
            return fail(s.error().message);
    return 0;
}

}  // namespace facet
