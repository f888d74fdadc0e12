#pragma once
// Internal to the glTF loader: mesh primitives into the Scene's vertex and index arrays.
#include <tiny_gltf.h>

#include <string>

#include "scene/scene.h"

namespace facet::gltf_detail {

// Appends one primitive (triangles only) to scene.vertices, scene.indices and
// scene.primitives. Expects scene.materials already converted, since a normal texture
// decides whether tangents are generated; a primitive with no material gets index
// model.materials.size() and sets needs_default_material.
void load_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                    bool& needs_default_material, Scene& scene);

}  // namespace facet::gltf_detail
