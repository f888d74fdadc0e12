#pragma once
// The fitted lookups' tables as scripts/fit_specular_lobes.py writes them
// (specular_lobes_table.cpp, specular_lobes_two_table.cpp): model-major, then roughness row,
// n.v column and lookup.
namespace facet {

inline constexpr int kSpecularLobeModels = 2;   // BrdfModel::gltf, BrdfModel::thesis
inline constexpr int kSpecularLobeRows = 9;     // roughness 0.2 .. 1.0 by 0.1
inline constexpr int kSpecularLobeColumns = 9;  // n.v 0.1 .. 0.9 by 0.1

// (s, roughness, weight) of each lookup: its axis at the fraction s of the angle from n to R.
extern const float kSpecularLobeEntries[kSpecularLobeModels * kSpecularLobeRows * kSpecularLobeColumns * 3][3];

// (s, roughness) of each of two lookups of equal weight (specular_lobes_two_table.cpp, written
// by scripts/fit_specular_lobes.py --two), in the same order.
extern const float kSpecularLobeTwoEntries[kSpecularLobeModels * kSpecularLobeRows * kSpecularLobeColumns * 2][2];

}  // namespace facet
