#pragma once
// Internal to the glTF loader: KHR_draco_mesh_compression.
#include <tiny_gltf.h>

namespace facet::gltf_detail {

// Every primitive carrying KHR_draco_mesh_compression is decoded (libdraco): each
// attribute the extension maps, and the faces as indices, are written in the component
// types of the primitive's own accessors into new buffers and bufferViews that those
// accessors then read, the extension removed. A stream that does not decode, or counts
// and component counts that disagree with the accessors, is an error naming the primitive.
void decompress_draco(tinygltf::Model& model);

}  // namespace facet::gltf_detail
