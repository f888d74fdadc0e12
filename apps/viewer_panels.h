#pragma once
// The viewer's panels, as in the thesis' program: left, the model and its material
// (preset); right, the environment, the display (exposure, tone mapping, gamma), the
// component view, the skybox, and the frame's and the bake's pass times. The panels only
// edit ViewerControls; the main loop applies the changes.
#include <string>
#include <vector>

#include "graph/graph_run.h"
#include "render/forward_renderer.h"
#include "render/views.h"

namespace facet {

struct ViewerControls {
    std::string model, env, preset;  // preset "" = the model's own materials
    View view = View::final_color;
    DisplaySettings display;
    bool skybox = true;
    bool reload = false;  // model, environment or preset changed: load and bake again
    // Shown, not edited.
    std::vector<PassTiming> frame_passes, bake_passes;
    double frame_ms = 0;
    std::string status;
};

void draw_panels(ViewerControls& controls);

}  // namespace facet
