#pragma once
// The two BRDF models (design.md, "BRDF models"), one switch through lights, environment
// lighting, extracted lights, the LUT, the reference mode, the views and the tests' truth.
#include <cstdint>
#include <optional>
#include <string_view>

namespace facet {

enum class BrdfModel : uint32_t {
    // glTF 2.0 appendix B: GGX, height-correlated Smith visibility, dielectric =
    // fresnel_mix(ior 1.5, Lambert, specular), metal = conductor_fresnel(baseColor).
    gltf = 0,
    // The thesis' Cook-Torrance: Smith/Schlick-GGX with k = (r+1)^2/8 (lights) and r^2/2
    // (environment), kd = (1 - F)(1 - metalness).
    thesis = 1,
};

// "gltf", "thesis" (header-only: the reference library names models too).
inline const char* brdf_model_name(BrdfModel model) { return model == BrdfModel::thesis ? "thesis" : "gltf"; }
inline std::optional<BrdfModel> parse_brdf_model(std::string_view name) {
    if (name == "gltf") return BrdfModel::gltf;
    if (name == "thesis") return BrdfModel::thesis;
    return std::nullopt;
}

}  // namespace facet
