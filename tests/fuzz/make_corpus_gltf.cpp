// glTF and GLB seeds: one quad in every index and uv type, textures (data URI, buffer
// view, file), cameras, lights, a node hierarchy, several scenes, strips and fans, points
// and lines, sparse accessors (on a view and on zeros), vertex colours and TEXCOORD_1,
// quantised positions, a skin and morph targets; then the malformed cases the loader
// must refuse with an error.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "make_corpus.h"
#include "../support/compressed_gltf.h"

namespace facet::fuzz {

namespace {

std::string base64(const ByteVector& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t n = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) n |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) n |= bytes[i + 2];
        for (size_t k = 0; k < 4; ++k)
            out += i + k <= bytes.size() ? digits[(n >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

template <class T>
size_t append(ByteVector& out, const std::vector<T>& values) {
    const size_t at = out.size();
    out.resize(at + values.size() * sizeof(T));
    std::memcpy(out.data() + at, values.data(), values.size() * sizeof(T));
    while (out.size() % 4) out.push_back(0);
    return at;
}

// The quad every seed draws from: four vertices, two triangles, in views 0..8 and
// accessors 0 POSITION, 1 NORMAL, 2 TEXCOORD_0 float, 3 TANGENT, 4/5/6 indices as
// uint16/uint8/uint32, 7/8 TEXCOORD_0 as normalised uint16/uint8.
struct Quad {
    ByteVector bin;
    std::string views, accessors;
};

Quad make_quad() {
    Quad q;
    std::string& v = q.views;
    auto view = [&](size_t offset, size_t length) {
        v += std::string(v.empty() ? "" : ",") + "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
             ",\"byteLength\":" + std::to_string(length) + "}";
    };
    view(append<float>(q.bin, {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}), 48);
    view(append<float>(q.bin, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}), 48);
    view(append<float>(q.bin, {0, 1, 1, 1, 1, 0, 0, 0}), 32);
    view(append<float>(q.bin, {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}), 64);
    view(append<uint16_t>(q.bin, {0, 1, 2, 0, 2, 3}), 12);
    view(append<uint8_t>(q.bin, {0, 1, 2, 0, 2, 3}), 6);
    view(append<uint32_t>(q.bin, {0, 1, 2, 0, 2, 3}), 24);
    view(append<uint16_t>(q.bin, {0, 65535, 65535, 65535, 65535, 0, 0, 0}), 16);
    view(append<uint8_t>(q.bin, {0, 255, 255, 255, 255, 0, 0, 0}), 8);
    q.accessors =
        R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},)"
        R"({"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"},)"
        R"({"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"},)"
        R"({"bufferView":3,"componentType":5126,"count":4,"type":"VEC4"},)"
        R"({"bufferView":4,"componentType":5123,"count":6,"type":"SCALAR"},)"
        R"({"bufferView":5,"componentType":5121,"count":6,"type":"SCALAR"},)"
        R"({"bufferView":6,"componentType":5125,"count":6,"type":"SCALAR"},)"
        R"({"bufferView":7,"componentType":5123,"count":4,"type":"VEC2","normalized":true},)"
        R"({"bufferView":8,"componentType":5121,"count":4,"type":"VEC2","normalized":true})";
    return q;
}

const std::string kOneNode = R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0)";
const std::string kTriangle = R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":4}]}],)" + kOneNode;

std::string textured(const std::string& image) {
    return R"("meshes":[{"name":"quad","primitives":[)"
           R"({"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2,"TANGENT":3},"indices":4,"material":0},)"
           R"({"attributes":{"POSITION":0,"TEXCOORD_0":7},"indices":5,"material":1},)"
           R"({"attributes":{"POSITION":0,"TEXCOORD_0":8},"indices":6,"material":2,"mode":4}]}],)"
           R"("materials":[{"name":"textured","pbrMetallicRoughness":{"baseColorFactor":[1,0.5,0.25,1],)"
           R"("baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"offset":[0.5,0],"rotation":0.3,)"
           R"("scale":[2,2],"texCoord":0}}},"metallicFactor":0.5,"roughnessFactor":0.25,)"
           R"("metallicRoughnessTexture":{"index":0}},"normalTexture":{"index":0,"scale":0.5},)"
           R"("occlusionTexture":{"index":0,"strength":0.7},"emissiveTexture":{"index":0},"emissiveFactor":[1,1,1],)"
           R"("extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":2},)"
           R"("KHR_materials_clearcoat":{"clearcoatFactor":0.8,"clearcoatRoughnessFactor":0.2,)"
           R"("clearcoatTexture":{"index":0},"clearcoatRoughnessTexture":{"index":0,"texCoord":0},)"
           R"("clearcoatNormalTexture":{"index":0,"scale":0.5,"extensions":{"KHR_texture_transform":{"rotation":1}}}},)"
           R"("KHR_materials_iridescence":{"iridescenceFactor":0.8,"iridescenceIor":1.6,"iridescenceThicknessMinimum":150,)"
           R"("iridescenceThicknessMaximum":700,"iridescenceTexture":{"index":0},)"
           R"("iridescenceThicknessTexture":{"index":0,"texCoord":0}},)"
           R"("KHR_materials_anisotropy":{"anisotropyStrength":0.5,"anisotropyRotation":0.3,)"
           R"("anisotropyTexture":{"index":0}}}},)"
           R"({"alphaMode":"MASK","alphaCutoff":0.3,"doubleSided":true,"normalTexture":{"index":0},)"
           R"("extensions":{"KHR_materials_ior":{"ior":1.33},"KHR_materials_specular":{"specularFactor":0.5,)"
           R"("specularColorFactor":[1,0.5,0.5],"specularTexture":{"index":0},"specularColorTexture":{"index":0,"texCoord":0}},)"
           R"("KHR_materials_sheen":{"sheenColorFactor":[0.9,0.5,0.2],"sheenRoughnessFactor":0.4,)"
           R"("sheenColorTexture":{"index":0},"sheenRoughnessTexture":{"index":0,"texCoord":0,)"
           R"("extensions":{"KHR_texture_transform":{"offset":[0.25,0]}}}},)"
           R"("KHR_materials_transmission":{"transmissionFactor":0.9,"transmissionTexture":{"index":0,"texCoord":0}},)"
           R"("KHR_materials_volume":{"thicknessFactor":0.5,"attenuationDistance":2,"attenuationColor":[0.9,0.6,0.3],)"
           R"("thicknessTexture":{"index":0,"extensions":{"KHR_texture_transform":{"rotation":0.5,"scale":[2,2]}}}}}},)"
           R"({"alphaMode":"BLEND","extensions":{"KHR_materials_unlit":{}}}],)"
           R"("textures":[{"source":0,"sampler":0}],)"
           R"("samplers":[{"magFilter":9728,"minFilter":9987,"wrapS":33648,"wrapT":33071}],)"
           R"("images":[)" + image + "],"
           R"("extensionsUsed":["KHR_materials_clearcoat","KHR_materials_emissive_strength","KHR_materials_ior",)"
           R"("KHR_materials_iridescence","KHR_materials_anisotropy","KHR_materials_sheen",)"
           R"("KHR_materials_specular","KHR_materials_transmission",)"
           R"("KHR_materials_unlit","KHR_materials_volume","KHR_texture_transform"],)" +
           kOneNode;
}

const std::string kStripsAndFans =
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":5},{"attributes":{"POSITION":0},"mode":6},)"
    R"({"attributes":{"POSITION":0,"NORMAL":1},"indices":5,"mode":5}]}],)" + kOneNode;

const std::string kHierarchy =
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":4}]}],)"
    R"("cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1,"zfar":100,"aspectRatio":1.5}},)"
    R"({"type":"orthographic","orthographic":{"xmag":2,"ymag":1,"znear":0.1,"zfar":50}}],)"
    R"("extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[)"
    R"({"type":"directional","color":[1,0.9,0.8],"intensity":3},{"type":"point","intensity":50,"range":10},)"
    R"({"type":"spot","intensity":80,"spot":{"innerConeAngle":0.2,"outerConeAngle":0.6}}]}},)"
    R"("nodes":[{"name":"root","children":[1,2,3],"translation":[0,1,0],"rotation":[0,0.7071068,0,0.7071068],)"
    R"("scale":[2,2,2]},{"mesh":0,"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,1,2,3,1]},)"
    R"({"camera":0,"translation":[0,0,5],"children":[4]},)"
    R"({"camera":1,"rotation":[-0.3826834,0,0,0.9238795],"extensions":{"KHR_lights_punctual":{"light":0}}},)"
    R"({"translation":[1,1,1],"extensions":{"KHR_lights_punctual":{"light":1}},"children":[5]},)"
    R"({"extensions":{"KHR_lights_punctual":{"light":2}},"rotation":[0.7071068,0,0,0.7071068]}],)"
    R"("scenes":[{"nodes":[0]}],"scene":0)";

const std::string kScenes =
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":4}]},)"
    R"({"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":2},"indices":6}]}],)"
    R"("nodes":[{"mesh":0},{"mesh":1,"scale":[1,-1,1]},{"mesh":0,"children":[1]}],)"
    R"("scenes":[{"nodes":[0]},{"name":"second","nodes":[2]}],"scene":1)";

const std::string kLinesAndPoints =
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":0},{"attributes":{"POSITION":0},"mode":1},)"
    R"({"attributes":{"POSITION":0},"mode":2},{"attributes":{"POSITION":0},"indices":5,"mode":3}]}],)" + kOneNode;

// Views and accessors the seeds below add to the quad's (views from 9, accessors from 9):
// 9 COLOR_0 VEC4 normalized UNSIGNED_BYTE, 10 JOINTS_0 UNSIGNED_BYTE, 11 WEIGHTS_0 FLOAT,
// 12 inverse bind matrices, 13 a morph target's positions, 14 POSITION as SHORT,
// 15 sparse POSITION on view 0, 16 sparse POSITION on zeros, 17 COLOR_0 VEC3 FLOAT,
// 18 a sparse accessor whose index 3 is past its 2 elements, 19 a target of 3 elements.
struct Extras {
    ByteVector bin;
    std::string views, accessors;
};

Extras make_extras(const Quad& q) {
    Extras e{q.bin, "", ""};
    auto view = [&](size_t offset, size_t length) {
        e.views += ",{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" + std::to_string(length) + "}";
    };
    view(append<uint8_t>(e.bin, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 128, 255, 255, 255, 0}), 16);  // view 9
    view(append<uint8_t>(e.bin, {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}), 16);                      // view 10
    view(append<float>(e.bin, {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}), 64);                  // view 11
    view(append<float>(e.bin, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,  //
                               1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1}),
         128);                                                                                   // view 12
    view(append<float>(e.bin, {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1}), 48);                         // view 13
    view(append<int16_t>(e.bin, {-100, -100, 0, 0, 100, -100, 0, 0, 100, 100, 0, 0, -100, 100, 0, 0}), 32);  // view 14
    view(append<uint8_t>(e.bin, {1, 3, 0, 0}), 4);                                                 // view 15
    view(append<float>(e.bin, {0.5f, 0.5f, 0.5f, 2, 2, 2}), 24);                                   // view 16
    view(append<float>(e.bin, {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}), 48);                          // view 17
    const std::string sparse = R"("sparse":{"count":2,"indices":{"bufferView":15,"componentType":5121},"values":{"bufferView":16}})";
    e.accessors =
        R"(,{"bufferView":9,"componentType":5121,"count":4,"type":"VEC4","normalized":true})"
        R"(,{"bufferView":10,"componentType":5121,"count":4,"type":"VEC4"})"
        R"(,{"bufferView":11,"componentType":5126,"count":4,"type":"VEC4"})"
        R"(,{"bufferView":12,"componentType":5126,"count":2,"type":"MAT4"})"
        R"(,{"bufferView":13,"componentType":5126,"count":4,"type":"VEC3"})"
        R"(,{"bufferView":14,"componentType":5122,"count":4,"type":"VEC3","normalized":true,"byteOffset":0})"
        R"(,{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",)" + sparse + "}"
        R"(,{"componentType":5126,"count":4,"type":"VEC3",)" + sparse + "}"
        R"(,{"bufferView":17,"componentType":5126,"count":4,"type":"VEC3"})"
        R"(,{"bufferView":0,"componentType":5126,"count":2,"type":"VEC3",)" + sparse + "}"
        R"(,{"bufferView":13,"componentType":5126,"count":3,"type":"VEC3"})";
    return e;
}

std::string document(const std::string& buffer, const std::string& rest, const Quad& q,
                     const std::string& more_views = "", const std::string& more_accessors = "") {
    return R"({"asset":{"version":"2.0","generator":"facet fuzz seeds"},"buffers":[)" + buffer +
           R"(],"bufferViews":[)" + q.views + more_views + R"(],"accessors":[)" + q.accessors + more_accessors +
           "]," + rest + "}";
}

std::string data_buffer(const ByteVector& bin) {
    return R"({"byteLength":)" + std::to_string(bin.size()) + R"(,"uri":"data:application/octet-stream;base64,)" +
           base64(bin) + "\"}";
}

ByteVector glb(std::string json, ByteVector bin) {
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin.push_back(0);
    ByteVector out;
    auto u32 = [&](uint32_t v) { append<uint32_t>(out, {v}); };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    u32(2);
    u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    u32(uint32_t(json.size()));
    u32(0x4E4F534A);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    u32(uint32_t(bin.size()));
    u32(0x004E4942);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    return out;
}

}  // namespace

void make_gltf_corpus(const std::filesystem::path& dir) {
    const Quad q = make_quad();
    const std::string buffer = data_buffer(q.bin);
    const ByteVector png = png_bytes(2, 2);
    const std::string png_uri = R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}";

    write_seed(dir, "triangle.gltf", document(buffer, kTriangle, q));
    write_seed(dir, "textured.gltf", document(buffer, textured(png_uri), q));
    write_seed(dir, "strips_fans.gltf", document(buffer, kStripsAndFans, q));
    write_seed(dir, "hierarchy_cameras_lights.gltf", document(buffer, kHierarchy, q));
    write_seed(dir, "scenes.gltf", document(buffer, kScenes, q));
    write_seed(dir, "no_scene.gltf",
               document(buffer, R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":6}]}],"nodes":[{"mesh":0}])", q));
    write_seed(dir, "lines_points.gltf", document(buffer, kLinesAndPoints, q));
    {
        const Extras e = make_extras(q);
        const std::string ebuffer = data_buffer(e.bin);
        auto seed = [&](const std::string& name, const std::string& rest) {
            write_seed(dir, name, document(ebuffer, rest, q, e.views, e.accessors));
        };
        seed("colours_uv1.gltf",
             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":9,"TEXCOORD_0":2,"TEXCOORD_1":7},)"
             R"("indices":4,"material":0},{"attributes":{"POSITION":0,"COLOR_0":17,"TEXCOORD_1":8},"indices":4}]}],)"
             R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"texCoord":1}},)"
             R"("emissiveTexture":{"index":0,"texCoord":0}}],"textures":[{"source":0}],"images":[)" + png_uri + "]," +
                 kOneNode);
        seed("sparse_quantised.gltf",
             R"("meshes":[{"primitives":[{"attributes":{"POSITION":15},"indices":4},{"attributes":{"POSITION":16},"indices":4},)"
             R"({"attributes":{"POSITION":14},"indices":4}]}],)"
             R"("extensionsUsed":["KHR_mesh_quantization"],)" + kOneNode);
        const std::string skinned =
            R"("meshes":[{"weights":[0.5],"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"JOINTS_0":10,"WEIGHTS_0":11},)"
            R"("indices":4,"targets":[{"POSITION":13}]}]}],)";
        seed("skin_morph.gltf",
             skinned + R"("skins":[{"joints":[1,2],"inverseBindMatrices":12}],)"
                       R"("nodes":[{"mesh":0,"skin":0,"weights":[0.25]},{"children":[2]},)"
                       R"({"translation":[0,1,0],"rotation":[0,0,0.7071068,0.7071068]},{"mesh":0,"scale":[-1,1,1]}],)"
                       R"("scenes":[{"nodes":[0,1,3]}],"scene":0)");
        seed("bad_skin_joint.gltf", skinned + R"("skins":[{"joints":[1,7]}],)"
                                              R"("nodes":[{"mesh":0,"skin":0},{}],"scenes":[{"nodes":[0,1]}])");
        seed("bad_skin_vertex_joint.gltf", skinned + R"("skins":[{"joints":[1]}],)"
                                                     R"("nodes":[{"mesh":0,"skin":0},{}],"scenes":[{"nodes":[0,1]}])");
        seed("bad_morph_count.gltf",
             R"("meshes":[{"weights":[1],"primitives":[{"attributes":{"POSITION":0},"indices":4,"targets":[{"POSITION":19}]}]}],)" +
                 kOneNode);
        seed("bad_morph_weights.gltf",
             R"("meshes":[{"weights":[1,1],"primitives":[{"attributes":{"POSITION":0},"indices":4,"targets":[{"POSITION":13}]}]}],)" +
                 kOneNode);
        seed("bad_sparse_index.gltf",
             R"("meshes":[{"primitives":[{"attributes":{"POSITION":18},"indices":4}]}],)" + kOneNode);
        seed("bad_texcoord_2.gltf",
             R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":4,"material":0}]}],)"
             R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"texCoord":2}}}],)"
             R"("textures":[{"source":0}],"images":[)" + png_uri + "]," + kOneNode);
        seed("bad_scene_index.gltf", kTriangle.substr(0, kTriangle.size() - 1) + "7");
    }
    // buffer.bin and texture.png lie beside every input (feed_gltf).
    write_seed(dir, "external.gltf",
               R"({"asset":{"version":"2.0"},"buffers":[{"uri":"buffer.bin","byteLength":44}],)"
               R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],)"
               R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
               R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}],)"
               R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],)"
               R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
               R"("textures":[{"source":0}],"images":[{"uri":"texture.png"}],)" + kOneNode + "}");
    {  // positions and normals interleaved, 24-byte stride
        ByteVector bin;
        append<float>(bin, {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1});
        write_seed(dir, "interleaved.gltf",
                   R"({"asset":{"version":"2.0"},"buffers":[)" + data_buffer(bin) +
                       R"(],"bufferViews":[{"buffer":0,"byteLength":72,"byteStride":24}],)"
                       R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
                       R"({"bufferView":0,"byteOffset":12,"componentType":5126,"count":3,"type":"VEC3"}],)"
                       R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}}]}],)" + kOneNode + "}");
    }

    // GLB: the same with the buffer as the BIN chunk, and the texture in a buffer view.
    const std::string glb_buffer = R"({"byteLength":)" + std::to_string(q.bin.size()) + "}";
    write_seed(dir, "triangle.glb", glb(document(glb_buffer, kTriangle, q), q.bin));
    ByteVector with_png = q.bin;
    const size_t png_at = append<uint8_t>(with_png, png);
    const std::string png_view = R"(,{"buffer":0,"byteOffset":)" + std::to_string(png_at) + R"(,"byteLength":)" +
                                 std::to_string(png.size()) + "}";
    const ByteVector textured_glb =
        glb(document(R"({"byteLength":)" + std::to_string(with_png.size()) + "}",
                     textured(R"({"bufferView":9,"mimeType":"image/png"})"), q, png_view),
            with_png);
    write_seed(dir, "textured.glb", textured_glb);
    write_seed(dir, "hierarchy.glb", glb(document(glb_buffer, kHierarchy, q), q.bin));

    // Malformed: each must be one error naming the file.
    const std::string mesh = R"("meshes":[{"primitives":[{"attributes":{"POSITION":9},"indices":4}]}],)" + kOneNode;
    write_seed(dir, "bad_index_past_vertices.gltf",
               document(buffer, mesh, q, "", R"(,{"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"})"));
    write_seed(dir, "bad_accessor_past_view.gltf",
               document(buffer, mesh, q, "", R"(,{"bufferView":0,"componentType":5126,"count":40,"type":"VEC3"})"));
    write_seed(dir, "bad_huge_count.gltf",
               document(buffer, mesh, q, "", R"(,{"bufferView":0,"componentType":5126,"count":4294967295,"type":"VEC3"})"));
    write_seed(dir, "bad_view_past_buffer.gltf",
               document(buffer, kTriangle, q, R"(,{"buffer":0,"byteOffset":16,"byteLength":100000})"));
    write_seed(dir, "bad_stride.gltf",
               document(buffer, mesh, q, R"(,{"buffer":0,"byteLength":48,"byteStride":3})",
                        R"(,{"bufferView":9,"componentType":5126,"count":4,"type":"VEC3"})"));
    write_seed(dir, "bad_node_cycle.gltf",
               document(buffer, R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                                R"("nodes":[{"mesh":0,"children":[1]},{"children":[0]}])",
                        q));
    write_seed(dir, "bad_two_parents.gltf",
               document(buffer, R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                                R"("nodes":[{"children":[2]},{"children":[2]},{"mesh":0}],"scenes":[{"nodes":[0,1]}])",
                        q));
    write_seed(dir, "bad_material_ref.gltf",
               document(buffer, R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":5}]}],)" + kOneNode, q));
    write_seed(dir, "bad_texture_ref.gltf",
               document(buffer, R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
                                R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
                                R"("textures":[{"source":3}],)" + kOneNode,
                        q));
    write_seed(dir, "bad_mode_unknown.gltf",
               document(buffer, R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":9}]}],)" + kOneNode, q));
    write_seed(dir, "bad_index_count.gltf",
               document(buffer, R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":9}]}],)" + kOneNode, q,
                        "", R"(,{"bufferView":4,"componentType":5123,"count":5,"type":"SCALAR"})"));
    write_seed(dir, "bad_required_extension.gltf",
               document(buffer, kTriangle + R"(,"extensionsRequired":["KHR_made_up_extension"])", q));
    write_seed(dir, "bad_image_bytes.gltf",
               document(buffer, textured(R"({"uri":"data:image/png;base64,bm90IGEgcG5n"})"), q));
    write_seed(dir, "bad_scene_ref.gltf", document(buffer, kTriangle + R"(,"scenes":[{"nodes":[7]}])", q));
    write_seed(dir, "bad_json.gltf", std::string(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4,)"));
    {  // NaN and Inf positions
        ByteVector bin;
        append<float>(bin, {0, 0, 0, std::numeric_limits<float>::quiet_NaN(), 0, 0, 0, INFINITY, 0});
        write_seed(dir, "bad_nan_position.glb",
                   glb(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36}],)"
                       R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
                       R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
                       R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)" + kOneNode + "}",
                       bin));
    }
    ByteVector truncated(textured_glb.begin(), textured_glb.begin() + textured_glb.size() / 2);
    write_seed(dir, "bad_truncated.glb", truncated);
    ByteVector long_header = textured_glb;
    long_header[8] = 0xFF;  // total length far beyond the file
    write_seed(dir, "bad_glb_length.glb", long_header);
    ByteVector long_chunk = textured_glb;
    long_chunk[13] = 0x7F;  // JSON chunk length past the end
    write_seed(dir, "bad_glb_chunk.glb", long_chunk);
    make_compressed_gltf_corpus(dir);
}

// Compressed meshes and extension lists (engine/scene/gltf_decompress*.cpp,
// gltf_extensions.cpp): small meshopt and Draco files written with the libraries' own
// encoders (tests/support/compressed_gltf.h), then corrupt streams and forged fields.
namespace {

namespace fs = std::filesystem;

ByteVector compressed_file(const std::string& name, void (*write)(const fs::path&)) {
    const fs::path dir = fs::temp_directory_path() / "facet-make-corpus-compressed";
    fs::create_directories(dir);
    write(dir / name);
    ByteVector bytes = read_bytes(dir / name);
    fs::remove_all(dir);
    return bytes;
}

// The GLB with its JSON chunk's first `from` replaced by `to` (the BIN chunk kept).
ByteVector edited_glb(const ByteVector& file, const std::string& from, const std::string& to) {
    uint32_t json_length;
    std::memcpy(&json_length, &file[12], 4);
    std::string json(file.begin() + 20, file.begin() + 20 + json_length);
    const size_t at = json.find(from);
    if (at != std::string::npos) json.replace(at, from.size(), to);
    uint32_t bin_length;
    std::memcpy(&bin_length, &file[20 + json_length], 4);
    const auto bin_at = file.begin() + 28 + json_length;
    return glb(json, ByteVector(bin_at, bin_at + bin_length));
}

// The byte `offset` into the BIN chunk set to `value`.
ByteVector poked_bin(ByteVector file, size_t offset, uint8_t value) {
    uint32_t json_length;
    std::memcpy(&json_length, &file[12], 4);
    file[28 + json_length + offset] = value;
    return file;
}

}  // namespace

void make_compressed_gltf_corpus(const fs::path& dir) {
    const ByteVector meshopt = compressed_file("m.glb", [](const fs::path& p) {
        test::write_meshopt_gltf(p, test::wavy_grid(5, 4));
    });
    write_seed(dir, "meshopt_grid.glb", meshopt);
    write_seed(dir, "meshopt_sequence_exp.glb", compressed_file("s.glb", [](const fs::path& p) {
        test::MeshoptOptions o;
        o.index_sequence = o.exponential_positions = true;
        o.required = false;
        test::write_meshopt_gltf(p, test::wavy_grid(3, 6), o);
    }));
    const ByteVector draco = compressed_file("d.glb", [](const fs::path& p) {
        test::write_draco_gltf(p, test::wavy_grid(5, 4));
    });
    write_seed(dir, "draco_grid.glb", draco);
    write_seed(dir, "draco_sequential.glb", compressed_file("q.glb", [](const fs::path& p) {
        test::DracoOptions o;
        o.speed = 10;
        test::write_draco_gltf(p, test::wavy_grid(2, 3), o);
    }));

    write_seed(dir, "bad_meshopt_stream.glb", poked_bin(meshopt, 0, 0x00));
    write_seed(dir, "garbled_meshopt_data.glb", poked_bin(meshopt, 40, 0xFF));
    write_seed(dir, "bad_meshopt_count.glb", edited_glb(meshopt, "\"count\": 30,", "\"count\": 300000000,"));
    write_seed(dir, "bad_meshopt_mode.glb", edited_glb(meshopt, "\"TRIANGLES\"", "\"TRIANGLE\""));
    write_seed(dir, "bad_meshopt_filter.glb",
               edited_glb(meshopt, "\"mode\": \"ATTRIBUTES\"", "\"mode\": \"ATTRIBUTES\", \"filter\": \"QUATERNION\""));
    write_seed(dir, "bad_meshopt_buffer.glb", edited_glb(meshopt, "{\"buffer\": 0,", "{\"buffer\": 7,"));
    write_seed(dir, "bad_draco_stream.glb", poked_bin(draco, 0, 'X'));
    write_seed(dir, "bad_draco_data.glb", poked_bin(draco, 30, 0xFF));
    write_seed(dir, "bad_draco_count.glb", edited_glb(draco, "\"count\": 30,", "\"count\": 29,"));
    write_seed(dir, "bad_draco_attribute.glb", edited_glb(draco, "\"TEXCOORD_0\": 2}", "\"TEXCOORD_0\": 99}"));
    write_seed(dir, "bad_draco_view.glb", edited_glb(draco, "{\"bufferView\": 0,", "{\"bufferView\": 5,"));

    const std::string triangle =
        R"({"asset":{"version":"2.0"},%LISTS%"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
        R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)" + kOneNode + "}";
    auto with_lists = [&](const std::string& lists) {
        std::string text = triangle;
        text.replace(text.find("%LISTS%"), 7, lists);
        return text;
    };
    const std::string webp_uri = "data:image/webp;base64," + base64(ByteVector(test::kWebp, test::kWebp + sizeof test::kWebp));
    const std::string webp_texture =
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
        R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
        R"("images":[{"uri":")" + webp_uri + R"("}],)";
    auto with_texture = [&](const std::string& texture, const std::string& image_uri) {
        std::string text = with_lists(R"("extensionsUsed":["EXT_texture_webp"],"extensionsRequired":["EXT_texture_webp"],)");
        const std::string meshes = R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)";
        std::string textured = webp_texture;
        textured.replace(textured.find(webp_uri), webp_uri.size(), image_uri);
        text.replace(text.find(meshes), meshes.size(), textured + R"("textures":[)" + texture + "],");
        return text;
    };
    write_seed(dir, "webp_texture.gltf", with_texture(R"({"extensions":{"EXT_texture_webp":{"source":0}}})", webp_uri));
    write_seed(dir, "bad_webp_source.gltf", with_texture(R"({"extensions":{"EXT_texture_webp":{"source":3}}})", webp_uri));
    write_seed(dir, "bad_webp_bytes.gltf",
               with_texture(R"({"extensions":{"EXT_texture_webp":{"source":0}}})",
                            "data:image/webp;base64," + base64(ByteVector(test::kWebp, test::kWebp + 40))));
    write_seed(dir, "extensions_used_unknown.gltf",
               with_lists(R"("extensionsUsed":["KHR_materials_made_up","KHR_lights_punctual"],)"));
    write_seed(dir, "bad_extensions_required_two.gltf",
               with_lists(R"("extensionsUsed":["KHR_made_up_a","EXT_made_up_b"],)"
                          R"("extensionsRequired":["KHR_made_up_a","EXT_made_up_b"],)"));
}

}  // namespace facet::fuzz
