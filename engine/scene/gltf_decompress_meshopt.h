#pragma once
// Internal to the glTF loader: EXT_meshopt_compression.
#include <tiny_gltf.h>

namespace facet::gltf_detail {

// Every bufferView carrying EXT_meshopt_compression is decoded (libmeshoptimizer) into a
// buffer of its own and pointed at it, the extension then removed from the view: the
// accessors read it as any plain view. The fallback buffer is never read. A field out of
// range or a stream that does not decode is an error naming the bufferView.
void decompress_meshopt(tinygltf::Model& model);

}  // namespace facet::gltf_detail
