#pragma once
// facet-bench sweep, stage "image": builtin:spheres under one environment, drawn with
// every shading method (split-sum, dominant, lights, lights+dominant, auto) and by the
// reference mode at each of SweepOptions::reference_spp samples per pixel, for each BRDF
// model asked for; each image against the exact integral of its model per roughness x
// metalness group (reference/final_image_accuracy.h). Renderer and truth read the same
// texels (written to a temporary .exr). Time: the median wall time over the runs (taken
// round-robin over the methods) of the frame's passes other than the views ("view ..."),
// or of render_reference.
#include <functional>
#include <string>

#include <facet/core/result.h>
#include <facet/reference/ibl_reference.h>

#include "bench_sweep.h"
#include "facet_bench_options.h"

namespace facet {

class Context;

// `record` gets each row as it is measured. An Error names the environment and the step.
Status sweep_final_image(Context& context, const test::Equirect& texels, const std::string& label,
                         const SweepOptions& options, const std::function<void(SweepRow)>& record);

}  // namespace facet
