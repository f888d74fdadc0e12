#pragma once
// The session's shading method resolved from the job (render/render_job.h): an explicit
// --shading, the older switches (extract_lights, frame.dominant_direction), or the
// automatic choice, made in two steps: before the bake (extract lights, wide regions
// included) and after it, among the methods that bake serves, by their predicted error
// (render/error_prediction.h) and cost.
#include <array>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/render/render_job.h>
#include <facet/render/shading_method.h>

namespace facet {

struct ResolvedShading {
    RenderJob job;  // the request with extract_lights and frame.dominant_direction set
    ShadingChoice choice;
};

ResolvedShading resolve_shading(const RenderJob& requested);

// The forward pass's cost rank of a method: split_sum 0 < dominant 1 < lights 2 <
// lights_dominant 3 (issue 13's order; automatic has none: UsageError).
int shading_cost_rank(ShadingMethod method);
// Whether a method shades extracted lights / bends the lookup towards n.
bool shades_lights(ShadingMethod method);
bool bends_lookup(ShadingMethod method);

// The methods a bake serves: an extraction that took lights out leaves a residual map,
// which only the methods shading those lights complete; any other bake serves the two
// split-sum lookups. An explicit request is its own only candidate. Cheapest first.
std::vector<ShadingMethod> shading_candidates(const ShadingChoice& choice, size_t extracted_lights);

struct ShadingCandidate {
    ShadingMethod method = ShadingMethod::split_sum;
    double predicted_error = 0;  // worst group, a fraction; NaN: not predicted (never within)
};
struct CandidatePick {
    size_t index = 0;  // into the candidates
    std::string reason;
};
// The cheapest candidate whose predicted error is within `target_error`; when none is, the
// most accurate one (the cheapest of equals), the reason saying so ("predicted 6.3% >
// target 3%"). A pure function of its inputs (the choice is deterministic). Empty
// `candidates`: UsageError.
CandidatePick choose_shading(std::span<const ShadingCandidate> candidates, double target_error);

// Where the frame's worst group misses the target with three fitted lookups, every bending
// group takes two where they are predicted within this factor of that worst: the frame misses
// its target either way, its worst group grows by at most this factor, and the two cost one
// table read and one cube read less (a tenth of DamagedHelmet's frame under the rooms, where
// a textured material reads two only if all its groups do; docs/accuracy.md, "Two lookups
// where the target is out of reach").
inline constexpr double kTwoLookupsTolerance = 1.15;

// The lookup per group, once a bending method (lights_dominant, dominant) is chosen
// automatically, from each group's predicted error with the same method without the bend
// (`plain`: lights, split_sum), with two fitted lookups (`two`) and with three (`bent`):
// a group reached by the probe (`reached`) reads along R where `plain` is within `within`
// (the session passes three quarters of its target, a margin for the probe's prediction),
// which costs a third of a split-sum frame less; else it bends, with two lookups where
// `two_by_default` (kDefaultTwoLookupGroups, render/specular_lobes.h: the probe's lookups there
// are two already), where `two` is within `within`, or, where the reached groups' worst
// with three (and R where chosen) is over `target`, where `two` is within
// kTwoLookupsTolerance of that worst; else with three. `error` is each group's predicted
// error with the lookups it uses, `worst` and `worst_group` their largest over the reached
// groups (NaN and -1 when none was measured). NaN is never within anything. A pure function
// (the choice is deterministic).
struct GroupBends {
    std::array<bool, 8> bend{true, true, true, true, true, true, true, true};
    std::array<bool, 8> two{};  // of the bending groups, those reading two lookups
    std::array<double, 8> error{};
    double worst = 0;
    int worst_group = -1;
};
GroupBends choose_group_bends(const std::array<double, 8>& bent, const std::array<double, 8>& two,
                              const std::array<double, 8>& plain, const std::array<bool, 8>& reached,
                              const std::array<bool, 8>& two_by_default, double within, double target);

// Without a prediction (a saved bake, no environment texels): after the bake, `lights`
// disks found holding `power_fraction` of the environment's power.
void finish_shading_choice(ResolvedShading& shading, size_t lights, double power_fraction);

// After the session's bake (render/render_session_state.h): predicts the errors of the
// methods the bake serves where the environment's texels are at hand, chooses (an
// automatic request) or keeps (an explicit one) the method, records both in s.shading
// and sets the frame's lookup and disk lights to match. Device failures are returned.
using SayFn = std::function<void(const std::string&)>;
Status choose_session_shading(RenderSession::State& s, const SayFn& say);

// "1.4%"
std::string percent_text(double fraction);

}  // namespace facet
