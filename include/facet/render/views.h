#pragma once
// The images the forward pass can write (design.md's AOVs): the final colour, the
// surface (normal, position, material inputs) and the thesis' shading components.
// Numbers match shaders/render/views.glsl.
#include <optional>
#include <string>
#include <vector>

namespace facet {

enum class View : int {
    final_color = 0,
    normal = 1,       // world space, unit
    position = 2,     // world space, metres
    basecolor = 3,
    metallic = 4,     // alpha 0 marks an unlit surface (KHR_materials_unlit, points, lines)
    roughness = 5,
    occlusion = 6,
    emissive = 7,
    D = 8,            // D_GGX for the first light's half vector (h = n without lights)
    F = 9,            // F_Schlick for the same h
    G = 10,           // G_Smith (Schlick-GGX) for the first light (mirror direction without)
    diffuse = 11,     // radiance from the diffuse lobe (lights + IBL)
    specular = 12,    // radiance from the specular lobe (lights + IBL)
    irradiance = 13,  // irradiance cube at n (E/pi)
    prefiltered = 14, // prefiltered specular at R
    specular_f0 = 15, // F0 (rgb) and the specular weight (a), for the reference renderer
    clearcoat = 16,   // KHR_materials_clearcoat's weight (r) and roughness (g)
    clearcoat_normal = 17,  // the clear coat's unit normal, world space
    iridescence = 18,       // KHR_materials_iridescence's weight (r), film ior (g), thickness in nm (b)
    anisotropy = 19,        // KHR_materials_anisotropy's direction (rgb, world) and strength (a)
    sheen = 20,             // KHR_materials_sheen's colour (rgb, linear) and roughness (a)
    transmission = 21,      // KHR_materials_transmission's weight (r), its lobe's roughness (g), the volume's thickness (b)
};

const char* view_name(View view);
// Whether the view shows the surface itself (what the material gives at the fragment) rather
// than its light: normal to transmission but D, F, G and the lobes' radiance. The forward pass
// writes those before any light is looked at (FACET_SURFACE_VIEW in render/forward.frag), with
// none of the lighting in their pipelines.
bool view_of_surface(View view);
std::optional<View> parse_view(const std::string& name);
// "normal,position,..." (every view but the final colour).
std::string view_names();
// A comma-separated list; the error names the unknown entry.
std::optional<std::vector<View>> parse_view_list(const std::string& list, std::string* error);

}  // namespace facet
