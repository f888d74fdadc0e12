#include <facet/scene/gltf_loader.h>

// Debian's libtinygltf is a compiled library: include the declarations only.
#include <tiny_gltf.h>

#include <cstdint>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include <facet/core/hash.h>
#include <facet/core/log.h>
#include "scene/gltf_accessors.h"
#include "scene/gltf_errors.h"
#include "scene/gltf_extensions.h"
#include "scene/gltf_images.h"
#include "scene/gltf_materials.h"
#include "scene/gltf_meshes.h"
#include "scene/gltf_nodes.h"
#include "scene/gltf_parse.h"

namespace facet {

using namespace gltf_detail;

namespace {

Scene convert(const tinygltf::Model& model, const GltfLimits& limits, int scene_index) {
    // extensionsRequired was checked by parse (gltf_extensions.h); what is used but
    // ignored is said.
    Scene scene;
    scene.warnings = ignored_extension_warnings(model);
    validate_buffer_views(model);
    const GeometryCount geometry = count_geometry(model, limits);
    scene.vertices.reserve(size_t(geometry.vertices));
    scene.indices.reserve(size_t(geometry.indices));
    for (size_t i = 0; i < model.samplers.size(); ++i) scene.samplers.push_back(convert_sampler(model.samplers[i], i));
    for (size_t i = 0; i < model.materials.size(); ++i) scene.materials.push_back(convert_material(model, i));

    bool needs_default_material = false;
    std::vector<PrimitiveDeform> deforms;  // by primitive, for the nodes that skin or morph them
    for (size_t m = 0; m < model.meshes.size(); ++m) {
        const tinygltf::Mesh& mesh = model.meshes[m];
        Mesh out;
        out.name = mesh.name;
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            std::string where = label("mesh", m, mesh.name) + " primitive " + std::to_string(p);
            deforms.push_back(load_primitive(model, mesh.primitives[p], where, needs_default_material, scene));
            out.primitives.push_back(uint32_t(scene.primitives.size() - 1));
        }
        scene.meshes.push_back(std::move(out));
    }
    if (needs_default_material) {
        Material fallback;  // glTF's defaults: white, metallic 1, roughness 1
        fallback.name = "default";
        scene.materials.push_back(fallback);
    }
    place_nodes(model, deforms, limits, scene_index, scene);
    return scene;
}

}  // namespace

Result<Scene> load_gltf(const std::string& path, const GltfLimits& limits, int scene_index) {
    try {
        FileBudget budget{limits.max_file_bytes};
        std::vector<uint8_t> bytes = read_file(path, budget);
        Hash64 hash;
        hash.add(bytes.data(), bytes.size());
        EncodedImages encoded;
        tinygltf::Model model = parse(path, bytes, encoded, budget);
        std::vector<uint8_t>().swap(bytes);  // tinygltf copied what it needs
        Scene scene = convert(model, limits, scene_index);
        // Images last: the cheap structural checks above fail faster on broken files.
        const std::vector<ImagePlan> plans = plan_images(model, encoded, scene, limits);
        for (size_t i = 0; i < model.images.size(); ++i) {
            scene.images.push_back(decode_image(model, i, encoded, plans[i]));
            encoded.erase(int(i));
            const TextureImage& image = scene.images.back();
            if (image.width != image.source_width || image.height != image.source_height)
                log(LogLevel::warning, path + ": image '" + image.name + "' " + std::to_string(image.source_width) +
                                           "x" + std::to_string(image.source_height) + " downsampled to " +
                                           std::to_string(image.width) + "x" + std::to_string(image.height) +
                                           " (textures are kept at most " + std::to_string(limits.max_texture_size) +
                                           " a side)");
        }

        for (const tinygltf::Buffer& buffer : model.buffers) hash.add(buffer.data.data(), buffer.data.size());
        for (const TextureImage& image : scene.images) hash.add(image.rgba.data(), image.rgba.size());
        scene.content_hash = hash.hex();
        scene.source = path;
        return scene;
    } catch (const LoadError& e) {
        return Error{path + ": " + e.reason};
    } catch (const std::bad_alloc&) {
        return Error{path + ": out of memory"};
    }
}

}  // namespace facet
