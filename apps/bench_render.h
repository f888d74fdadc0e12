#pragma once
// facet-bench render: frame time of the forward renderer in one process.
#include "cli.h"

namespace facet {

// Renders --frames frames after one warm-up (pipelines compiled, IBL baked once) and
// prints the median GPU time of every pass (timestamp queries), of the frame, and the
// median wall time per frame. Returns the exit status.
int run_render_bench(const cli::Parsed& args);

}  // namespace facet
