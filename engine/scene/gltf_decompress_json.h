#pragma once
// Internal to the glTF loader: what compressed files (and WebP data uris) do that
// tinygltf 2.7 refuses, rewritten in the JSON before it parses the file.
//
// - EXT_meshopt_compression's fallback buffer has a byteLength and usually no uri (its
//   bytes exist only compressed). tinygltf refuses a buffer without uri in a .gltf, and
//   in a .glb copies the BIN chunk for it (or refuses when byteLength is larger). Facet
//   never reads it (each view on it is decoded from the compressed buffer), so it is
//   given a 1-byte data uri (in place of its file too, when it has one).
// - KHR_draco_mesh_compression's accessors need no bufferView, but tinygltf refuses an
//   indices accessor without one ("accessor[N] invalid bufferView"). Such an accessor
//   is given the primitive's Draco bufferView; the decoder points it at the decoded
//   indices before anything reads it.
// - EXT_texture_webp's images may be data uris of type image/webp, which tinygltf does
//   not know (it takes them for file names): they are given type
//   application/octet-stream, whose bytes it hands to the loader as any image's.
#include <cstdint>
#include <vector>

namespace facet::gltf_detail {

// When `file` (a .gltf's JSON, or a .glb when `glb`) needs either rewrite, writes the
// rewritten file to `out` and returns true; otherwise (nothing to do, or JSON it cannot
// follow: tinygltf then reports the file as it is) returns false and leaves `out` alone.
bool prepare_compressed_json(const std::vector<uint8_t>& file, bool glb, std::vector<uint8_t>& out);

}  // namespace facet::gltf_detail
