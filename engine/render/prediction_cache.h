#pragma once
// The error prediction (render/error_prediction.h) kept in the bake cache beside the bake
// it was made with, so that a session whose bake came from the cache skips the probe too.
// Its key: the bake key (environment, bake settings, the bake's revision), the frame's BRDF
// model, multiscatter and samples, the probe's materials, the methods asked for, the
// prediction's settings and every embedded shader's text (a shader change predicts again).
// With a shader directory (hot reload) or no bake cache, nothing is kept.
#include <span>

#include <facet/core/result.h>
#include "render/error_prediction.h"

namespace facet {

// `from_cache`: set when the prediction was read from the cache.
Result<ShadingPrediction> predict_or_reuse(RenderSession::State& s, std::span<const ShadingMethod> methods,
                                           const PredictionSettings& settings, bool& from_cache);

}  // namespace facet
