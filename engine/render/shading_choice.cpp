#include "render/shading_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <facet/core/result.h>
#include <facet/reference/final_image_accuracy.h>
#include "render/error_prediction.h"
#include "render/prediction_cache.h"
#include "render/render_session_state.h"

namespace facet {

ResolvedShading resolve_shading(const RenderJob& requested) {
    ResolvedShading r{requested, {}};
    ShadingMethod method = requested.shading;
    r.choice.requested = method;
    r.choice.target_error = requested.target_error;
    if (requested.extract_lights || requested.frame.dominant_direction) {
        // The older switches add their part to the method (to the plain split sum when
        // automatic).
        const bool lights = requested.extract_lights || method == ShadingMethod::lights ||
                            method == ShadingMethod::lights_dominant;
        const bool dominant = requested.frame.dominant_direction || method == ShadingMethod::dominant ||
                              method == ShadingMethod::lights_dominant;
        method = lights ? (dominant ? ShadingMethod::lights_dominant : ShadingMethod::lights)
                        : ShadingMethod::dominant;
        r.choice.requested = method;
    }
    if (method == ShadingMethod::automatic) {
        // Extract whatever is bright, wide regions included; finish_shading_choice decides
        // with what was found.
        r.job.extract_lights = requested.env != "none";
        r.job.frame.dominant_direction = true;
        r.choice.method = r.job.extract_lights ? ShadingMethod::lights_dominant : ShadingMethod::dominant;
        r.choice.reason = "no environment";
        return r;
    }
    r.job.extract_lights = method == ShadingMethod::lights || method == ShadingMethod::lights_dominant;
    r.job.frame.dominant_direction = method == ShadingMethod::dominant || method == ShadingMethod::lights_dominant;
    r.choice.method = method;
    r.choice.reason = "requested";
    return r;
}

int shading_cost_rank(ShadingMethod method) {
    switch (method) {
        case ShadingMethod::split_sum: return 0;
        case ShadingMethod::dominant: return 1;
        case ShadingMethod::lights: return 2;
        case ShadingMethod::lights_dominant: return 3;
        case ShadingMethod::automatic: break;
    }
    throw UsageError("shading_cost_rank: automatic is not a method to cost");
}

bool shades_lights(ShadingMethod m) { return m == ShadingMethod::lights || m == ShadingMethod::lights_dominant; }
bool bends_lookup(ShadingMethod m) { return m == ShadingMethod::dominant || m == ShadingMethod::lights_dominant; }

std::vector<ShadingMethod> shading_candidates(const ShadingChoice& choice, size_t extracted_lights) {
    if (choice.requested != ShadingMethod::automatic) return {choice.method};
    if (extracted_lights > 0) return {ShadingMethod::lights, ShadingMethod::lights_dominant};
    return {ShadingMethod::split_sum, ShadingMethod::dominant};
}

std::string percent_text(double fraction) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f%%", 100 * fraction);
    return text;
}

CandidatePick choose_shading(std::span<const ShadingCandidate> candidates, double target_error) {
    if (candidates.empty()) throw UsageError("choose_shading: no candidate");
    // Cheapest first; equal costs keep the order given.
    std::vector<size_t> order(candidates.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return shading_cost_rank(candidates[a].method) < shading_cost_rank(candidates[b].method);
    });
    std::string others;  // every candidate's prediction, for the reason
    for (size_t i : order) {
        others += others.empty() ? "" : ", ";
        others += std::string(shading_method_name(candidates[i].method)) + " " +
                  (std::isnan(candidates[i].predicted_error) ? std::string("not predicted")
                                                              : percent_text(candidates[i].predicted_error));
    }
    const std::string target = percent_text(target_error);
    for (size_t i : order)
        if (candidates[i].predicted_error <= target_error)  // false for NaN
            return {i, "predicted " + percent_text(candidates[i].predicted_error) + " <= target " + target +
                           ", the cheapest within it (" + others + ")"};
    // None within: the most accurate (NaN never is); the cheapest when none was predicted.
    size_t best = order.front();
    for (size_t i : order) {
        const double e = candidates[i].predicted_error, b = candidates[best].predicted_error;
        if (!std::isnan(e) && (std::isnan(b) || e < b)) best = i;
    }
    if (std::isnan(candidates[best].predicted_error))
        return {best, "no prediction, the cheapest (" + others + ")"};
    return {best, "predicted " + percent_text(candidates[best].predicted_error) + " > target " + target +
                      ": no method within it, the most accurate (" + others + ")"};
}

GroupBends choose_group_bends(const std::array<double, 8>& bent, const std::array<double, 8>& two,
                              const std::array<double, 8>& plain, const std::array<bool, 8>& reached,
                              const std::array<bool, 8>& two_by_default, double within, double target) {
    GroupBends out;
    out.two = two_by_default;
    // Along R where the plain lookup is within; the frame's worst with the others bent.
    double worst_bent = -1;  // none measured
    for (size_t g = 0; g < 8; ++g) {
        out.error[g] = bent[g];
        if (!reached[g]) continue;
        if (plain[g] <= within) {  // NaN is never within
            out.bend[g] = false;
            out.error[g] = plain[g];
        }
        if (!std::isnan(out.error[g])) worst_bent = std::max(worst_bent, out.error[g]);
    }
    // Two lookups where they are within, or within the tolerance of that worst where it
    // misses the target (never less than `within`).
    const double bound = worst_bent > target ? std::max(kTwoLookupsTolerance * worst_bent, within) : within;
    out.worst = std::numeric_limits<double>::quiet_NaN();
    for (size_t g = 0; g < 8; ++g) {
        if (!reached[g]) continue;
        if (out.bend[g] && !two_by_default[g] && two[g] <= bound) {
            out.two[g] = true;
            out.error[g] = two[g];
        }
        if (std::isnan(out.error[g])) continue;
        if (out.worst_group < 0 || out.error[g] > out.worst) {
            out.worst = out.error[g];
            out.worst_group = int(g);
        }
    }
    return out;
}

void finish_shading_choice(ResolvedShading& r, size_t lights, double power_fraction) {
    if (r.choice.requested != ShadingMethod::automatic || !r.job.extract_lights) return;
    if (lights == 0) {
        // Nothing compact or bright enough to take out: the split sum with the lookup bent
        // towards n (it halves the rough lobes' error under skies and studios).
        r.choice.method = ShadingMethod::dominant;
        r.choice.reason = "no bright region to extract";
        return;
    }
    r.choice.method = ShadingMethod::lights_dominant;
    r.choice.reason = std::to_string(lights) + " light(s) extracted, " +
                      std::to_string(int(std::lround(100 * power_fraction))) + "% of the power";
}

namespace {

std::string group_label(size_t g) { return test::group_name(test::measure_group(int(g))); }

}  // namespace

Status choose_session_shading(RenderSession::State& s, const SayFn& say) {
    ResolvedShading& r = s.shading;
    const BakeMetadata& m = s.baked->metadata();
    const size_t lights = s.baked->lights().size();
    const bool texels = s.env && !s.env->image.rgba.empty() && s.job.ibl_intensity > 0;
    const bool wanted = r.choice.requested == ShadingMethod::automatic || s.job.predict_named_method;
    // The groups that bend the lookup: as the job says (every group unless a host says
    // otherwise), unless the automatic choice decides below.
    s.frame.dominant_groups = r.job.frame.dominant_groups;
    s.frame.two_lookup_groups = r.job.frame.two_lookup_groups;
    r.choice.unbent_groups.clear();
    r.choice.two_lookup_groups.clear();
    if (!texels || !wanted) {
        finish_shading_choice(r, lights, m.extracted_power_fraction);
    } else {
        const std::vector<ShadingMethod> methods = shading_candidates(r.choice, lights);
        // Candidates come cheapest first: the automatic choice needs no prediction past the
        // first within the target.
        PredictionSettings settings;
        if (r.choice.requested == ShadingMethod::automatic) {
            settings.stop_within = r.choice.target_error;
            settings.two_lookups = true;
        }
        bool from_cache = false;
        auto predicted = predict_or_reuse(s, methods, settings, from_cache);
        if (!predicted) return predicted.error();
        const std::array<bool, 8>& groups = predicted->groups;
        std::vector<ShadingCandidate> candidates;
        for (const MethodPrediction& p : predicted->methods) candidates.push_back({p.method, p.worst});
        size_t chosen = 0;
        if (r.choice.requested == ShadingMethod::automatic) {
            CandidatePick pick = choose_shading(candidates, r.choice.target_error);
            chosen = pick.index;
            r.choice.method = candidates[chosen].method;
            r.choice.reason = (lights ? std::to_string(lights) + " light(s) extracted, " +
                                            std::to_string(int(std::lround(100 * m.extracted_power_fraction))) +
                                            "% of the power; "
                                      : std::string("no bright region to extract; ")) +
                              pick.reason;
        }
        const MethodPrediction& p = predicted->methods[chosen];
        GroupBends bends;  // every group with the chosen method's own lookup
        bends.error = p.group_error;
        bends.worst = p.worst;
        bends.worst_group = p.worst_group;
        if (r.choice.requested == ShadingMethod::automatic && bends_lookup(p.method)) {
            // The same method without the bend, predicted before it (cheaper, so tried first).
            const ShadingMethod plain = p.method == ShadingMethod::lights_dominant ? ShadingMethod::lights
                                                                                    : ShadingMethod::split_sum;
            // Within three quarters of the target, not the target itself: the probe's
            // prediction can be a few tenths of a point off the frame's measure (venice_sunset's
            // [0.2,0.4) metal with lights alone: 2.9% predicted, 3.04% measured at 640x360).
            for (const MethodPrediction& q : predicted->methods)
                if (q.method == plain)
                    bends = choose_group_bends(p.group_error, p.two_lookup_error, q.group_error, groups,
                                               kDefaultTwoLookupGroups, 0.75 * r.choice.target_error,
                                               r.choice.target_error);
            auto list = [](const std::vector<std::string>& labels) {
                std::string text;
                for (const std::string& g : labels) text += (text.empty() ? "" : ", ") + g;
                return text;
            };
            for (size_t g = 0; g < 8; ++g) {
                if (!groups[g]) continue;
                if (!bends.bend[g]) r.choice.unbent_groups.push_back(group_label(g));
                else if (bends.two[g] && !kDefaultTwoLookupGroups[g]) r.choice.two_lookup_groups.push_back(group_label(g));
            }
            if (!r.choice.unbent_groups.empty())
                r.choice.reason += "; along R where " + std::string(shading_method_name(plain)) +
                                   " is within 3/4 of the target: " + list(r.choice.unbent_groups);
            if (!r.choice.two_lookup_groups.empty())
                r.choice.reason += "; two fitted lookups instead of three: " + list(r.choice.two_lookup_groups);
            s.frame.dominant_groups = bends.bend;
            s.frame.two_lookup_groups = bends.two;
        }
        if (bends.worst_group >= 0) {
            r.choice.predicted_error = bends.worst;
            r.choice.predicted_worst_group = group_label(size_t(bends.worst_group));
            for (size_t g = 0; g < 8; ++g)
                if (groups[g] && !std::isnan(bends.error[g]))
                    r.choice.predicted_groups.push_back({group_label(g), bends.error[g]});
        }
        if (from_cache)
            say("predicted errors of " + std::to_string(predicted->methods.size()) + " method(s) from the bake cache");
        else
            say("predicted the error of " + std::to_string(predicted->methods.size()) + " method(s) on a probe in " +
                std::to_string(int(std::lround(1000 * predicted->seconds))) + " ms (truth sums " +
                std::to_string(int(std::lround(1000 * predicted->truth_seconds))) + " ms)");
    }
    r.job.frame.dominant_direction = bends_lookup(r.choice.method);
    r.job.frame.dominant_groups = s.frame.dominant_groups;
    r.job.frame.two_lookup_groups = s.frame.two_lookup_groups;
    s.frame.dominant_direction = r.job.frame.dominant_direction;
    std::string line = "shading: " + std::string(shading_method_name(r.choice.method)) + " (" + r.choice.reason + ")";
    if (r.choice.predicted_error)
        line += "; predicted error " + percent_text(*r.choice.predicted_error) + " in " + r.choice.predicted_worst_group +
                ", target " + percent_text(r.choice.target_error);
    say(line);
    return Ok{};
}

}  // namespace facet
