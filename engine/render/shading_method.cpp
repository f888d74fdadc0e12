#include <facet/render/shading_method.h>

#include <algorithm>

#include <facet/scene/scene.h>

namespace facet {
namespace {
constexpr const char* kShadingMethodNames[] = {"auto", "split-sum", "dominant", "lights", "lights+dominant"};
}  // namespace

const char* shading_method_name(ShadingMethod method) { return kShadingMethodNames[static_cast<int>(method)]; }

std::optional<ShadingMethod> parse_shading_method(std::string_view name) {
    for (int i = 0; i < 5; ++i)
        if (name == kShadingMethodNames[i]) return static_cast<ShadingMethod>(i);
    return std::nullopt;
}

const char* shading_method_names() { return "auto, split-sum, dominant, lights, lights+dominant"; }

}  // namespace facet

namespace facet {

std::array<bool, 8> material_shading_groups(const Material& m) {
    // The bands of facet-bench accuracy's measure (reference/final_image_accuracy.h); the
    // probe's groups (render/error_prediction.cpp) and the session's group labels follow them.
    const auto& band_lo = kShadingGroupBandLow;
    const bool textured = m.metallic_roughness_texture.valid();
    const float hi = std::max(m.roughness, band_lo[0]), lo = std::max(textured ? 0.0f : m.roughness, band_lo[0]);
    const bool metal = m.metallic >= 0.5f, dielectric = m.metallic < 0.5f || textured;
    std::array<bool, 8> groups{};
    for (size_t band = 0; band < band_lo.size(); ++band) {
        const float band_hi = band + 1 < band_lo.size() ? band_lo[band + 1] : 1.0001f;
        if (!(lo < band_hi && hi >= band_lo[band])) continue;
        groups[2 * band] = dielectric;
        groups[2 * band + 1] = metal;
    }
    return groups;
}

}  // namespace facet
