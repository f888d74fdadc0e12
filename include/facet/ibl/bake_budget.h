#pragma once
// The accuracy budget: given a target error, the bake picks for this environment the
// cheapest irradiance method, specular method (judged only on the levels of the scene's
// roughness range) and LUT that meet it, each measured by baking it and comparing with
// the brute-force truth at sampled directions (ibl_measure.h). The choice and the
// measured error (the prediction for the full bake) go into bake.json.
#include <functional>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/ibl/bake_settings.h>
#include <facet/ibl/ibl_bake.h>

namespace facet {

class Context;
class ProgramCache;

struct BudgetChoice {
    std::string stage, method, params;
    double predicted_error = 0;  // relative RMS against the truth at the sampled directions
    double time_ms = 0;          // wall time of the stage's passes when measured
    bool met = false;            // false: nothing met the target; the most accurate is used
};

struct Budget {
    double target = 0.02;
    float roughness_min = 0.0f, roughness_max = 1.0f;
    IblSettings settings;  // the base settings with the chosen methods
    std::vector<BudgetChoice> choices;
};

// `env` must hold its texels (materialize_environment). Candidates are tried from the
// cheapest (by facet-bench sweep's timings) until one meets the target. `progress` gets
// a line per candidate measured; `stop` is asked between passes ("pass") and inside the
// brute-force sums ("budget"): when it says stop, the Error is_cancelled(). `whole`: where
// lights were taken out of `env`, the whole environment, which the irradiance is baked from
// (SpecularSplit), so that its method is judged there.
Result<Budget> choose_within_budget(Context& context, ProgramCache& programs, const EnvironmentSource& env,
                                    const IblSettings& base, double target, float roughness_min,
                                    float roughness_max, const BakeProgressFn& progress = {},
                                    const BakeStopFn& stop = {}, const EnvironmentSource* whole = nullptr);

}  // namespace facet
