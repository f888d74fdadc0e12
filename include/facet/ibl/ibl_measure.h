#pragma once
// Measuring IBL bakes against the brute-force truth (facet::reference: double precision
// over every texel), shared by facet-bench sweep and the accuracy budget (ibl/bake_budget.h): bake one stage with given settings (median wall time of its own passes, each
// pass its own submission), read it back, compare cube levels with a truth function.
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/ibl/bake_settings.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/shader/program_cache.h>
#include <facet/reference/ibl_reference.h>

namespace facet {

class Context;

struct ErrorStats {
    double err2 = 0, ref2 = 0, max_rel = 0, peak = 0, count = 0;
    bool bad = false;  // NaN, Inf or negative
    void add(const test::Vec3& want, const float* got, double mean_floor) {
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(got[c]) || got[c] < 0) bad = true;
            const double d = double(got[c]) - want[size_t(c)];
            err2 += d * d;
            ref2 += want[size_t(c)] * want[size_t(c)];
            peak = std::max(peak, want[size_t(c)]);
            count += 1;
            if (want[size_t(c)] > mean_floor) max_rel = std::max(max_rel, std::abs(d) / want[size_t(c)]);
        }
    }
    double rel_rmse() const { return ref2 > 0 ? std::sqrt(err2 / ref2) : 0; }
    double psnr() const {
        const double rmse = std::sqrt(err2 / std::max(count, 1.0));
        return rmse > 0 ? 20 * std::log10(peak / rmse) : 200;
    }
};

double median(std::vector<double> v);

struct Baked {
    std::vector<std::vector<float>> faces;  // [level * layers + layer] RGBA texels
    uint32_t size = 0, levels = 0;
    double gpu_ms = 0;  // wall time of the stage's own passes (median)
};

class IblMeasure {
public:
    // With its own shader compiler and programs.
    IblMeasure(Context& context, int runs, const ShaderCompilerOptions& compiler = {});
    // With the caller's programs (which must outlive it).
    IblMeasure(Context& context, ProgramCache& programs, int runs);
    // Bakes `what` ("irradiance", "specular" or "lut") with `settings`, `runs` times.
    // `stop` is asked after every pass ("pass"); when it says stop, the result is an
    // Error for which is_cancelled() holds.
    Result<Baked> bake(const EnvironmentSource& env, IblSettings settings, const std::string& what,
                       const BakeStopFn& stop = {});
    Context& context() { return context_; }
    ProgramCache& programs() { return *programs_; }

private:
    Context& context_;
    std::unique_ptr<ShaderCompiler> compiler_;
    std::unique_ptr<ProgramCache> own_programs_;
    ProgramCache* programs_;
    int runs_;
};

// A cube level compared with `truth(direction)` at k x k texels per face; any NaN, Inf or
// negative texel anywhere marks the stats bad.
void compare_cube(const Baked& b, uint32_t level, const std::function<test::Vec3(const test::Vec3&)>& truth,
                  ErrorStats& stats, uint32_t k = 4);

// A baked LUT (A, B) against quadrature at 8 x 8 points between texel centres, read with
// bilinear filtering as the renderer reads it, so that a coarse LUT shows its
// interpolation error.
ErrorStats lut_error(const Baked& lut, bool height_correlated);

}  // namespace facet
