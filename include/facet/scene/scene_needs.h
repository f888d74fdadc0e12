#pragma once
// What a scene's materials need from image-based lighting, so that the bake models no
// more than that: the smallest roughness any surface can have (textures scanned) and
// whether any surface has a diffuse part.
#include <facet/scene/scene.h>

namespace facet {

struct SceneNeeds {
    float min_roughness = 0.0f;  // over every material, texture texels included
    bool diffuse = true;         // some surface is not a pure metal, or has a sheen (both read the irradiance)
};

SceneNeeds scene_needs(const Scene& scene);

}  // namespace facet
