// The extension registry: extensionsRequired that Facet lacks is one error naming them
// all, extensionsUsed that it ignores is a warning on the Scene naming each; and the JSON
// rewrite that lets tinygltf read compressed files (gltf_decompress_json.h).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <filesystem>
#include <string>
#include <vector>

#include <facet/scene/gltf_loader.h>
#include "scene/gltf_decompress_json.h"
#include "scene/gltf_extensions.h"
#include "support/compressed_gltf.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using namespace gltf_detail;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_gltf_extensions_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    fs::path file(const std::string& name) const { return path / name; }
};

// One triangle in a data uri; `lists` adds extensionsUsed / extensionsRequired members.
std::string triangle_gltf(const std::string& lists) {
    // Three float positions (0,0,0) (1,0,0) (0,1,0), 36 bytes, base64.
    return R"({"asset": {"version": "2.0"},)" + lists + R"(
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
}

Result<Scene> load_text(const TempDir& dir, const std::string& text) {
    const fs::path path = dir.file("model.gltf");
    test::write_bytes(path, text.data(), text.size());
    return load_gltf(path.string());
}

TEST(GltfExtensions, RegistryIsSortedAndHoldsWhatTheLoaderReads) {
    const auto& names = supported_extensions();
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
    for (const char* name : {"EXT_meshopt_compression", "KHR_draco_mesh_compression", "KHR_lights_punctual",
                             "KHR_materials_emissive_strength"})
        EXPECT_TRUE(is_supported_extension(name)) << name;
    EXPECT_FALSE(is_supported_extension("KHR_materials_made_up"));
    EXPECT_FALSE(is_supported_extension(""));
}

TEST(GltfExtensions, TwoUnsupportedRequiredAreOneErrorNamingBoth) {
    TempDir dir;
    const Result<Scene> scene = load_text(dir, triangle_gltf(R"(
  "extensionsUsed": ["KHR_lights_punctual", "KHR_made_up_one", "EXT_made_up_two"],
  "extensionsRequired": ["KHR_made_up_one", "KHR_lights_punctual", "EXT_made_up_two", "KHR_made_up_one"],)"));
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().message, dir.file("model.gltf").string() +
                                         ": requires 2 unsupported extensions: KHR_made_up_one, EXT_made_up_two");
}

TEST(GltfExtensions, OneUnsupportedRequiredIsNamed) {
    TempDir dir;
    const Result<Scene> scene = load_text(dir, triangle_gltf(R"(
  "extensionsUsed": ["KHR_made_up_one"], "extensionsRequired": ["KHR_made_up_one"],)"));
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().message, dir.file("model.gltf").string() + ": requires unsupported extension KHR_made_up_one");
}

TEST(GltfExtensions, UnknownUsedIsAWarningNamingIt) {
    TempDir dir;
    const Result<Scene> scene = load_text(dir, triangle_gltf(R"(
  "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_made_up_glass", "KHR_made_up_glass"],)"));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_EQ(scene->warnings[0], "extension KHR_made_up_glass is used by the file but not implemented: ignored");
    EXPECT_EQ(scene->vertices.size(), 3u);
}

TEST(GltfExtensions, NoListsNoWarnings) {
    TempDir dir;
    const Result<Scene> scene = load_text(dir, triangle_gltf(""));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->warnings.empty());
}

std::vector<uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }
std::string text_of(const std::vector<uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

TEST(GltfCompressedJson, FallbackBufferGetsAOneByteUri) {
    const std::string json = R"({"buffers": [{"uri": "a.bin", "byteLength": 10},
        {"byteLength": 4000, "extensions": {"EXT_meshopt_compression": {"fallback": true}}},
        {"byteLength": 5, "extensions": {"EXT_meshopt_compression": {"fallback": false}}}]})";
    std::vector<uint8_t> out;
    ASSERT_TRUE(prepare_compressed_json(bytes_of(json), false, out));
    EXPECT_EQ(text_of(out), R"({"buffers": [{"uri": "a.bin", "byteLength": 10},
        {"byteLength": 1, "uri": "data:application/octet-stream;base64,AA==", "extensions": {"EXT_meshopt_compression": {"fallback": true}}},
        {"byteLength": 5, "extensions": {"EXT_meshopt_compression": {"fallback": false}}}]})");
}

TEST(GltfCompressedJson, DracoIndicesAccessorGetsTheDracoView) {
    const std::string json = R"({"accessors": [{"count": 3}, {"bufferView": 0, "count": 3}, {"count": 3}],
  "meshes": [{"primitives": [{"indices": 2, "attributes": {"POSITION": 0},
     "extensions": {"KHR_draco_mesh_compression": {"bufferView": 7, "attributes": {"POSITION": 0}}}}]}]})";
    std::vector<uint8_t> out;
    ASSERT_TRUE(prepare_compressed_json(bytes_of(json), false, out));
    EXPECT_EQ(text_of(out), R"({"accessors": [{"count": 3}, {"bufferView": 0, "count": 3}, {"bufferView": 7, "count": 3}],
  "meshes": [{"primitives": [{"indices": 2, "attributes": {"POSITION": 0},
     "extensions": {"KHR_draco_mesh_compression": {"bufferView": 7, "attributes": {"POSITION": 0}}}}]}]})");
}

TEST(GltfCompressedJson, LeavesOtherAndMalformedFilesAlone) {
    std::vector<uint8_t> out = {42};
    for (const std::string json : {std::string(R"({"buffers": [{"byteLength": 4}]})"),
                                   std::string(R"({"buffers": [{"byteLength": 4, "extensions": {"EXT_meshopt_compression": {"fallback": true})"),
                                   std::string(R"({"meshes": [{"primitives": [{"indices": "x", "extensions": {"KHR_draco_mesh_compression": 1}}]}]})"),
                                   std::string(200, '['), std::string(""), std::string("\"fallback\"")}) {
        EXPECT_FALSE(prepare_compressed_json(bytes_of(json), false, out)) << json;
        EXPECT_FALSE(prepare_compressed_json(bytes_of(json), true, out)) << json;
    }
    EXPECT_EQ(out, std::vector<uint8_t>{42});
}

TEST(GltfCompressedJson, GlbKeepsItsBinChunkAndLengths) {
    TempDir dir;
    test::write_meshopt_gltf(dir.file("grid.glb"), test::wavy_grid(4, 4));
    std::string file;
    {
        std::ifstream in(dir.file("grid.glb"), std::ios::binary);
        file.assign(std::istreambuf_iterator<char>(in), {});
    }
    std::vector<uint8_t> out;
    ASSERT_TRUE(prepare_compressed_json(bytes_of(file), true, out));
    auto u32 = [](const uint8_t* p) { uint32_t v; std::memcpy(&v, p, 4); return v; };
    const uint32_t old_json = u32(reinterpret_cast<const uint8_t*>(&file[12]));
    const uint32_t new_json = u32(&out[12]);
    EXPECT_EQ(new_json % 4, 0u);
    EXPECT_EQ(u32(&out[8]), out.size());
    // The BIN chunk follows, byte for byte.
    EXPECT_EQ(text_of(out).substr(20 + new_json), file.substr(20 + old_json));
    EXPECT_NE(text_of(out).find("base64,AA=="), std::string::npos);
}

}  // namespace
}  // namespace facet
