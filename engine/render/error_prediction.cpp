#include "render/error_prediction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include <facet/graph/render_graph.h>
#include <facet/reference/final_image_accuracy.h>
#include <facet/render/gpu_scene.h>
#include <facet/render/shading_method.h>
#include <facet/scene/builtin_scenes.h>
#include <facet/scene/scene_needs.h>
#include "core/guarded.h"
#include "render/shading_choice.h"

namespace facet {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr float smoothest = 0.2f;  // the measure's smoothest roughness (its first band's lower edge)

// The environment the truth sums: box-filtered by the largest power of two that keeps it
// at least `width` wide. A texel of 256 is 1.4 degrees, narrower than any lobe of
// roughness 0.2 (the measure's smoothest), and box filtering keeps the power.
test::Equirect truth_environment(const EnvironmentSource& env, uint32_t width) {
    test::Equirect e{env.width, env.height, env.image.rgba};
    uint32_t factor = 1;
    while (env.width / (factor * 2) >= width && env.width % (factor * 2) == 0 && env.height % (factor * 2) == 0)
        factor *= 2;
    return factor == 1 ? e : test::downsample(e, factor);
}

// The views the measure reads (render/views.h's normal, position, base colour, metalness,
// roughness), computed on the CPU by casting each pixel centre's ray at the probe's
// spheres: the renderer would need a pipeline per view (seconds on lavapipe). The mesh
// differs from the sphere by 0.1% of its radius, far below what changes the truth.
struct ProbeViews {
    std::vector<float> normal, position, basecolor, metallic, roughness;
};

ProbeViews cast_probe_views(const Scene& scene, const CameraView& camera, uint32_t width, uint32_t height) {
    const size_t count = size_t(width) * height;
    ProbeViews v;
    for (auto* image : {&v.normal, &v.position, &v.basecolor, &v.metallic, &v.roughness}) image->assign(count * 4, 0.0f);
    const glm::vec3 forward = glm::normalize(camera.target - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float tan_y = std::tan(0.5f * camera.yfov), tan_x = tan_y * float(width) / float(height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            // Vulkan's framebuffer: row 0 at the top (clip space y down).
            const float ndc_x = 2.0f * (float(x) + 0.5f) / float(width) - 1.0f;
            const float ndc_y = 2.0f * (float(y) + 0.5f) / float(height) - 1.0f;
            const glm::vec3 d = glm::normalize(forward + ndc_x * tan_x * right - ndc_y * tan_y * up);
            float nearest = std::numeric_limits<float>::max();
            const Instance* hit = nullptr;
            glm::vec3 centre{}, normal{};
            for (const Instance& instance : scene.instances) {
                const Primitive& p = scene.primitives[instance.primitive];
                const glm::vec3 c = glm::vec3(instance.world * glm::vec4(0.5f * (p.bounds_min + p.bounds_max), 1.0f));
                const float r = 0.5f * (p.bounds_max.x - p.bounds_min.x) * glm::length(glm::vec3(instance.world[0]));
                // |o + t d - c|^2 = r^2, nearest root in front of the eye.
                const glm::vec3 oc = camera.position - c;
                const float b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - r * r);
                if (disc < 0) continue;
                const float t = -b - std::sqrt(disc);
                if (t <= 0 || t >= nearest) continue;
                nearest = t;
                hit = &instance;
                centre = c;
                normal = (camera.position + t * d - c) / r;
            }
            if (!hit) continue;
            const size_t i = (size_t(y) * width + x) * 4;
            const Material& m = scene.materials[scene.primitives[hit->primitive].material];
            const glm::vec3 position = camera.position + nearest * d;
            for (int c = 0; c < 3; ++c) {
                v.normal[i + size_t(c)] = glm::normalize(normal)[c];
                v.position[i + size_t(c)] = position[c];
                v.basecolor[i + size_t(c)] = m.base_color[c];
                v.metallic[i + size_t(c)] = m.metallic;
                v.roughness[i + size_t(c)] = m.roughness;
            }
            for (auto* image : {&v.normal, &v.position, &v.basecolor, &v.metallic, &v.roughness}) (*image)[i + 3] = 1.0f;
        }
    return v;
}

}  // namespace

Scene probe_scene(const Scene& scene) {
    Scene probe = builtin_scene("builtin:spheres").value();  // built in: cannot fail
    // Untextured materials: the probe's spheres take their (roughness, metalness) pairs
    // themselves, in turn (a scene of 49 or fewer pairs is probed exactly).
    bool textured = false;
    std::vector<std::pair<float, float>> pairs;
    for (const Material& m : scene.materials) {
        textured = textured || m.metallic_roughness_texture.valid();
        if (m.roughness >= smoothest) pairs.push_back({m.roughness, m.metallic});
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    if (!textured && !pairs.empty() && pairs.size() <= probe.materials.size()) {
        for (size_t i = 0; i < probe.materials.size(); ++i)
            std::tie(probe.materials[i].roughness, probe.materials[i].metallic) = pairs[i % pairs.size()];
        return probe;
    }
    // Otherwise the grid spans the materials' range: factors, down to 0 where a texture
    // scales them.
    const SceneNeeds needs = scene_needs(scene);
    float r_lo = 1, r_hi = 0, m_lo = 1, m_hi = 0;
    for (const Material& m : scene.materials) {
        const bool scaled = m.metallic_roughness_texture.valid();
        r_lo = std::min(r_lo, scaled ? 0.0f : m.roughness);
        r_hi = std::max(r_hi, m.roughness);
        m_lo = std::min(m_lo, scaled ? 0.0f : m.metallic);
        m_hi = std::max(m_hi, m.metallic);
    }
    r_lo = std::max({r_lo, needs.min_roughness, smoothest});
    if (!(r_hi >= r_lo)) r_lo = smoothest, r_hi = 1, m_lo = 0, m_hi = 1;  // nothing the measure sees
    if (!(m_hi >= m_lo)) m_lo = 0, m_hi = 1;
    if (!needs.diffuse) m_lo = m_hi = 1;
    const SpheresGrid grid;
    for (size_t i = 0; i < probe.materials.size(); ++i) {
        const float column = float(i % grid.columns) / float(grid.columns - 1);
        const float row = float(i / grid.columns) / float(grid.rows - 1);
        probe.materials[i].roughness = r_lo + (r_hi - r_lo) * column;
        probe.materials[i].metallic = m_lo + (m_hi - m_lo) * row;
    }
    return probe;
}

std::array<bool, 8> material_groups(const Scene& scene) {
    std::array<bool, 8> reached{};
    for (const Material& m : scene.materials) {
        if (m.roughness < smoothest) continue;  // not in the measure (material_shading_groups counts it in the first band)
        const std::array<bool, 8> groups = material_shading_groups(m);
        for (size_t g = 0; g < groups.size(); ++g) reached[g] = reached[g] || groups[g];
    }
    return reached;
}

Result<ShadingPrediction> predict_shading_errors(RenderSession::State& s, std::span<const ShadingMethod> methods,
                                                 const PredictionSettings& settings) try {
    const auto start = std::chrono::steady_clock::now();
    Context& context = *s.context;
    const Scene probe = probe_scene(s.scene);
    const std::array<bool, 8> groups = material_groups(probe);
    auto gpu_scene = GpuScene::create(context, probe);
    if (!gpu_scene) return gpu_scene.error();
    auto renderer = ForwardRenderer::create(context, *s.programs);
    if (!renderer) return renderer.error();
    GraphExecutor executor(context);

    // The frame's model and options; the environment alone lights the probe (the truth
    // has no punctual lights). The frame's sample count: the pipeline of the method chosen
    // is then the frame's own (built once) where the scene's materials are like the probe's.
    FrameSettings f = s.frame;
    f.width = settings.width;
    f.height = settings.height;
    f.skybox = false;
    f.lights.clear();
    const auto [lo, hi] = probe.world_bounds();
    f.camera = frame_bounds(lo, hi, glm::radians(45.0f), float(f.width) / float(f.height));

    auto render = [&](ShadingMethod method, bool two_lookups) -> Result<std::vector<float>> {
        f.dominant_direction = bends_lookup(method);
        f.dominant_groups.fill(true);  // the method's own error in every group
        f.two_lookup_groups = kDefaultTwoLookupGroups;
        if (two_lookups) f.two_lookup_groups.fill(true);
        f.environment_lights = shades_lights(method) ? s.baked->lights() : std::vector<DiskLight>{};
        f.environment_light_level = s.baked->metadata().light_split_level;
        f.views.clear();
        RenderGraph graph;
        const std::optional<IblInputs> ibl = import_ibl(s, graph);
        auto images = renderer.value()->add_passes(graph, **gpu_scene, f, ibl);
        if (!images) return images.error();
        graph.export_image(images->hdr, readable);
        CompiledGraph compiled = graph.compile();
        auto ran = executor.submit_and_wait(compiled);
        if (!ran) return ran.error();
        return read_floats(context, *(*ran)->transient_image(images->hdr), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    };

    ShadingPrediction out;
    out.groups = groups;
    std::optional<test::FinalImageTruth> truth;
    for (size_t i = 0; i < methods.size(); ++i) {
        auto hdr = render(methods[i], false);
        if (!hdr) return hdr.error();
        if (!truth) {
            // The probe's geometry and materials are the same for every method: the truth
            // is summed once, at the pixels the first render covers.
            const ProbeViews v = cast_probe_views(probe, f.camera, f.width, f.height);
            const test::FinalImageViews views{f.width, f.height, *hdr, v.normal, v.position, v.basecolor, v.metallic,
                                              v.roughness};
            test::AccuracySettings accuracy;
            accuracy.intensity = s.job.ibl_intensity;
            accuracy.max_pixels = settings.pixels;
            const test::TexelLights texels = test::texel_lights(truth_environment(*s.env, settings.truth_env_width));
            const glm::vec3 eye = f.camera.position;
            truth = test::final_image_truth(views, {eye.x, eye.y, eye.z}, texels, s.frame.brdf, accuracy);
            out.truth_seconds = truth->seconds;
        }
        // A NaN or Inf in the render counts as an infinite error: never within a target.
        auto group_errors = [&](const std::vector<float>& image) {
            const test::FinalImageAccuracy a = test::final_image_accuracy(*truth, image);
            std::array<double, 8> out{};
            for (size_t g = 0; g < 8; ++g) {
                const double e = a.groups[g].mean_rel;
                out[g] = a.groups[g].pixels == 0 ? nan : std::isfinite(e) ? e : inf;
            }
            return out;
        };
        MethodPrediction p;
        p.method = methods[i];
        p.worst = nan;
        p.group_error = group_errors(*hdr);
        for (size_t g = 0; g < 8; ++g) {
            if (!groups[g] || std::isnan(p.group_error[g])) continue;
            if (p.worst_group < 0 || p.group_error[g] > p.worst) {
                p.worst = p.group_error[g];
                p.worst_group = int(g);
            }
        }
        if (settings.two_lookups && bends_lookup(methods[i])) {
            auto two = render(methods[i], true);
            if (!two) return two.error();
            p.two_lookup_error = group_errors(*two);
        }
        out.methods.push_back(p);
        // The methods come cheapest first: one within the target ends the search (a dearer
        // one would not be chosen), saving its pipeline and probe render.
        if (p.worst <= settings.stop_within) break;
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
} catch (const VulkanError& e) {  // a readback's failure (read_floats)
    return Error{e.what(), e.result()};
}

}  // namespace facet
