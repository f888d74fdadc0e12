#pragma once
// The viewer's panels, as in the thesis' program: left, the model and its material
// (preset); right, the environment, the display (exposure, tone mapping, gamma), the
// component view, the skybox, and the frame's and the bake's pass times. The panels only
// edit ViewerControls; the main loop applies the changes.
#include <optional>
#include <string>
#include <vector>

#include <facet/graph/graph_run.h>
#include <facet/render/forward_renderer.h>
#include <facet/render/shading_method.h>
#include <facet/render/views.h>
#include <facet/ibl/irradiance.h>
#include <facet/ibl/specular.h>
#include <facet/scene/scene.h>

namespace facet {

// A load running in the background (apps/viewer_loader.h), as the panel shows it.
struct LoadShown {
    std::string what, last_line;
    uint32_t passes_done = 0, passes_total = 0;  // of its bake
};

struct ViewerControls {
    std::string model, env, preset;  // preset "" = the model's own materials
    // Material factors for every material (the thesis' sliders); applied without a bake.
    bool override_material = false;
    glm::vec3 albedo{1.0f, 0.78f, 0.34f};
    float metallic = 1.0f, roughness = 0.3f, occlusion = 1.0f;
    // Each input times the model's texture, or the factor alone.
    bool albedo_texture = true, metal_rough_texture = true, occlusion_texture = true;
    bool material_changed = false;
    std::vector<Light> lights;  // every punctual light of the frame
    IrradianceMethod irradiance = IrradianceMethod::convolve;
    SpecularMethod specular = SpecularMethod::automatic;
    View view = View::final_color;
    DisplaySettings display;
    bool skybox = true;
    bool reload = false;  // model, environment or preset changed: load and bake again
    // Shown, not edited.
    std::vector<PassTiming> frame_passes, bake_passes;
    std::vector<std::string> warnings;  // IBL methods outside their domain
    ShadingChoice shading;              // the shading method in use, why, and its predicted error
    double frame_ms = 0;
    std::string status;
    std::optional<LoadShown> loading;
};

void draw_panels(ViewerControls& controls);

}  // namespace facet
