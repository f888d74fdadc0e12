#pragma once
// glTF 2.0 files (.gltf with external or data-URI resources, and .glb) into a Scene.
#include <string>

#include "core/result.h"
#include "scene/scene.h"

namespace facet {

// Loads the default scene (else scene 0, else every root node): the node hierarchy
// flattened into instances, every mesh, material, sampler and image (decoded to
// RGBA8), KHR_lights_punctual lights and cameras placed by their nodes. Missing
// normals are generated, and missing tangents where a material has a normal texture.
// Any malformed input gives Error{"<path>: <reason>"}; nothing is read out of bounds.
Result<Scene> load_gltf(const std::string& path);

}  // namespace facet
