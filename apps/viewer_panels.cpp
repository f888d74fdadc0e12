#include "viewer_panels.h"

#include <cstring>

#include <imgui.h>

#include "ibl/ibl_bake.h"
#include "scene/builtin_scenes.h"
#include "scene/material_presets.h"

namespace facet {
namespace {

// An editable path: applied when Enter is pressed.
bool path_input(const char* label, std::string& value) {
    char buffer[1024];
    std::strncpy(buffer, value.c_str(), sizeof buffer - 1);
    buffer[sizeof buffer - 1] = '\0';
    if (ImGui::InputText(label, buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue)) {
        value = buffer;
        return true;
    }
    return false;
}

bool choice(const char* label, std::string& value, const std::vector<std::string>& options) {
    bool changed = false;
    if (ImGui::BeginCombo(label, value.empty() ? "(none)" : value.c_str())) {
        for (const std::string& o : options)
            if (ImGui::Selectable(o.empty() ? "(none)" : o.c_str(), o == value)) {
                value = o;
                changed = true;
            }
        ImGui::EndCombo();
    }
    return changed;
}

void pass_table(const char* title, const std::vector<PassTiming>& passes) {
    if (!ImGui::CollapsingHeader(title)) return;
    for (const PassTiming& t : passes) ImGui::Text("%-32s %8.2f ms", t.name.c_str(), t.time_ms);
}

}  // namespace

void draw_panels(ViewerControls& c) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(280, 0), ImGuiCond_Once);
    ImGui::Begin("Model");
    c.reload |= choice("built-in", c.model, {"builtin:spheres", "builtin:sphere"});
    c.reload |= path_input("glTF file", c.model);
    std::vector<std::string> presets = {""};
    for (const MaterialPreset& p : material_presets()) presets.push_back(p.name);
    c.reload |= choice("material", c.preset, presets);
    ImGui::End();

    ImGui::SetNextWindowPos(ImVec2(display.x - 320, 0), ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(320, 0), ImGuiCond_Once);
    ImGui::Begin("Lighting and display");
    c.reload |= choice("environment", c.env, {"builtin:sky", "builtin:white", "none"});
    c.reload |= path_input("HDR file", c.env);
    ImGui::SliderFloat("exposure", &c.display.exposure, 0.01f, 16.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    int tonemap = int(c.display.tonemap);
    const char* tonemaps[] = {"none", "reinhard", "exposure", "aces", "neutral"};
    if (ImGui::Combo("tone mapping", &tonemap, tonemaps, 5)) c.display.tonemap = Tonemap(tonemap);
    bool srgb = c.display.gamma <= 0.0f;
    if (ImGui::Checkbox("sRGB", &srgb)) c.display.gamma = srgb ? 0.0f : 2.2f;
    if (!srgb) ImGui::SliderFloat("gamma", &c.display.gamma, 1.0f, 3.0f);
    ImGui::Checkbox("skybox", &c.skybox);
    int view = int(c.view);
    std::vector<const char*> views;
    for (int v = 0; v <= int(View::prefiltered); ++v) views.push_back(view_name(View(v)));
    if (ImGui::Combo("view", &view, views.data(), int(views.size()))) c.view = View(view);
    ImGui::Separator();
    ImGui::Text("frame %.1f ms", c.frame_ms);
    pass_table("frame passes (GPU)", c.frame_passes);
    pass_table("bake passes (GPU)", c.bake_passes);
    if (!c.status.empty()) ImGui::TextWrapped("%s", c.status.c_str());
    ImGui::End();
}

}  // namespace facet
