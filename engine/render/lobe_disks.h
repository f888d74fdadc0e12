#pragma once
// The extracted lights as a lobe of one roughness tells them apart. A studio's softbox comes
// out of light extraction as a few overlapping caps (its core in pieces, its halo around
// them) so that a near-mirror shows its shape; a rough lobe, many times wider than the
// group, integrates them as it would one cap of the same power, centroid and angular spread,
// and every cap costs each pixel the same arithmetic. The forward pass gives a material
// whose roughness is a constant of its pipeline (no roughness texture, no layer or lobe of
// another roughness) the disks of its roughness (render/forward_pass.cpp).
#include <span>
#include <vector>

#include <facet/ibl/light_extraction.h>

namespace facet {

// The fraction of the lobe's width (GGX's alpha = roughness^2, radians about R) that a group
// of caps merged into one may span (its angular radius, sqrt(2) x the RMS angle of its light
// from its centre). AccuracyTargets holds at this value (docs/accuracy.md).
inline constexpr float kMergedCapLobeFraction = 0.5f;
// And never wider than this (radians; the widest piece light extraction makes is about 12
// degrees): the disks' closed form was checked against sums over caps of 3-11 degrees, and
// merged caps of 13-20 degrees read the studio's rough metals 11-16% too bright.
inline constexpr float kMergedCapMaxRadius = 0.2f;

// Where GGX's alpha is at least this many times a cap's angular radius, the lobe shades the
// cap as a point at its centre carrying the cap's irradiance, corrected for D's curvature
// across it (facet_disk_point_lobe, shaders/facet/shading.glsl): as close to the sum over the
// cap as the closed form there, at about half its arithmetic (docs/accuracy.md). Uncorrected,
// the point is too bright where R hits the centre of a cap k times narrower than the lobe:
// about 1 / (4 k^2) seen from above (2.8% for k = 3), 10% at n.v 0.4.
inline constexpr float kPointCapLobeRatio = 3.0f;

// Whether a lobe of `roughness` shades `disk` as a point (kPointCapLobeRatio).
bool disk_is_point_for_lobe(const DiskLight& disk, float roughness);

// `disks` with the caps that a lobe of `roughness` cannot tell apart merged, greedily from the
// most powerful: a cap joins the first group whose merged cap, and every member's far edge
// from its centre, stay within kMergedCapLobeFraction x alpha and kMergedCapMaxRadius, else
// starts its own. A merged cap keeps the group's power per
// channel (radiance x the cap's solid angle 2 pi (1 - cos theta), as the shaders take it), its
// power-weighted mean direction and its spread (the mean
// squared angle from that direction, each cap counting theta^2 / 2 about its own centre); a
// group of one is the cap itself, untouched. Deterministic; the groups come in the order of
// their first cap in `disks`, so that where nothing merges the result is `disks` as given.
std::vector<DiskLight> disks_for_lobe(std::span<const DiskLight> disks, float roughness);

}  // namespace facet
