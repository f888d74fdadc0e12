// The automatic shading choice as a pure function (render/shading_choice.h): candidates
// with their predicted worst-group errors -> the cheapest within the target, else the
// most accurate with a reason saying so; and the candidates a bake serves.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <facet/reference/final_image_accuracy.h>
#include <facet/render/shading_method.h>
#include <facet/scene/scene.h>
#include "render/shading_choice.h"

namespace facet {
namespace {

using M = ShadingMethod;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

TEST(ShadingChoice, CostOrderIsSplitSumDominantLightsBoth) {
    EXPECT_LT(shading_cost_rank(M::split_sum), shading_cost_rank(M::dominant));
    EXPECT_LT(shading_cost_rank(M::dominant), shading_cost_rank(M::lights));
    EXPECT_LT(shading_cost_rank(M::lights), shading_cost_rank(M::lights_dominant));
    EXPECT_THROW(shading_cost_rank(M::automatic), UsageError);
}

// Per group, once a bending method is chosen: a reached group whose plain lookup is within
// the threshold reads along R and carries the plain lookup's error; unreached, unmeasured
// (NaN) or over-threshold groups bend; the worst is over the reached groups' chosen errors.
TEST(ShadingChoice, GroupsWithinTheTargetReadAlongR) {
    const std::array<double, 8> bent = {0.010, 0.020, 0.011, 0.021, 0.012, 0.022, 0.013, 0.023};
    const std::array<double, 8> plain = {0.015, 0.060, 0.0225, 0.040, nan, 0.010, 0.001, 0.002};
    std::array<bool, 8> reached;
    reached.fill(true);
    reached[7] = false;
    std::array<double, 8> two_unmeasured;
    two_unmeasured.fill(nan);
    const std::array<bool, 8> no_two{};
    const GroupBends b = choose_group_bends(bent, two_unmeasured, plain, reached, no_two, 0.0225, 0.03);
    const std::array<bool, 8> expected = {false, true, false, true, true, false, false, true};
    EXPECT_EQ(b.bend, expected);
    EXPECT_DOUBLE_EQ(b.error[0], 0.015);  // along R: the plain lookup's
    EXPECT_DOUBLE_EQ(b.error[1], 0.020);  // bent: the bent lookup's
    EXPECT_DOUBLE_EQ(b.error[2], 0.0225); // exactly at the threshold is within
    EXPECT_DOUBLE_EQ(b.error[4], 0.012);  // NaN is never within
    EXPECT_DOUBLE_EQ(b.worst, 0.0225);    // group 7 is not reached: its 0.023 does not count
    EXPECT_EQ(b.worst_group, 2);
    // Nothing measured: no worst.
    std::array<double, 8> none;
    none.fill(nan);
    const GroupBends n = choose_group_bends(none, none, none, reached, no_two, 0.03, 0.04);
    EXPECT_TRUE(std::isnan(n.worst));
    EXPECT_EQ(n.worst_group, -1);
    // Deterministic.
    EXPECT_EQ(choose_group_bends(bent, two_unmeasured, plain, reached, no_two, 0.0225, 0.03).bend, b.bend);
    EXPECT_EQ(b.two, no_two) << "two lookups only where predicted";
}

// Two fitted lookups instead of three in a bending group: where the group's default says so
// (the bands from 0.6, whose predictions are the two lookups' already), where two are within
// the threshold, or, where the frame's worst with three misses the target, where two are
// within kTwoLookupsTolerance of that worst; never in along R's groups, never unmeasured.
TEST(ShadingChoice, TwoLookupsWhereTheyAreWithinOrTheTargetIsOutOfReach) {
    const double within = 0.0225, target = 0.03;
    std::array<bool, 8> reached;
    reached.fill(true);
    const std::array<bool, 8> by_default = {false, false, false, false, false, true, false, false};
    // In reach (worst with three 2.9%): two only within the threshold.
    //                                  0      1      2      3      4      5      6      7
    std::array<double, 8> three = {0.020, 0.029, 0.010, 0.010, 0.010, 0.028, 0.010, nan};
    std::array<double, 8> two = {0.022, 0.031, 0.023, nan, 0.010, 0.060, 0.010, 0.010};
    const std::array<double, 8> plain = {0.050, 0.050, 0.050, 0.050, 0.050, 0.050, 0.001, 0.050};
    const GroupBends a = choose_group_bends(three, two, plain, reached, by_default, within, target);
    const std::array<bool, 8> in_reach = {true, false, false, false, true, true, false, true};
    EXPECT_EQ(a.two, in_reach);
    EXPECT_DOUBLE_EQ(a.error[0], 0.022);
    EXPECT_DOUBLE_EQ(a.error[5], 0.028) << "the default's prediction is the bent one";
    EXPECT_FALSE(a.bend[6]) << "along R";
    EXPECT_DOUBLE_EQ(a.error[6], 0.001);
    EXPECT_DOUBLE_EQ(a.worst, 0.029);
    EXPECT_EQ(a.worst_group, 1);
    // Out of reach (group 2 at 4.0% with three): two within 4.6% (15% over it).
    three[2] = 0.040;
    two = {0.022, 0.031, 0.045, 0.047, nan, 0.060, 0.010, 0.046};
    const GroupBends b = choose_group_bends(three, two, plain, reached, by_default, within, target);
    const std::array<bool, 8> out_of_reach = {true, true, true, false, false, true, false, true};
    EXPECT_EQ(b.two, out_of_reach);
    EXPECT_DOUBLE_EQ(b.error[1], 0.031) << "within target with three, but the frame misses it anyway";
    EXPECT_DOUBLE_EQ(b.error[3], 0.010) << "4.7% is more than 15% over 4.0%: three";
    EXPECT_DOUBLE_EQ(b.worst, 0.046);
    EXPECT_EQ(b.worst_group, 7);
    // An unreached group keeps its default, never counts, and does not set the worst.
    reached[2] = false;
    const GroupBends u = choose_group_bends(three, two, plain, reached, by_default, within, target);
    EXPECT_FALSE(u.two[2]);
    EXPECT_TRUE(u.bend[2]);
    const std::array<bool, 8> in_reach_again = {true, false, false, false, false, true, false, false};
    EXPECT_EQ(u.two, in_reach_again) << "without group 2 the frame is in reach again: two only within the threshold";
}

// The engine's roughness bands are the measure's (reference/final_image_accuracy.h).
TEST(ShadingChoice, GroupBandsAreTheMeasures) {
    for (int g = 0; g < 8; ++g) {
        const test::GroupError e = test::measure_group(g);
        EXPECT_FLOAT_EQ(float(e.roughness_min), kShadingGroupBandLow[size_t(g / 2)]) << "group " << g;
        if (g / 2 + 1 < 4) EXPECT_FLOAT_EQ(float(e.roughness_max), kShadingGroupBandLow[size_t(g / 2 + 1)]) << "group " << g;
    }
}

// The groups a material can fall in: its band and class; a metallic-roughness texture
// scales both down, so every band up to its factor and the dielectric class too; under 0.2
// the first band.
TEST(ShadingChoice, MaterialGroupsFollowTheFactorsAndTheirTexture) {
    Material m;
    m.roughness = 0.5f;
    m.metallic = 1.0f;
    std::array<bool, 8> expected{};
    expected[3] = true;  // [0.4,0.6) metal
    EXPECT_EQ(material_shading_groups(m), expected);
    m.metallic = 0.49f;
    expected = {};
    expected[2] = true;  // [0.4,0.6) dielectric
    EXPECT_EQ(material_shading_groups(m), expected);
    m.roughness = 0.05f;
    expected = {};
    expected[0] = true;  // under 0.2: the first band
    EXPECT_EQ(material_shading_groups(m), expected);
    m.roughness = 1.0f;
    expected = {};
    expected[6] = true;  // 1 is in [0.8,1.0]
    EXPECT_EQ(material_shading_groups(m), expected);
    m.roughness = 0.7f;
    m.metallic = 0.5f;
    m.metallic_roughness_texture.image = 0;
    expected = {true, true, true, true, true, true, false, false};  // every band up to 0.7, both classes
    EXPECT_EQ(material_shading_groups(m), expected);
}

TEST(ShadingChoice, CheapestWithinTheTargetWins) {
    // Given out of cost order: the order of the list must not matter.
    const std::vector<ShadingCandidate> c = {{M::dominant, 0.021}, {M::split_sum, 0.029}};
    const CandidatePick pick = choose_shading(c, 0.03);
    EXPECT_EQ(c[pick.index].method, M::split_sum);
    EXPECT_NE(pick.reason.find("predicted 2.9% <= target 3.0%"), std::string::npos) << pick.reason;
    // A tighter target moves to the more accurate, dearer one.
    EXPECT_EQ(c[choose_shading(c, 0.025).index].method, M::dominant);
}

TEST(ShadingChoice, ExactlyAtTheTargetIsWithin) {
    const std::vector<ShadingCandidate> c = {{M::lights, 0.03}, {M::lights_dominant, 0.01}};
    EXPECT_EQ(c[choose_shading(c, 0.03).index].method, M::lights);
}

TEST(ShadingChoice, NoneWithinGivesTheMostAccurateAndSaysSo) {
    const std::vector<ShadingCandidate> c = {{M::lights, 0.081}, {M::lights_dominant, 0.063}};
    const CandidatePick pick = choose_shading(c, 0.03);
    EXPECT_EQ(c[pick.index].method, M::lights_dominant);
    EXPECT_NE(pick.reason.find("predicted 6.3% > target 3.0%"), std::string::npos) << pick.reason;
    // Equal errors: the cheaper one.
    const std::vector<ShadingCandidate> tie = {{M::lights_dominant, 0.05}, {M::lights, 0.05}};
    EXPECT_EQ(tie[choose_shading(tie, 0.03).index].method, M::lights);
}

TEST(ShadingChoice, UnpredictedOrInfiniteNeverCountsAsWithin) {
    const double inf = std::numeric_limits<double>::infinity();
    const std::vector<ShadingCandidate> c = {{M::split_sum, nan}, {M::dominant, 0.02}};
    EXPECT_EQ(c[choose_shading(c, 0.03).index].method, M::dominant);
    const std::vector<ShadingCandidate> bad = {{M::split_sum, inf}, {M::dominant, 0.5}};
    EXPECT_EQ(bad[choose_shading(bad, 0.03).index].method, M::dominant);
    // Nothing predicted at all: the cheapest, said.
    const std::vector<ShadingCandidate> none = {{M::dominant, nan}, {M::split_sum, nan}};
    const CandidatePick pick = choose_shading(none, 0.03);
    EXPECT_EQ(none[pick.index].method, M::split_sum);
    EXPECT_NE(pick.reason.find("no prediction"), std::string::npos) << pick.reason;
    EXPECT_THROW(choose_shading({}, 0.03), UsageError);
}

TEST(ShadingChoice, DeterministicForTheSameInput) {
    const std::vector<ShadingCandidate> c = {{M::lights, 0.0301}, {M::lights_dominant, 0.0299}};
    const CandidatePick a = choose_shading(c, 0.03), b = choose_shading(c, 0.03);
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.reason, b.reason);
    EXPECT_EQ(c[a.index].method, M::lights_dominant);
}

TEST(ShadingChoice, CandidatesAreWhatTheBakeServes) {
    ShadingChoice automatic;
    automatic.requested = M::automatic;
    EXPECT_EQ(shading_candidates(automatic, 2), (std::vector<M>{M::lights, M::lights_dominant}));
    EXPECT_EQ(shading_candidates(automatic, 0), (std::vector<M>{M::split_sum, M::dominant}));
    ShadingChoice explicit_choice;
    explicit_choice.requested = explicit_choice.method = M::dominant;
    EXPECT_EQ(shading_candidates(explicit_choice, 3), std::vector<M>{M::dominant});
}

TEST(ShadingChoice, ResolveCarriesTheTarget) {
    RenderJob job;
    job.target_error = 0.05;
    EXPECT_EQ(resolve_shading(job).choice.target_error, 0.05);
    EXPECT_TRUE(resolve_shading(job).job.extract_lights);  // automatic: the extraction bake
}

}  // namespace
}  // namespace facet
