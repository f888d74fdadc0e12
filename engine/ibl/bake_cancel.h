#pragma once
// Stopping a bake at a safe point (ibl/bake_settings.h BakeStopFn): the point throws
// BakeCancelled, which unwinds through the engine's owners (GPU objects, temporaries) and
// becomes Error{kBakeCancelled} at the public function that was called. Never leaves
// the engine.
#include <facet/ibl/bake_settings.h>

namespace facet {

struct BakeCancelled {};

inline void bake_safe_point(const BakeStopFn& stop, const char* point) {
    if (stop && stop(point)) throw BakeCancelled{};
}

}  // namespace facet
