#pragma once
// facet-bench sweep: speed against accuracy. Every IBL method and its parameters
// (irradiance; specular with sample counts; LUT size and samples) on a set of
// environments, each with its median GPU time and its error against the brute-force truth
// (facet::reference, reference/ibl_reference.cpp: double precision over every texel): relative RMS, max
// relative error, PSNR; failures (NaN, Inf, negative values, error above bound) marked.
// Stage "image": the final image of builtin:spheres with every shading method and the
// reference mode at several sample counts, against the exact integral per roughness x
// metalness group (issue 13's measure, bench_sweep_image.h).
// Writes sweep.csv and sweep.json; scripts/chart.py draws the charts and the report.
#include <array>
#include <optional>
#include <string>

#include <facet/reference/final_image_accuracy.h>

#include "cli.h"

namespace facet {

struct SweepRow {
    std::string env, stage, method, params;
    double gpu_ms = 0, rel_rmse = 0, max_rel = 0, psnr = 0;
    bool failed = false;
    std::string failure;
    // Stage "image" only: the BRDF model of frame and truth, the reference mode's samples
    // per pixel (0 for the forward pass), what "auto" picked and why, and every group's error.
    std::string brdf;
    uint32_t samples_per_pixel = 0;
    std::string auto_choice, auto_reason;
    std::optional<test::FinalImageAccuracy> accuracy;
};

int run_sweep(const cli::Parsed& args);

}  // namespace facet
