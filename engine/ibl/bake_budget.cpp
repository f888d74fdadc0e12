#include <facet/ibl/bake_budget.h>

#include <cmath>
#include <optional>

#include <facet/ibl/ibl_measure.h>

#include "ibl/bake_cancel.h"

namespace facet {
namespace {

// Tries `candidates` in order and keeps the first whose error meets the target (or the
// most accurate when none does).
template <class Settings>
struct Candidate {
    std::string method, params;
    Settings settings;
};

template <class Settings>
Result<std::pair<Settings, BudgetChoice>> first_meeting(
    const std::vector<Candidate<Settings>>& candidates, const std::string& stage, double target,
    const std::function<Result<std::pair<double, double>>(const Settings&)>& measure,
    const std::function<void(const std::string&)>& progress) {
    std::pair<Settings, BudgetChoice> best{candidates.front().settings, {}};
    best.second.predicted_error = INFINITY;
    for (const auto& c : candidates) {
        auto measured = measure(c.settings);
        if (!measured) return measured.error();
        const auto [error, ms] = *measured;
        if (progress)
            progress("budget: " + stage + " " + c.method + " (" + c.params + "): error " + std::to_string(error) +
                     ", " + std::to_string(ms) + " ms");
        BudgetChoice choice{stage, c.method, c.params, error, ms, error <= target};
        if (choice.met) return std::pair<Settings, BudgetChoice>{c.settings, choice};
        if (error < best.second.predicted_error) best = {c.settings, choice};
    }
    return best;
}

}  // namespace

Result<Budget> choose_within_budget(Context& context, ProgramCache& programs, const EnvironmentSource& env,
                                    const IblSettings& base, double target, float rmin, float rmax,
                                    const BakeProgressFn& progress, const BakeStopFn& stop,
                                    const EnvironmentSource* whole) try {
    if (!(target > 0)) return Error{"--target-error must be positive"};
    if (!(rmin >= 0 && rmin <= rmax && rmax <= 1)) return Error{"--roughness must be A,B with 0 <= A <= B <= 1"};
    if (env.sky || env.image.rgba.empty() || (whole && (whole->sky || whole->image.rgba.empty())))
        return Error{"budget: the environment's texels are needed"};
    Budget budget;
    budget.target = target;
    budget.roughness_min = rmin;
    budget.roughness_max = rmax;
    budget.settings = base;
    IblMeasure measure(context, programs, 1);
    const test::Equirect e{env.width, env.height, env.image.rgba};
    auto stats_of = [](const ErrorStats& s) { return s.bad ? INFINITY : s.rel_rmse(); };

    if (base.want_irradiance) {
        const EnvironmentSource& lit = whole ? *whole : env;  // what the irradiance is baked from
        std::optional<test::Equirect> whole_texels;
        if (whole) whole_texels = test::Equirect{whole->width, whole->height, whole->image.rgba};
        const test::Equirect& lit_texels = whole ? *whole_texels : e;
        std::vector<Candidate<IrradianceSettings>> candidates;
        auto add = [&](const char* method, std::string params, auto set) {
            IrradianceSettings s = base.irradiance;
            set(s);
            candidates.push_back({method, std::move(params), s});
        };
        add("lowmip", "face 2", [](IrradianceSettings& s) { s.method = IrradianceMethod::lowmip; s.lowmip_size = 2; });
        add("sh9", "windowed", [](IrradianceSettings& s) { s.method = IrradianceMethod::sh9; });
        for (uint32_t src : {4u, 8u, 16u, 32u})
            add("convolve", "source " + std::to_string(src), [src](IrradianceSettings& s) {
                s.method = IrradianceMethod::convolve;
                s.source_size = src;
            });
        auto chosen = first_meeting<IrradianceSettings>(
            candidates, "irradiance", target,
            [&](const IrradianceSettings& s) -> Result<std::pair<double, double>> {
                IblSettings settings = base;
                settings.irradiance = s;
                auto baked = measure.bake(lit, settings, "irradiance", stop);
                if (!baked) return baked.error();
                ErrorStats stats;
                compare_cube(*baked, 0, [&](const test::Vec3& n) {
                    bake_safe_point(stop, "budget");  // each truth is a sum over every texel
                    return test::irradiance_over_pi(lit_texels, n);
                }, stats, 3);
                return std::pair{stats_of(stats), baked->gpu_ms};
            },
            progress);
        if (!chosen) return chosen.error();
        budget.settings.irradiance = chosen->first;
        budget.choices.push_back(chosen->second);
    }
    if (base.want_specular) {
        std::vector<Candidate<SpecularSettings>> candidates;
        auto add = [&](SpecularMethod method, uint32_t samples) {
            SpecularSettings s = base.specular;
            s.method = method;
            // automatic's sampled levels are hybrid ones: their sample count is hybrid_sample_count.
            if (samples && method == SpecularMethod::automatic) s.hybrid_sample_count = samples;
            else if (samples) s.sample_count = samples;
            s.min_roughness = std::max(s.min_roughness, rmin);
            const bool sampled = method == SpecularMethod::filtered || method == SpecularMethod::automatic;
            candidates.push_back({specular_method_name(method), sampled ? std::to_string(samples) + " samples" : "", s});
        };
        // Cheapest first (facet-bench sweep, docs/bench/report.md).
        // automatic (hybrid levels) at 64 samples is both cheaper and closer than filtered at
        // 256 (builtin:sky 512 wide, roughness 0.3-1: 48 ms and 0.17% against 76 ms and 16%).
        add(SpecularMethod::mips, 0);
        add(SpecularMethod::automatic, 64);
        add(SpecularMethod::automatic, 128);
        add(SpecularMethod::automatic, 512);
        add(SpecularMethod::filtered, 1024);
        add(SpecularMethod::convolve, 0);
        const test::TexelTable table(e);
        auto chosen = first_meeting<SpecularSettings>(
            candidates, "specular", target,
            [&](const SpecularSettings& s) -> Result<std::pair<double, double>> {
                IblSettings settings = base;
                settings.specular = s;
                auto baked = measure.bake(env, settings, "specular", stop);
                if (!baked) return baked.error();
                ErrorStats stats;
                for (uint32_t m = 1; m < baked->levels; ++m) {
                    const float r = float(m) / float(baked->levels - 1);
                    // Only the levels a lookup in [rmin, rmax] reads (trilinear: its neighbours).
                    const float step = 1.0f / float(baked->levels - 1);
                    if (r < rmin - step || r > rmax + step) continue;
                    compare_cube(*baked, m, [&](const test::Vec3& n) {
                        bake_safe_point(stop, "budget");
                        return test::prefiltered(table, n, r);
                    }, stats, 3);
                }
                return std::pair{stats_of(stats), baked->gpu_ms};
            },
            progress);
        if (!chosen) return chosen.error();
        budget.settings.specular = chosen->first;
        budget.choices.push_back(chosen->second);
    }
    if (base.want_lut) {
        std::vector<Candidate<BrdfLutSettings>> candidates;
        for (auto [size, samples] : {std::pair{32u, 256u}, {64u, 512u}, {64u, 2048u}, {128u, 2048u}}) {
            BrdfLutSettings s = base.lut;
            s.size = size;
            s.sample_count = samples;
            candidates.push_back({"lut " + std::to_string(size), std::to_string(samples) + " samples", s});
        }
        auto chosen = first_meeting<BrdfLutSettings>(
            candidates, "lut", target,
            [&](const BrdfLutSettings& s) -> Result<std::pair<double, double>> {
                IblSettings settings = base;
                settings.lut = s;
                auto baked = measure.bake(env, settings, "lut", stop);
                if (!baked) return baked.error();
                const ErrorStats stats = lut_error(*baked, s.brdf == BrdfModel::gltf);
                return std::pair{stats_of(stats), baked->gpu_ms};
            },
            progress);
        if (!chosen) return chosen.error();
        budget.settings.lut = chosen->first;
        budget.choices.push_back(chosen->second);
    }
    return budget;
} catch (const BakeCancelled&) {
    return Error{kBakeCancelled};
}

}  // namespace facet
