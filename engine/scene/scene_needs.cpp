#include <facet/scene/scene_needs.h>

#include <algorithm>
#include <cmath>

namespace facet {
namespace {

// Smallest value of one channel over an image (1 when the image is missing).
float channel_min(const Scene& scene, const TextureRef& ref, int channel) {
    if (!ref.valid() || size_t(ref.image) >= scene.images.size()) return 1.0f;
    const TextureImage& image = scene.images[size_t(ref.image)];
    uint8_t low = 255;
    for (size_t i = size_t(channel); i < image.rgba.size(); i += 4) low = std::min(low, image.rgba[i]);
    return float(low) / 255.0f;
}

}  // namespace

SceneNeeds scene_needs(const Scene& scene) {
    SceneNeeds needs;
    needs.min_roughness = 1.0f;
    needs.diffuse = false;
    for (const Material& m : scene.materials) {
        const float roughness_scale = channel_min(scene, m.metallic_roughness_texture, 1);  // G = roughness
        needs.min_roughness = std::min(needs.min_roughness, std::clamp(m.roughness, 0.0f, 1.0f) * roughness_scale);
        // Metalness is factor x B; the diffuse lobe exists wherever it is below 1.
        const float metal_min = m.metallic * channel_min(scene, m.metallic_roughness_texture, 2);
        if (metal_min < 1.0f) needs.diffuse = true;
        // A sheen layer reads the irradiance cube (facet/sheen.glsl: its lobe is wide).
        if (m.has_sheen()) needs.diffuse = true;
        // A clear coat reads the levels of its own roughness.
        if (m.clearcoat > 0.0f)
            needs.min_roughness = std::min(needs.min_roughness, std::clamp(m.clearcoat_roughness, 0.0f, 1.0f) *
                                                                    channel_min(scene, m.clearcoat_roughness_texture, 1));
        // A transmission reads the levels of its lobe's roughness, the surface's times
        // clamp(2 ior - 2, 0, 1) (facet/transmission.glsl; ior from the dielectric's F0).
        if (m.has_transmission()) {
            const float f = std::sqrt(std::clamp(m.dielectric_f0, 0.0f, 0.99f)), ior = (1.0f + f) / (1.0f - f);
            needs.min_roughness = std::min(needs.min_roughness, std::clamp(m.roughness, 0.0f, 1.0f) * roughness_scale *
                                                                    std::clamp(2.0f * ior - 2.0f, 0.0f, 1.0f));
        }
    }
    if (scene.materials.empty()) needs.min_roughness = 0.0f;
    return needs;
}

}  // namespace facet
