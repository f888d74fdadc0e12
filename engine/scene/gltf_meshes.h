#pragma once
// Internal to the glTF loader: mesh primitives into the Scene's vertex and index arrays.
#include <tiny_gltf.h>

#include <cstdint>
#include <string>

#include <facet/scene/gltf_loader.h>
#include <facet/scene/scene.h>
#include "scene/gltf_attributes.h"

namespace facet::gltf_detail {

struct GeometryCount {
    uint64_t vertices = 0, indices = 0;  // list indices
};

// What the scene's primitives will take, from their accessors' declared counts alone,
// checked against the limits before any vertex is read (fails naming what exceeds).
GeometryCount count_geometry(const tinygltf::Model& model, const GltfLimits& limits);

// Appends one primitive to scene.vertices, scene.indices and scene.primitives, and
// returns what nodes may do to it (skin, morph targets). Expects scene.materials already
// converted, since a normal texture decides whether tangents are generated; a primitive
// with no material gets index model.materials.size() and sets needs_default_material.
PrimitiveDeform load_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                    bool& needs_default_material, Scene& scene);

}  // namespace facet::gltf_detail
