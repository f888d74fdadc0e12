#pragma once
// facet-bench sweep: speed against accuracy. Every IBL method and its parameters
// (irradiance; specular with sample counts; LUT size and samples) and the final image
// (split sum with each specular setting against the reference mode) on a set of
// environments, each with its median GPU time and its error against the brute-force truth
// (facet::reference, reference/ibl_reference.cpp: double precision over every texel): relative RMS, max
// relative error, PSNR; failures (NaN, Inf, negative values, error above bound) marked.
// Writes sweep.csv and sweep.json; scripts/chart.py draws the charts and the report.
#include "cli.h"

namespace facet {

int run_sweep(const cli::Parsed& args);

}  // namespace facet
