#include <facet/ibl/ibl_measure.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include "ibl/bake_cancel.h"

namespace facet {
namespace {

// Passes every bake shares (input, cube, its mips) do not count towards a method's time.
bool shared_pass(const std::string& name) {
    return name == "upload environment" || name == "procedural sky" || name == "equirect to cube" ||
           name.rfind("cube mip", 0) == 0;
}

}  // namespace

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

IblMeasure::IblMeasure(Context& context, int runs, const ShaderCompilerOptions& compiler)
    : context_(context),
      compiler_(std::make_unique<ShaderCompiler>(compiler)),
      own_programs_(std::make_unique<ProgramCache>(context, *compiler_)),
      programs_(own_programs_.get()),
      runs_(runs) {}

IblMeasure::IblMeasure(Context& context, ProgramCache& programs, int runs)
    : context_(context), programs_(&programs), runs_(runs) {}

Result<Baked> IblMeasure::bake(const EnvironmentSource& env, IblSettings settings, const std::string& what,
                               const BakeStopFn& stop) try {
    settings.want_irradiance = what == "irradiance";
    settings.want_specular = what == "specular";
    settings.want_lut = what == "lut";
    settings = resolved_ibl_settings(settings, env);
    Baked out;
    std::vector<double> times;
    for (int r = 0; r < runs_; ++r) {
        IblBake ibl(context_, *programs_);
        RenderGraph graph;
        auto images = ibl.add_passes(graph, env, settings);
        if (!images) return images.error();
        const ImageHandle result = what == "irradiance" ? images->irradiance : what == "specular" ? images->specular
                                                                                                 : images->lut;
        graph.export_image(result, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                    VK_ACCESS_2_TRANSFER_READ_BIT});
        CompiledGraph compiled = graph.compile();
        GraphRun run(context_, compiled);
        // Pass by pass, each submission waited for: wall time per pass. Lavapipe's
        // timestamps undercount compute passes, so they cannot rank methods.
        double ms = 0;
        auto last = std::chrono::steady_clock::now();
        Status done = run.submit_and_wait([&](uint32_t, uint32_t, const std::string& pass) {
            const auto now = std::chrono::steady_clock::now();
            if (!shared_pass(pass)) ms += std::chrono::duration<double, std::milli>(now - last).count();
            last = now;
            bake_safe_point(stop, "pass");
        });
        if (!done) return done.error();
        times.push_back(ms);
        if (r + 1 < runs_) continue;
        const Image& image = *run.transient_image(result);
        out.size = image.desc().width;
        out.levels = image.desc().mip_levels;
        for (uint32_t m = 0; m < out.levels; ++m)
            for (uint32_t f = 0; f < image.desc().array_layers; ++f) {
                auto bytes = read_image(context_, image, m, f, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
                if (!bytes) return bytes.error();
                std::vector<float> v(bytes->size() / 4);
                std::memcpy(v.data(), bytes->data(), v.size() * 4);
                out.faces.push_back(std::move(v));
            }
    }
    out.gpu_ms = median(times);
    return out;
} catch (const BakeCancelled&) {
    return Error{kBakeCancelled};
}

// A cube level compared with `truth(direction)` at 4 x 4 texels per face; any NaN, Inf or
// negative texel anywhere counts as a failure.
void compare_cube(const Baked& b, uint32_t level, const std::function<test::Vec3(const test::Vec3&)>& truth,
                  ErrorStats& stats, uint32_t k_max) {
    const uint32_t n = std::max(1u, b.size >> level);
    std::vector<std::pair<test::Vec3, const float*>> points;
    double mean = 0;
    for (uint32_t f = 0; f < 6; ++f) {
        const std::vector<float>& face = b.faces[level * 6 + f];
        for (float v : face)
            if (!std::isfinite(v) || v < 0) stats.bad = true;
        for (uint32_t j = 0; j < std::min(n, k_max); ++j)
            for (uint32_t i = 0; i < std::min(n, k_max); ++i) {
                const uint32_t x = (2 * i + 1) * n / (2 * std::min(n, k_max)), y = (2 * j + 1) * n / (2 * std::min(n, k_max));
                const test::Vec3 d = test::cube_texel_direction(f, x, y, n);
                points.push_back({truth(d), &face[(size_t(y) * n + x) * 4]});
                mean += test::luminance(points.back().first);
            }
    }
    mean /= double(points.size());
    for (auto& [want, got] : points) stats.add(want, got, 0.01 * mean);
}

ErrorStats lut_error(const Baked& lut, bool height_correlated) {
    ErrorStats stats;
    const uint32_t n = lut.size;
    const std::vector<float>& t = lut.faces[0];
    for (float v : t)
        if (!std::isfinite(v) || v < 0) stats.bad = true;
    auto texel = [&](int x, int y, int c) {
        x = std::clamp(x, 0, int(n) - 1);
        y = std::clamp(y, 0, int(n) - 1);
        return double(t[(size_t(y) * n + size_t(x)) * 4 + size_t(c)]);
    };
    for (uint32_t j = 0; j < 8; ++j)
        for (uint32_t i = 0; i < 8; ++i) {
            const double u = (i + 0.3) / 8, v = (j + 0.6) / 8;  // NdotV, roughness
            const double x = u * n - 0.5, y = v * n - 0.5;
            const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
            const double fx = x - x0, fy = y - y0;
            float got[3] = {0, 0, 0};
            for (int c = 0; c < 2; ++c)
                got[c] = float((1 - fy) * ((1 - fx) * texel(x0, y0, c) + fx * texel(x0 + 1, y0, c)) +
                               fy * ((1 - fx) * texel(x0, y0 + 1, c) + fx * texel(x0 + 1, y0 + 1, c)));
            const test::Ab ab = test::brdf_lut_reference(u, v, height_correlated);
            stats.add({ab.a, ab.b, 0.0}, got, 0.01);
        }
    return stats;
}

}  // namespace facet
