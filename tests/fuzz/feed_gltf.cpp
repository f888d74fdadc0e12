#include <cmath>
#include <cstring>
#include <vector>

#include "feed.h"
#include <facet/io/image_io.h>
#include <facet/scene/gltf_loader.h>

namespace facet::fuzz {

namespace {

// Files an input's uris may name (the seeds do): three positions then three uint16
// indices, and a 2x2 texture.
void write_neighbours() {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint16_t indices[4] = {0, 1, 2, 0};  // the last one pads to 4 bytes
    std::vector<uint8_t> buffer(sizeof positions + sizeof indices);
    std::memcpy(buffer.data(), positions, sizeof positions);
    std::memcpy(buffer.data() + sizeof positions, indices, sizeof indices);
    write_input(buffer, "buffer.bin");
    const uint8_t texels[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
    Status png = write_ldr_image(work_dir() + "/texture.png", 2, 2, texels);
    FACET_FUZZ_EXPECT(png.ok(), png.error().message);
}

bool finite(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(glm::vec4 v) { return finite(glm::vec3(v)) && std::isfinite(v.w); }
bool finite(const glm::mat4& m) { return finite(m[0]) && finite(m[1]) && finite(m[2]) && finite(m[3]); }

void check_texture(const Scene& scene, const TextureRef& ref, const std::string& where) {
    if (!ref.valid()) return;
    FACET_FUZZ_EXPECT(size_t(ref.image) < scene.images.size(), where + ": image out of range");
    FACET_FUZZ_EXPECT(ref.sampler == -1 || (ref.sampler >= 0 && size_t(ref.sampler) < scene.samplers.size()),
                      where + ": sampler out of range");
}

// What the renderer relies on: every index inside its primitive's vertices, every
// reference in range, and no NaN or Inf reaching a GPU buffer.
void check_scene(const Scene& scene) {
    for (size_t i = 0; i < scene.primitives.size(); ++i) {
        const Primitive& p = scene.primitives[i];
        const std::string where = "primitive " + std::to_string(i);
        const uint32_t corners = p.topology == Topology::triangles ? 3 : p.topology == Topology::lines ? 2 : 1;
        FACET_FUZZ_EXPECT(p.index_count % corners == 0, where + ": not a list of its topology");
        FACET_FUZZ_EXPECT(uint64_t(p.first_index) + p.index_count <= scene.indices.size(), where + ": indices out of range");
        FACET_FUZZ_EXPECT(uint64_t(p.vertex_offset) + p.vertex_count <= scene.vertices.size(),
                          where + ": vertices out of range");
        FACET_FUZZ_EXPECT(p.material < scene.materials.size(), where + ": material out of range");
        for (uint32_t k = 0; k < p.index_count; ++k)
            FACET_FUZZ_EXPECT(scene.indices[p.first_index + k] < p.vertex_count,
                              where + ": index " + std::to_string(scene.indices[p.first_index + k]) + " >= " +
                                  std::to_string(p.vertex_count));
        FACET_FUZZ_EXPECT(finite(p.bounds_min) && finite(p.bounds_max), where + ": bounds not finite");
    }
    for (size_t i = 0; i < scene.vertices.size(); ++i) {
        const Vertex& v = scene.vertices[i];
        FACET_FUZZ_EXPECT(finite(v.position) && finite(v.normal) && finite(v.uv) && finite(v.tangent) &&
                              finite(v.color) && finite(v.uv1),
                          "vertex " + std::to_string(i) + " is not finite");
    }
    for (const Mesh& mesh : scene.meshes)
        for (uint32_t p : mesh.primitives) FACET_FUZZ_EXPECT(p < scene.primitives.size(), "mesh primitive out of range");
    for (const Instance& instance : scene.instances) {
        FACET_FUZZ_EXPECT(instance.primitive < scene.primitives.size(), "instance primitive out of range");
        FACET_FUZZ_EXPECT(finite(instance.world), "instance '" + instance.node + "': world matrix not finite");
    }
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        const std::string where = "material " + std::to_string(i);
        FACET_FUZZ_EXPECT(finite(m.base_color) && finite(m.emissive) && std::isfinite(m.metallic) &&
                              std::isfinite(m.roughness) && std::isfinite(m.normal_scale) &&
                              std::isfinite(m.occlusion_strength) && std::isfinite(m.alpha_cutoff),
                          where + ": a factor is not finite");
        for (const TextureRef* ref : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                      &m.occlusion_texture, &m.emissive_texture})
            check_texture(scene, *ref, where);
    }
    for (const TextureImage& image : scene.images)
        FACET_FUZZ_EXPECT(image.width > 0 && image.height > 0 &&
                              image.rgba.size() == size_t(image.width) * image.height * 4,
                          "image '" + image.name + "': size and texels disagree");
    for (const TextureSampler& sampler : scene.samplers)
        FACET_FUZZ_EXPECT(sampler.wrap_u <= 2 && sampler.wrap_v <= 2, "sampler wrap mode out of range");
    for (const Light& light : scene.lights)
        FACET_FUZZ_EXPECT(finite(light.color) && std::isfinite(light.intensity) && finite(light.position) &&
                              finite(light.direction) && std::isfinite(light.range) &&
                              std::isfinite(light.inner_cone) && std::isfinite(light.outer_cone),
                          "a light is not finite");
    for (const Camera& camera : scene.cameras)
        FACET_FUZZ_EXPECT(finite(camera.position) && finite(camera.target) && finite(camera.up) &&
                              std::isfinite(camera.yfov) && std::isfinite(camera.znear) && std::isfinite(camera.zfar) &&
                              std::isfinite(camera.ymag),
                          "camera '" + camera.name + "' is not finite");
}

}  // namespace

bool feed_gltf(Bytes input) {
    static const bool neighbours_written = (write_neighbours(), true);
    (void)neighbours_written;
    const bool glb = input.size() >= 4 && std::memcmp(input.data(), "glTF", 4) == 0;
    const std::string path = write_input(input, glb ? "model.glb" : "model.gltf");
    Result<Scene> scene = load_gltf(path);
    if (!scene) {
        expect_names_file(scene.error(), path);
        return false;
    }
    check_scene(*scene);
    return true;
}

}  // namespace facet::fuzz
