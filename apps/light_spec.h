#pragma once
// --light SPEC, the lights facet-render, facet-viewer and facet-bench take on the
// command line (in the units of KHR_lights_punctual).
#include <string>

#include <facet/core/result.h>
#include <facet/scene/scene.h>

namespace facet {

// "directional dir=X,Y,Z [color=R,G,B] [intensity=LUX]", "point pos=X,Y,Z [range=M]
// [intensity=CD] ...", "spot pos=... dir=... [inner=DEG] [outer=DEG] ...".
Result<Light> parse_light(const std::string& text);

}  // namespace facet
