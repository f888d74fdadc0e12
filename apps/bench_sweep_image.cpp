#include "bench_sweep_image.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <facet/gpu/context.h>
#include <facet/ibl/ibl_measure.h>
#include <facet/io/image_io.h>
#include <facet/reference/final_image_accuracy.h>
#include <facet/render/render_job.h>
#include "shader_cache.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

const std::vector<float>& view_of(const RenderedImages& frame, View view) {
    static const std::vector<float> none;
    for (const auto& [v, pixels] : frame.views)
        if (v == view) return pixels;
    return none;
}

// The frame's own passes (forward, tone mapping), not the views drawn for the truth.
double frame_ms(const RenderedImages& frame) {
    double ms = 0;
    for (const PassTiming& t : frame.pass_wall)
        if (t.name.rfind("view ", 0) != 0) ms += t.time_ms;
    return ms;
}

// NaN, Inf or a negative value in a covered pixel: a failure whatever the error.
bool has_bad_values(const std::vector<float>& hdr) {
    for (size_t i = 0; i + 3 < hdr.size(); i += 4)
        if (hdr[i + 3] > 0)
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(hdr[i + c]) || hdr[i + c] < 0) return true;
    return false;
}

// Removes the temporary environment however the stage ends.
struct TemporaryFile {
    fs::path path;
    ~TemporaryFile() {
        std::error_code ec;
        fs::remove(path, ec);
    }
};

}  // namespace

Status sweep_final_image(Context& context, const test::Equirect& texels, const std::string& label,
                         const SweepOptions& o, const std::function<void(SweepRow)>& record) {
    const TemporaryFile file{fs::temp_directory_path() /
                             ("facet_sweep_" + std::to_string(::getpid()) + "_" + label + ".exr")};
    if (Status s = write_hdr_image(file.path.string(), texels.w, texels.h, texels.rgba); !s) return s.error();
    const test::TexelLights lights = test::texel_lights(texels);
    test::AccuracySettings settings;
    settings.max_pixels = o.max_pixels;
    auto error = [&](const std::string& what, const Error& e) {
        return Error{label + ": image: " + what + ": " + e.message, e.vk_result};
    };
    const ShadingMethod methods[] = {ShadingMethod::split_sum, ShadingMethod::dominant, ShadingMethod::lights,
                                     ShadingMethod::lights_dominant, ShadingMethod::automatic};
    for (BrdfModel model : o.brdf_models) {
        // Every method's session first; then the timed frames round-robin, so that a shared
        // machine's changing load falls on every method alike.
        std::vector<std::unique_ptr<RenderSession>> sessions;
        for (ShadingMethod method : methods) {
            RenderJob job;
            job.model = "builtin:spheres";
            job.env = file.path.string();
            job.shader_dir = shader_dir_from_environment();
            job.shader_cache_dir = o.shader_cache;
            job.frame.width = o.image_width;
            job.frame.height = o.image_height;
            job.frame.skybox = false;
            job.frame.brdf = model;
            job.frame.views = {View::normal, View::position, View::basecolor, View::metallic, View::roughness};
            job.shading = method;
            settings.intensity = job.ibl_intensity;
            auto session = RenderSession::create(context, job);
            if (!session) return error(shading_method_name(method), session.error());
            // One frame untimed first: pipelines and images are created on the first.
            if (auto warm = (*session)->render_frame(true); !warm) return error(shading_method_name(method), warm.error());
            sessions.push_back(std::move(session).value());
        }
        std::vector<std::vector<double>> times(sessions.size());
        std::vector<RenderedImages> frames(sessions.size());
        for (int r = 0; r < o.runs; ++r)
            for (size_t m = 0; m < sessions.size(); ++m) {
                auto images = sessions[m]->render_frame(true);
                if (!images) return error(shading_method_name(methods[m]), images.error());
                times[m].push_back(frame_ms(*images));
                frames[m] = std::move(images).value();
            }
        for (size_t m = 0; m < sessions.size(); ++m) {
            RenderSession& session = *sessions[m];
            const RenderedImages& frame = frames[m];
            const ShadingMethod method = methods[m];
            const std::string name = shading_method_name(method);
            test::FinalImageViews views{frame.width,
                                        frame.height,
                                        frame.hdr,
                                        view_of(frame, View::normal),
                                        view_of(frame, View::position),
                                        view_of(frame, View::basecolor),
                                        view_of(frame, View::metallic),
                                        view_of(frame, View::roughness)};
            const glm::vec3 eye = session.camera().position;
            auto measure = [&](SweepRow row, const std::vector<float>& hdr) -> Status {
                row.brdf = brdf_model_name(model);
                views.hdr = hdr;
                try {
                    row.accuracy = test::final_image_accuracy(views, {eye.x, eye.y, eye.z}, lights, model, settings);
                } catch (const std::invalid_argument& e) {
                    return Error{label + ": image: " + row.method + ": " + e.what()};
                }
                for (const test::GroupError& g : row.accuracy->groups)
                    if (g.pixels) row.max_rel = std::isfinite(g.max_rel) ? std::max(row.max_rel, g.max_rel) : g.max_rel;
                if (has_bad_values(hdr)) row.failed = true, row.failure = "NaN, Inf or negative values";
                else if (!std::isfinite(row.accuracy->worst_mean_rel) || row.accuracy->worst < 0)
                    row.failed = true, row.failure = "no finite error measured";
                record(std::move(row));
                return Ok{};
            };
            SweepRow row{label, "image", name, "defaults", median(times[m])};
            if (method == ShadingMethod::automatic) {
                row.auto_choice = shading_method_name(session.shading().method);
                row.auto_reason = session.shading().reason;
                row.params = "picked " + row.auto_choice;
            }
            if (Status s = measure(row, frame.hdr); !s) return s;
            if (method != ShadingMethod::split_sum) continue;
            // The reference mode on the same session and camera: exactly N samples per pixel,
            // after one untimed call that creates its pipelines.
            ReferenceSettings warm_up;
            warm_up.min_samples = warm_up.max_samples = 1;
            warm_up.noise_target = 0;
            if (auto warm = session.render_reference(warm_up); !warm) return error("reference mode", warm.error());
            for (uint32_t spp : o.reference_spp) {
                ReferenceSettings rs;
                rs.min_samples = rs.max_samples = spp;
                rs.noise_target = 0;
                std::vector<double> wall_ms;
                std::vector<float> hdr;
                for (int r = 0; r < o.runs; ++r) {
                    const auto start = std::chrono::steady_clock::now();
                    auto reference = session.render_reference(rs);
                    if (!reference) return error("reference mode", reference.error());
                    wall_ms.push_back(
                        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
                    hdr = std::move(reference->hdr);
                }
                SweepRow ref{label, "image", "reference", std::to_string(spp) + " spp", median(wall_ms)};
                ref.samples_per_pixel = spp;
                if (Status s = measure(ref, hdr); !s) return s;
            }
        }
    }
    return Ok{};
}

}  // namespace facet
