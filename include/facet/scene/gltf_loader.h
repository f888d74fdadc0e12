#pragma once
// glTF 2.0 files (.gltf with external or data-URI resources, and .glb) into a Scene.
#include <cstdint>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/scene/scene.h>

namespace facet {

// A model's memory budget (README, "Large inputs"). Each size is checked before the
// data it describes is read or decoded: file sizes before reading them, vertex and
// index counts from the accessors before any vertex is converted, texture sizes from
// the PNG/JPEG headers before decoding. A model beyond a limit is refused with an error
// naming the file, what exceeds and the limit.
struct GltfLimits {
    // Bytes read from disk: the .gltf or .glb and every external buffer and image.
    uint64_t max_file_bytes = uint64_t(1) << 30;
    // Vertices and list indices of the whole scene, each primitive counted once, plus
    // the copies skinned or morphed (72 and 4 bytes each: 1.3 GiB at these limits;
    // indices stay far inside uint32). 2^24 vertices is 16.7 million; 3 x 2^24
    // indices, 16.7 million triangles.
    uint64_t max_vertices = uint64_t(1) << 24;
    uint64_t max_indices = uint64_t(3) << 24;
    // Textures with a side larger than this are box-downsampled to fit while they are
    // decoded (a warning says so); mips are built from the result as from any texture.
    uint32_t max_texture_size = 4096;
    // Every texture as RGBA8 after downsampling, mips included.
    uint64_t max_texture_bytes = uint64_t(1) << 30;
};

// Refused from the header whatever the limits above: a side above 32768 or more than
// 2^28 pixels (16384 x 16384), and, for images whose decoder holds them whole
// (interlaced PNG, progressive JPEG), more than 256 MiB decoded when they need
// downsampling.
constexpr uint32_t kMaxTextureSide = 32768;
constexpr uint64_t kMaxTexturePixels = uint64_t(1) << 28;
constexpr uint64_t kMaxWholeDecodeBytes = uint64_t(256) << 20;

// Loads scene `scene` of the file (-1: its default scene, else scene 0, else every root
// node): the node hierarchy flattened into instances, every mesh, material, sampler and
// image (decoded to RGBA8), KHR_lights_punctual lights and cameras placed by their
// nodes. Every primitive mode (strips, fans and loops become lists), accessor form
// (sparse, every component type, normalized or not) and vertex attribute a still frame
// needs (COLOR_0, TEXCOORD_0/1); skins posed by their joints' node transforms and
// morph targets with their default weights (node.weights over mesh.weights) are applied
// on the CPU, in a copy of the primitive per node. Missing normals are generated, and
// missing tangents where a material has a normal texture.
// Any malformed input gives Error{"<path>: <reason>"}; nothing is read out of bounds.
Result<Scene> load_gltf(const std::string& path, const GltfLimits& limits = {}, int scene = -1);

// The glTF extensions load_gltf implements, sorted (for help texts and documentation).
// Others in a file's extensionsRequired make it an error naming them all; others in its
// extensionsUsed are ignored with one Scene::warnings line each.
std::vector<std::string> gltf_supported_extensions();

}  // namespace facet
