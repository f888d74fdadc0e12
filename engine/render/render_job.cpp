#include <facet/render/render_job.h>

#include "render/render_session_state.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <span>

#include <facet/gpu/context.h>
#include <facet/gpu/device_limits.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/cache/directory_cache.h>
#include <facet/ibl/bake_rules.h>
#include <facet/ibl/baked_environment.h>
#include <facet/ibl/light_extraction.h>
#include <facet/ibl/method_domain.h>
#include <facet/render/frame_budget.h>
#include <facet/render/gpu_scene.h>
#include <facet/scene/builtin_scenes.h>
#include <facet/scene/gltf_loader.h>
#include <facet/scene/scene_needs.h>
#include <facet/shader/program_cache.h>
#include "core/guarded.h"

namespace facet {

RenderSession::RenderSession(std::unique_ptr<State> state) : state_(std::move(state)) {}
RenderSession::~RenderSession() = default;
const Scene& RenderSession::scene() const { return state_->scene; }
const CameraView& RenderSession::camera() const { return state_->frame.camera; }
const FrameSettings& RenderSession::frame() const { return state_->frame; }
const EnvironmentSource* RenderSession::environment() const { return state_->env ? &*state_->env : nullptr; }
const BakedEnvironment* RenderSession::baked() const { return state_->baked ? &*state_->baked : nullptr; }
const std::vector<PassTiming>& RenderSession::bake_timings() const { return state_->bake_timings; }
size_t RenderSession::pipeline_variants() const { return state_->renderer->pipeline_variants(); }

Result<std::unique_ptr<RenderSession>> RenderSession::create(Context& context, const RenderJob& job,
                                                             const ProgressFn& progress) {
    return create(context, job, Callbacks{progress, {}, {}});
}

Result<std::unique_ptr<RenderSession>> RenderSession::create(Context& context, const RenderJob& job, Scene scene,
                                                             const ProgressFn& progress) {
    return create(context, job, std::move(scene), Callbacks{progress, {}, {}});
}

namespace {

// A safe point between the loading steps (the bake has its own inside it).
bool session_stopped(const RenderSession::Callbacks& cb, const char* point) { return cb.stop && cb.stop(point); }

}  // namespace

Result<std::unique_ptr<RenderSession>> RenderSession::create(Context& context, const RenderJob& job,
                                                             const Callbacks& cb) {
    const ProgressFn& progress = cb.progress;
    std::optional<MaterialPreset> preset;
    if (job.preset) {
        preset = find_material_preset(*job.preset);
        if (!preset)
            return Error{"--preset: unknown preset '" + *job.preset + "' (" + material_preset_names() + ")"};
    }
    auto scene = job.model.rfind("builtin:", 0) == 0 ? builtin_scene(job.model, preset)
                                                      : load_gltf(job.model, job.model_limits, job.model_scene);
    if (!scene) return scene.error();
    if (preset && !is_builtin_scene(job.model)) apply_material_preset(*scene, *preset);
    if (progress)
        progress("loaded " + job.model + ": " + std::to_string(scene->instances.size()) + " draws, " +
                 std::to_string(scene->indices.size() / 3) + " triangles, " + std::to_string(scene->materials.size()) +
                 " materials, " + std::to_string(scene->images.size()) + " textures");
    if (session_stopped(cb, "model")) return Error{kBakeCancelled};
    return create(context, job, std::move(scene).value(), cb);
}

namespace {

// The session's image-based lighting: a saved bake (--ibl DIR), else the bake cache's entry
// for this bake key (baked and saved into it on a miss), else a fresh bake.
// `baked_here`: set when the bake ran in this call (it then said what it extracted).
Result<BakedEnvironment> bake_for_session(Context& context, RenderSession::State& s,
                                          const std::function<void(const std::string&)>& say,
                                          const RenderSession::Callbacks& cb, bool& baked_here) {
    const RenderJob& job = s.job;
    baked_here = false;
    if (!job.ibl_dir.empty()) {
        say("loading the bake in " + job.ibl_dir);
        return BakedEnvironment::load(context, job.ibl_dir);
    }
    BakeSettings settings;
    settings.ibl = ibl_settings_for_scene(job.ibl, scene_needs(s.scene), job.frame.multiscatter);
    settings.ibl.lut.brdf = job.frame.brdf;  // the frame's model decides the LUT's
    settings.extract_lights = job.extract_lights;
    settings.extraction = job.extraction;
    settings.preview = false;  // environment.png: nothing here shows or saves it
    // The LUT is kept with the bakes, under the same bound.
    settings.lut_cache = {job.bake_cache_dir, job.bake_cache_max_bytes, false};
    BakeCallbacks callbacks;
    callbacks.progress = say;
    callbacks.pass_done = [&](uint32_t done, uint32_t total, const std::string& pass) {
        say("baking [" + std::to_string(done) + "/" + std::to_string(total) + "] " + pass);
        if (cb.bake_pass_done) cb.bake_pass_done(done, total, pass);
    };
    callbacks.stop = cb.stop;
    auto bake = [&]() -> Result<BakedEnvironment> {
        say("baking " + job.env + " (" + std::to_string(s.env->width) + "x" + std::to_string(s.env->height) + ")");
        baked_here = true;
        return bake_environment(context, *s.programs, *s.env, settings, callbacks);
    };
    if (job.bake_cache_dir.empty()) return bake();
    BakeSettings resolved = settings;
    resolved.ibl = resolved_ibl_settings(settings.ibl, *s.env);
    const std::string key = bake_key(*s.env, resolved);
    // The cache checks sizes; the load below checks each file's hash as it reads it, so a
    // hit reads every file once.
    DirectoryCache cache({job.bake_cache_dir, job.bake_cache_max_bytes, false});
    // A damaged entry found while loading is removed and filled again, once.
    for (int attempt = 0;; ++attempt) {
        bool bake_failed = false;  // the bake's own error passes through; the cache's names the folder
        std::optional<BakedEnvironment> fresh;
        auto entry = cache.get_or_fill(key, [&](const std::string& dir) -> Status {
            auto baked = bake();
            if (!baked) {
                bake_failed = true;
                return baked.error();
            }
            // Only what load() reads: no previews in the cache.
            if (Status saved = baked->save(dir, BakeSaveOptions{false}); !saved) return saved;
            fresh = std::move(baked).value();
            return Ok{};
        });
        if (!entry) return bake_failed ? entry.error() : Error{"bake cache " + job.bake_cache_dir + ": " + entry.error().message};
        if (!entry->damage.empty()) say("bake cache: entry " + key + " was damaged (" + entry->damage + "); baked again");
        say(std::string("bake cache: ") + (entry->built ? "stored " : "using ") + entry->path);
        if (fresh) return std::move(*fresh);  // the images just saved are still on the GPU
        auto loaded = BakedEnvironment::load(context, entry->path, [&](const std::string& name, std::span<const std::byte> bytes) {
            return check_cache_file(*entry, name, bytes);
        });
        if (loaded || attempt > 0) return loaded;
        say("bake cache: entry " + key + " was damaged (" + loaded.error().message + "); baking again");
        entry->hold.reset();
        if (Status removed = cache.remove(key); !removed)
            return Error{"bake cache " + job.bake_cache_dir + ": " + removed.error().message};
    }
}

}  // namespace

Result<std::unique_ptr<RenderSession>> RenderSession::create(Context& context, const RenderJob& requested,
                                                             Scene scene, const Callbacks& cb) {
    const ProgressFn& progress = cb.progress;
    if (!(requested.target_error > 0 && requested.target_error < 1))
        return Error{"target error " + std::to_string(requested.target_error) +
                     " is outside (0, 1): it is a fraction of the exact value (0.03 = 3%)"};
    auto s = std::make_unique<State>();
    s->context = &context;
    s->shading = resolve_shading(requested);
    const RenderJob& job = s->shading.job;
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

    if (job.programs) {
        // The caller's pipelines: its Vulkan objects must belong to this session's device.
        if (&job.programs->context() != &context)
            return Error{"RenderJob::programs: the pipeline cache belongs to another Vulkan context"};
        s->programs = job.programs;
    } else {
        ShaderCompilerOptions compiler_options;
        compiler_options.source_dir = job.shader_dir;
        compiler_options.disk_cache_dir = job.shader_cache_dir;
        s->compiler = std::make_unique<ShaderCompiler>(compiler_options);
        s->own_programs = std::make_unique<ProgramCache>(context, *s->compiler);
        s->programs = s->own_programs.get();
    }
    // With a saved bake (--ibl DIR) the environment is the bake's: job.env is not read.
    const bool saved_bake = !job.ibl_dir.empty();
    if (!saved_bake && job.env != "none") {
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
        // Texels on the CPU (a procedural sky rendered): the shading choice's truth sums
        // them, and the reference mode integrates the whole environment, lights included.
        if (Status st = materialize_environment(context, *s->programs, *s->env); !st) return st.error();
        if (job.extract_lights) s->original_texels = s->env->image.rgba;
        if (session_stopped(cb, "environment")) return Error{kBakeCancelled};
    }
    if (saved_bake || job.env != "none") {
        bool baked_here = false;
        auto baked = bake_for_session(context, *s, say, cb, baked_here);
        if (!baked) return baked.error();
        s->baked = std::move(baked).value();
        const BakeMetadata& m = s->baked->metadata();
        if (m.settings.want_lut && m.settings.lut.brdf != s->frame.brdf)
            return Error{(saved_bake ? job.ibl_dir : std::string("the bake")) + ": its BRDF LUT is for the " +
                         brdf_model_name(m.settings.lut.brdf) + " BRDF model, the render asks for " +
                         brdf_model_name(s->frame.brdf) + " (--brdf): bake again with --brdf " +
                         brdf_model_name(s->frame.brdf) + " or render with --brdf " +
                         brdf_model_name(m.settings.lut.brdf)};
        s->frame.environment_lights = s->baked->lights();
        s->frame.environment_light_level = m.light_split_level;
        if (job.extract_lights && !saved_bake) {
            // A fresh bake said it already (its progress line); a cached one did not.
            if (!baked_here)
                say("extracted " + std::to_string(s->baked->lights().size()) + " light(s) from " + job.env + ", " +
                    std::to_string(int(std::lround(100 * m.extracted_power_fraction))) + "% of its power");
            for (const std::string& note : m.extraction_notes) say("light extraction: " + note);
        }
        if (session_stopped(cb, "shading")) return Error{kBakeCancelled};
        if (Status chosen = choose_session_shading(*s, say); !chosen) return chosen.error();
        for (const std::string& note : m.format_notes) say(note);
        s->ibl_settings = m.settings;
        s->warnings = m.warnings;
        for (const std::string& w : s->warnings) say("warning: " + w);
        s->bake_timings = m.timings;
    }
    if (session_stopped(cb, "scene")) return Error{kBakeCancelled};
    auto gpu_scene = GpuScene::create(context, s->scene);
    if (!gpu_scene) return gpu_scene.error();
    s->gpu_scene = std::move(*gpu_scene);
    auto renderer = ForwardRenderer::create(context, *s->programs);
    if (!renderer) return renderer.error();
    s->renderer = std::move(*renderer);
    s->executor = std::make_unique<GraphExecutor>(context);
    return std::unique_ptr<RenderSession>(new RenderSession(std::move(s)));
}

Result<RenderedImages> RenderSession::render_frame(bool pass_by_pass) try {
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
        auto bytes = or_throw(read_image(context, *run.transient_image(h), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
        std::vector<float> values(bytes.size() / sizeof(float));
        std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
        return values;
    };
    out.hdr = read_floats(images->hdr);
    auto ldr = or_throw(read_image(context, *run.transient_image(images->ldr), 0, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
    out.ldr.resize(ldr.size());
    std::memcpy(out.ldr.data(), ldr.data(), ldr.size());
    for (auto& [view, handle] : images->views) out.views.push_back({view, read_floats(handle)});
    out.timings = run.timings();
    out.pass_wall = std::move(pass_wall);
    out.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
} catch (const VulkanError& e) {  // a readback's failure (or_throw above)
    return Error{e.what(), e.result()};
}

}  // namespace facet
