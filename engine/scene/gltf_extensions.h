#pragma once
// Internal to the glTF loader: the extensions Facet implements, and what a file's
// extensionsRequired and extensionsUsed lists mean against them.
#include <tiny_gltf.h>

#include <string>
#include <string_view>
#include <vector>

namespace facet::gltf_detail {

// Every extension the loader implements (sorted). One place to list them: the checks
// below and `facet-render --help` read it.
const std::vector<std::string_view>& supported_extensions();
bool is_supported_extension(std::string_view name);

// Fails with one error naming every extension in extensionsRequired that Facet lacks:
// loading on without one would draw wrong geometry or images.
void check_required_extensions(const tinygltf::Model& model);

// One warning per extension in extensionsUsed that Facet ignores (the file is drawn
// without it), for Scene::warnings.
std::vector<std::string> ignored_extension_warnings(const tinygltf::Model& model);

// Textures with EXT_texture_webp take its source (a WebP image) in place of their own.
void use_webp_sources(tinygltf::Model& model);

// What parse() calls once tinygltf has read the model: the required check, then every
// compressed bufferView and primitive (EXT_meshopt_compression, KHR_draco_mesh_compression)
// decoded into plain buffers and WebP sources chosen, so the rest of the loader reads an
// ordinary model.
void apply_extensions(tinygltf::Model& model);

}  // namespace facet::gltf_detail
