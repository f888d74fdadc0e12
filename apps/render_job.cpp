#include "render_job.h"

#include "render_session_state.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <facet/gpu/context.h>
#include <facet/gpu/device_limits.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/ibl/light_extraction.h>
#include <facet/ibl/method_domain.h>
#include <facet/render/frame_budget.h>
#include <facet/render/gpu_scene.h>
#include <facet/scene/builtin_scenes.h>
#include <facet/scene/gltf_loader.h>
#include <facet/scene/scene_needs.h>
#include <facet/shader/program_cache.h>

namespace facet {

RenderSession::RenderSession(std::unique_ptr<State> state) : state_(std::move(state)) {}
RenderSession::~RenderSession() = default;
const Scene& RenderSession::scene() const { return state_->scene; }
const CameraView& RenderSession::camera() const { return state_->frame.camera; }
const FrameSettings& RenderSession::frame() const { return state_->frame; }
const EnvironmentSource* RenderSession::environment() const { return state_->env ? &*state_->env : nullptr; }
const std::vector<PassTiming>& RenderSession::bake_timings() const { return state_->bake_timings; }
size_t RenderSession::pipeline_variants() const { return state_->renderer->pipeline_variants(); }

Result<std::unique_ptr<RenderSession>> RenderSession::create(Context& context, const RenderJob& job,
                                                             const ProgressFn& progress) {
    std::optional<MaterialPreset> preset;
    if (job.preset) {
        preset = find_material_preset(*job.preset);
        if (!preset)
            return Error{"--preset: unknown preset '" + *job.preset + "' (" + material_preset_names() + ")"};
    }
    auto scene = job.model.rfind("builtin:", 0) == 0 ? builtin_scene(job.model, preset)
                                                      : load_gltf(job.model, job.model_limits);
    if (!scene) return scene.error();
    if (preset && !is_builtin_scene(job.model)) apply_material_preset(*scene, *preset);
    if (progress)
        progress("loaded " + job.model + ": " + std::to_string(scene->instances.size()) + " draws, " +
                 std::to_string(scene->indices.size() / 3) + " triangles, " + std::to_string(scene->materials.size()) +
                 " materials, " + std::to_string(scene->images.size()) + " textures");
    return create(context, job, std::move(scene).value(), progress);
}

Result<std::unique_ptr<RenderSession>> RenderSession::create(Context& context, const RenderJob& job, Scene scene,
                                                             const ProgressFn& progress) {
    auto s = std::make_unique<State>();
    s->context = &context;
    s->job = job;
    auto say = [&](const std::string& line) {
        if (progress) progress(line);
    };
    s->scene = std::move(scene);
    if (s->scene.instances.empty()) return Error{s->scene.source + ": the scene has nothing to draw"};
    s->frame = job.frame;
    s->frame.lights = s->scene.lights;
    s->frame.lights.insert(s->frame.lights.end(), job.extra_lights.begin(), job.extra_lights.end());
    const auto [lo, hi] = s->scene.world_bounds();
    const float aspect = float(s->frame.width) / float(std::max(1u, s->frame.height));
    const float yfov = glm::radians(job.fov_deg);
    if (job.gltf_camera) {
        if (s->scene.cameras.empty()) return Error{job.model + ": --camera gltf, but the file has no camera"};
        const Camera& c = s->scene.cameras.front();
        s->frame.camera = {c.position, c.target, c.up, c.yfov, c.znear};
    } else if (job.orbit) {
        const glm::vec3 target = job.target.value_or(0.5f * (lo + hi));
        s->frame.camera = orbit_camera(target, (*job.orbit)[0], (*job.orbit)[1], (*job.orbit)[2], yfov);
    } else {
        s->frame.camera = frame_bounds(lo, hi, yfov, aspect);
        if (job.target) {
            const float distance = glm::length(s->frame.camera.position - s->frame.camera.target);
            s->frame.camera = orbit_camera(*job.target, 0.0f, 0.0f, distance, yfov);
        }
    }

    // A frame the device cannot hold fails before the model is uploaded and the lighting baked.
    if (Status fits = check_frame_fits(context, s->frame); !fits) return fits.error();

    ShaderCompilerOptions compiler_options;
    compiler_options.source_dir = job.shader_dir;
    compiler_options.disk_cache_dir = job.shader_cache_dir;
    s->compiler = std::make_unique<ShaderCompiler>(compiler_options);
    s->programs = std::make_unique<ProgramCache>(context, *s->compiler);
    if (job.env != "none") {
        auto env = resolve_environment(job.env, job.env_width, {job.sanitize, job.max_env_width});
        if (!env) return env.error();
        s->env = std::move(env).value();
        if (s->env->source_width != s->env->width)
            say(job.env + ": " + std::to_string(s->env->source_width) + "x" + std::to_string(s->env->source_height) +
                " downsampled to " + std::to_string(s->env->width) + "x" + std::to_string(s->env->height) +
                " while reading (--max-env-width " + std::to_string(job.max_env_width) + ")");
        if (s->env->image.sanitized_texels)
            say(job.env + ": replaced " + std::to_string(s->env->image.sanitized_texels) +
                " NaN, Inf or negative texels with 0");
        if (job.extract_lights) {
            if (Status st = materialize_environment(context, *s->programs, *s->env); !st) return st.error();
            s->original_texels = s->env->image.rgba;
            LightExtraction extraction = extract_lights(s->env->image.rgba, s->env->width, s->env->height);
            s->env->image.rgba = std::move(extraction.residual);
            s->frame.environment_lights = extraction.lights;
            say("extracted " + std::to_string(extraction.lights.size()) + " light(s) from " + job.env + ", " +
                std::to_string(int(std::lround(100 * extraction.extracted_power_fraction))) + "% of its power");
            for (const std::string& note : extraction.notes) say("light extraction: " + note);
        }
        // Model no more than the scene needs: pure metals need no irradiance.
        IblSettings requested = job.ibl;
        const SceneNeeds needs = scene_needs(s->scene);
        requested.want_irradiance = needs.diffuse || job.frame.multiscatter;
        requested.specular.min_roughness = needs.min_roughness;
        s->ibl_settings = resolved_ibl_settings(requested, *s->env);
        if (!s->env->sky)
            s->warnings = method_warnings(
                environment_stats(s->original_texels.empty() ? s->env->image.rgba : s->original_texels,
                                  s->env->width, s->env->height),
                s->ibl_settings);
        for (const std::string& w : s->warnings) say("warning: " + w);
        s->ibl_bake = std::make_unique<IblBake>(context, *s->programs);
        // With extracted lights, specular levels whose lobe is narrower than twice the
        // widest light come from the whole environment (their split sum sees the lights
        // well); the disks take over from the first level that is wider.
        SpecularSplit split;
        EnvironmentSource whole;
        if (!s->frame.environment_lights.empty()) {
            float widest = 0.0f;
            for (const DiskLight& d : s->frame.environment_lights) widest = std::max(widest, d.angular_radius);
            const uint32_t levels = s->ibl_settings.specular.levels;
            uint32_t level = 1;
            while (level < levels) {
                const float roughness = float(level) / float(std::max(levels - 1, 1u));
                if (roughness * roughness >= widest) break;
                ++level;
            }
            whole = *s->env;
            whole.image.rgba = s->original_texels;
            split = {&whole, level};
            s->frame.environment_light_level = level;
        }
        RenderGraph graph;
        auto images = s->ibl_bake->add_passes(graph, *s->env, s->ibl_settings, split);
        if (!images) return images.error();
        s->ibl_images = *images;
        for (ImageHandle h : {s->ibl_images.cube, s->ibl_images.irradiance, s->ibl_images.specular, s->ibl_images.lut})
            if (h.valid()) graph.export_image(h, sampled_by_fragments);
        graph.export_image(s->ibl_images.equirect, readable);  // the reference mode reads the texels
        s->bake_graph = graph.compile();
        s->bake_run = std::make_unique<GraphRun>(context, s->bake_graph);
        say("baking " + job.env + " (" + std::to_string(s->env->width) + "x" + std::to_string(s->env->height) +
            ", cube " + std::to_string(s->ibl_settings.cube_size) + "^2)");
        s->bake_run->submit_and_wait([&](uint32_t done, uint32_t total, const std::string& pass) {
            say("baking [" + std::to_string(done) + "/" + std::to_string(total) + "] " + pass);
        });
        s->bake_timings = s->bake_run->timings();
    }
    s->gpu_scene = std::make_unique<GpuScene>(context, s->scene);
    s->renderer = std::make_unique<ForwardRenderer>(context, *s->programs);
    s->executor = std::make_unique<GraphExecutor>(context);
    return std::unique_ptr<RenderSession>(new RenderSession(std::move(s)));
}

Result<RenderedImages> RenderSession::render_frame(bool pass_by_pass) {
    State& s = *state_;
    Context& context = *s.context;
    const auto start = std::chrono::steady_clock::now();
    RenderGraph graph;
    const std::optional<IblInputs> ibl = import_ibl(s, graph);
    auto images = s.renderer->add_passes(graph, *s.gpu_scene, s.frame, ibl);
    if (!images) return images.error();
    graph.export_image(images->hdr, readable);
    graph.export_image(images->ldr, readable);
    for (auto& [view, handle] : images->views) graph.export_image(handle, readable);
    CompiledGraph compiled = graph.compile();
    if (Status fits = check_graph_fits(context, compiled); !fits) return fits.error();
    // The session's executor keeps the frame's images for the next frame of the same shape.
    std::vector<PassTiming> pass_wall;
    auto last = std::chrono::steady_clock::now();
    GraphRun::Progress progress;
    if (pass_by_pass)
        progress = [&](uint32_t, uint32_t, const std::string& pass) {
            const auto now = std::chrono::steady_clock::now();
            pass_wall.push_back({pass, std::chrono::duration<double, std::milli>(now - last).count()});
            last = now;
        };
    auto ran = s.executor->submit_and_wait(compiled, 0, progress);
    if (!ran) return ran.error();
    GraphRun& run = **ran;

    RenderedImages out;
    out.width = s.frame.width;
    out.height = s.frame.height;
    auto read_floats = [&](ImageHandle h) {
        auto bytes = read_image(context, *run.transient_image(h), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        std::vector<float> values(bytes.size() / sizeof(float));
        std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
        return values;
    };
    out.hdr = read_floats(images->hdr);
    auto ldr = read_image(context, *run.transient_image(images->ldr), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    out.ldr.resize(ldr.size());
    std::memcpy(out.ldr.data(), ldr.data(), ldr.size());
    for (auto& [view, handle] : images->views) out.views.push_back({view, read_floats(handle)});
    out.timings = run.timings();
    out.pass_wall = std::move(pass_wall);
    out.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace facet
