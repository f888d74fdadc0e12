#pragma once
// Where each IBL method holds its documented error bound, and the warning it gives
// outside that domain (written into bake.json and printed), instead of silently returning
// a wrong image. The bounds come from facet-bench sweep (docs/bench/report.md) and the
// stability tests:
//   irradiance convolve: <= 2% relative RMS everywhere;
//   riemann (step <= 0.025), sh9, blur, lowmip: <= 5% on skies without compact lights;
//   specular automatic, convolve, filtered (>= 1024 samples): <= 5% everywhere;
//   importance: <= 10% without lights much brighter than their surroundings;
//   mips: a box filter, not a GGX lobe, outside its domain on any non-uniform input.
#include <span>
#include <string>
#include <vector>

#include <facet/ibl/ibl_bake.h>

namespace facet {

struct EnvironmentStats {
    double peak_over_median = 1;        // luminance; infinite when the median is 0
    double compact_light_power = 0;     // share of the power in compact bright regions
    float widest_light_radius = 0;      // radians, over those regions
    bool black = false;                 // no light at all
    uint32_t width = 0, height = 0;
};

// `content` false: the size and `black` only, which is all method_warnings reads where
// method_warnings_read_content is false (the rest costs a median and a light search:
// ~50 ms at 1024x512).
EnvironmentStats environment_stats(std::span<const float> rgba, uint32_t width, uint32_t height,
                                   bool content = true);

// The documented bound in words, e.g. "2% everywhere", for panels and reports.
std::string documented_bound(IrradianceMethod method);
std::string documented_bound(SpecularMethod method, uint32_t sample_count);

// One sentence per method used outside its domain (empty: every method is inside).
std::vector<std::string> method_warnings(const EnvironmentStats& stats, const IblSettings& settings);
// Whether method_warnings reads more of `stats` than the size and `black` for `settings`:
// only for methods whose domain depends on the input's dynamic range or lights.
bool method_warnings_read_content(const IblSettings& settings);

}  // namespace facet
