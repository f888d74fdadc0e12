#include "viewer_panels.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include <imgui.h>

#include <facet/ibl/ibl_bake.h>
#include <facet/ibl/method_domain.h>
#include <facet/scene/builtin_scenes.h>
#include <facet/scene/material_presets.h>

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
    c.reload |= choice("preset", c.preset, presets);
    ImGui::Separator();
    c.material_changed |= ImGui::Checkbox("override the materials", &c.override_material);
    if (c.override_material) {
        c.material_changed |= ImGui::ColorEdit3("albedo", &c.albedo.x);
        c.material_changed |= ImGui::Checkbox("x albedo texture", &c.albedo_texture);
        c.material_changed |= ImGui::SliderFloat("metalness", &c.metallic, 0.0f, 1.0f);
        c.material_changed |= ImGui::SliderFloat("roughness", &c.roughness, 0.0f, 1.0f);
        c.material_changed |= ImGui::Checkbox("x metallic-roughness texture", &c.metal_rough_texture);
        c.material_changed |= ImGui::SliderFloat("AO", &c.occlusion, 0.0f, 1.0f);
        c.material_changed |= ImGui::Checkbox("x occlusion texture", &c.occlusion_texture);
    }
    ImGui::Separator();
    ImGui::Text("lights");
    const char* types[] = {"directional", "point", "spot"};
    for (size_t i = 0; i < c.lights.size(); ++i) {
        Light& l = c.lights[i];
        ImGui::PushID(int(i));
        int type = int(l.type);
        if (ImGui::Combo("type", &type, types, 3)) l.type = LightType(type);
        ImGui::ColorEdit3("colour", &l.color.x);
        ImGui::SliderFloat(l.type == LightType::directional ? "lux" : "candela", &l.intensity, 0.0f, 1000.0f, "%.2f",
                           ImGuiSliderFlags_Logarithmic);
        if (l.type != LightType::point && ImGui::SliderFloat3("direction", &l.direction.x, -1.0f, 1.0f) &&
            glm::length(l.direction) < 1e-3f)
            l.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        if (l.type != LightType::directional) ImGui::DragFloat3("position", &l.position.x, 0.05f);
        bool removed = ImGui::Button("remove");
        ImGui::PopID();
        if (removed) {
            c.lights.erase(c.lights.begin() + long(i));
            break;
        }
    }
    if (ImGui::Button("add a light")) {
        Light l;
        l.direction = glm::normalize(glm::vec3(-1.0f, -1.0f, -1.0f));
        l.intensity = 3.0f;
        c.lights.push_back(l);
    }
    ImGui::End();

    ImGui::SetNextWindowPos(ImVec2(display.x - 320, 0), ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(320, 0), ImGuiCond_Once);
    ImGui::Begin("Lighting and display");
    c.reload |= choice("environment", c.env, {"builtin:sky", "builtin:white", "none"});
    c.reload |= path_input("HDR file", c.env);
    int irradiance = int(c.irradiance), specular = int(c.specular);
    const char* irradiance_methods[] = {"convolve", "riemann", "sh9", "blur", "lowmip"};
    const char* specular_methods[] = {"automatic", "importance", "filtered", "convolve", "mips", "hybrid"};
    if (ImGui::Combo("irradiance", &irradiance, irradiance_methods, 5)) {
        c.irradiance = IrradianceMethod(irradiance);
        c.reload = true;
    }
    if (ImGui::Combo("specular", &specular, specular_methods, 6)) {
        c.specular = SpecularMethod(specular);
        c.reload = true;
    }
    ImGui::TextWrapped("irradiance error: %s", documented_bound(c.irradiance).c_str());
    ImGui::TextWrapped("specular error: %s", documented_bound(c.specular, 1024).c_str());
    if (c.loading) {
        // The window keeps drawing the current scene meanwhile.
        const LoadShown& l = *c.loading;
        ImGui::TextWrapped("loading %s", l.what.c_str());
        char overlay[64];
        if (l.passes_total > 0)
            std::snprintf(overlay, sizeof overlay, "bake: %u / %u passes", l.passes_done, l.passes_total);
        else
            std::snprintf(overlay, sizeof overlay, "loading");
        ImGui::ProgressBar(l.passes_total ? float(l.passes_done) / float(l.passes_total) : 0.0f, ImVec2(-1.0f, 0.0f),
                           overlay);
        ImGui::TextDisabled("%s", l.last_line.c_str());
    }
    double bake_ms = 0;
    for (const PassTiming& t : c.bake_passes) bake_ms += t.time_ms;
    ImGui::Text("bake %.0f ms GPU", bake_ms);
    ImGui::TextWrapped("shading: %s (%s)", shading_method_name(c.shading.method), c.shading.reason.c_str());
    if (c.shading.predicted_error) {
        // The probe's prediction of issue 13's measure (render/shading_method.h), worst group first.
        const bool within = *c.shading.predicted_error <= c.shading.target_error;
        ImGui::TextColored(within ? ImVec4(0.6f, 1.0f, 0.6f, 1.0f) : ImVec4(1.0f, 0.7f, 0.3f, 1.0f),
                           "predicted error %.1f%% (target %.1f%%), worst: %s", 100 * *c.shading.predicted_error,
                           100 * c.shading.target_error, c.shading.predicted_worst_group.c_str());
        for (const GroupErrorPrediction& g : c.shading.predicted_groups) {
            auto in = [&](const std::vector<std::string>& list) {
                return std::find(list.begin(), list.end(), g.group) != list.end();
            };
            const char* lookup = in(c.shading.unbent_groups)       ? "  (along R)"
                                 : in(c.shading.two_lookup_groups) ? "  (two lookups)"
                                                                   : "";
            ImGui::Text("  %-30s %5.1f%%%s", g.group.c_str(), 100 * g.error, lookup);
        }
    } else {
        ImGui::TextDisabled("predicted error: none (no environment texels to compare with)");
    }
    for (const std::string& w : c.warnings) ImGui::TextColored(ImVec4(1.0f, 0.7f, 0.3f, 1.0f), "%s", w.c_str());
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
    if (!c.status.empty()) {
        const bool error = c.status.find("error") != std::string::npos;
        ImGui::PushStyleColor(ImGuiCol_Text, error ? ImVec4(1.0f, 0.4f, 0.4f, 1.0f) : ImVec4(0.7f, 0.9f, 0.7f, 1.0f));
        ImGui::TextWrapped("%s", c.status.c_str());
        ImGui::PopStyleColor();
    }
    ImGui::End();
}

}  // namespace facet
