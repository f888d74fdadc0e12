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

#include <OpenImageIO/imageio.h>

#include <facet/scene/gltf_loader.h>
#include "io/image_header.h"
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
    for (const char* name : {"EXT_meshopt_compression", "EXT_texture_webp", "KHR_draco_mesh_compression",
                             "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_ior",
                             "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_unlit",
                             "KHR_materials_volume", "KHR_mesh_quantization", "KHR_texture_transform"})
        EXPECT_TRUE(is_supported_extension(name)) << name;
    EXPECT_EQ(gltf_supported_extensions(), std::vector<std::string>(names.begin(), names.end()));
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

// An RGBA8 PNG written by OpenImageIO.
void write_image(const fs::path& path, int width, int height, const std::vector<uint8_t>& rgba) {
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    ASSERT_TRUE(out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) && out->close())
        << out->geterror();
}

std::string textured_triangle(const std::string& texture) {
    std::string text = triangle_gltf(R"(
  "extensionsUsed": ["EXT_texture_webp"],
  "images": [{"uri": "fallback.png"}, {"uri": "texture.webp"}],
  "textures": [)" + texture + R"(],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],)");
    const std::string from = R"({"attributes": {"POSITION": 0}})";
    text.replace(text.find(from), from.size(), R"({"attributes": {"POSITION": 0}, "material": 0})");
    return text;
}

using test::kWebp;
using test::kWebpTexels;

TEST(GltfExtensions, WebpSourceReplacesTheFallback) {
    TempDir dir;
    test::write_bytes(dir.file("texture.webp"), kWebp, sizeof kWebp);
    write_image(dir.file("fallback.png"), 3, 2, std::vector<uint8_t>(24, 99));
    Result<Scene> scene = load_text(dir, textured_triangle(R"({"source": 0, "extensions": {"EXT_texture_webp": {"source": 1}}})"));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->warnings.empty());
    ASSERT_EQ(scene->materials.size(), 1u);
    const int image = scene->materials[0].base_color_texture.image;
    ASSERT_EQ(image, 1);
    const TextureImage& texture = scene->images[size_t(image)];
    ASSERT_EQ(texture.width, 3u);
    ASSERT_EQ(texture.height, 2u);
    ASSERT_EQ(texture.rgba.size(), kWebpTexels.size());
    // Colour comes back through the reader's 8-bit premultiplication: within 255 / alpha
    // codes of the straight value (exact where alpha is 255).
    for (size_t i = 0; i < kWebpTexels.size(); ++i) {
        const int alpha = kWebpTexels[i / 4 * 4 + 3];
        const int tolerance = i % 4 == 3 ? 0 : (255 + alpha - 1) / alpha;
        EXPECT_NEAR(int(texture.rgba[i]), int(kWebpTexels[i]), tolerance) << "byte " << i;
    }
}

TEST(GltfExtensions, WebpHeadersGiveTheirSize) {
    auto riff = [](const char* chunk, std::vector<uint8_t> data) {
        std::vector<uint8_t> bytes = {'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W', 'E', 'B', 'P'};
        for (int i = 0; i < 4; ++i) bytes.push_back(uint8_t(chunk[i]));
        bytes.insert(bytes.end(), {0, 0, 0, 0});
        bytes.insert(bytes.end(), data.begin(), data.end());
        bytes.resize(std::max<size_t>(bytes.size(), 40), 0);
        return bytes;
    };
    // Lossless: 14-bit width - 1 and height - 1 after the 0x2f signature, then the alpha bit.
    auto lossless = read_image_header(kWebp, sizeof kWebp);
    ASSERT_TRUE(lossless);
    EXPECT_EQ(lossless->format, "webp");
    EXPECT_EQ(lossless->width, 3u);
    EXPECT_EQ(lossless->height, 2u);
    EXPECT_EQ(lossless->channels, 4u);
    // Lossy key frame: 3 tag bytes, 9d 01 2a, 14-bit width and height (640 x 480).
    const std::vector<uint8_t> vp8 = riff("VP8 ", {0, 0, 0, 0x9d, 0x01, 0x2a, 0x80, 0x02, 0xe0, 0x01});
    auto lossy = read_image_header(vp8.data(), vp8.size());
    ASSERT_TRUE(lossy);
    EXPECT_EQ(lossy->width, 640u);
    EXPECT_EQ(lossy->height, 480u);
    EXPECT_EQ(lossy->channels, 3u);
    // Extended: flags (0x10 alpha), 3 reserved bytes, 24-bit width - 1 and height - 1 (5000 x 70000 - 1).
    const std::vector<uint8_t> vp8x = riff("VP8X", {0x10, 0, 0, 0, 0x87, 0x13, 0x00, 0x6f, 0x11, 0x01});
    auto extended = read_image_header(vp8x.data(), vp8x.size());
    ASSERT_TRUE(extended);
    EXPECT_EQ(extended->width, 5000u);
    EXPECT_EQ(extended->height, 70000u);
    EXPECT_EQ(extended->channels, 4u);
    // A lossy frame without its start code, an unknown chunk and a cut file: nothing.
    const std::vector<uint8_t> broken = riff("VP8 ", {0, 0, 0, 0x9d, 0x01, 0x2b});
    EXPECT_FALSE(read_image_header(broken.data(), broken.size()));
    const std::vector<uint8_t> unknown = riff("ABCD", {0});
    EXPECT_FALSE(read_image_header(unknown.data(), unknown.size()));
    EXPECT_FALSE(read_image_header(kWebp, 20));
}

TEST(GltfExtensions, WebpSourceOutOfRangeIsAnError) {
    TempDir dir;
    test::write_bytes(dir.file("texture.webp"), kWebp, sizeof kWebp);
    write_image(dir.file("fallback.png"), 1, 1, {1, 2, 3, 255});
    Result<Scene> scene = load_text(dir, textured_triangle(R"({"source": 0, "extensions": {"EXT_texture_webp": {"source": 4}}})"));
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.error().message.find("texture 0 (EXT_texture_webp): source 4 out of range"), std::string::npos)
        << scene.error().message;
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

TEST(GltfCompressedJson, FallbackFileIsNotRead) {
    const std::string json = R"({"buffers": [{"byteLength": 4000, "uri": "m.fallback.bin",
        "extensions": {"EXT_meshopt_compression": {"fallback": true}}}]})";
    std::vector<uint8_t> out;
    ASSERT_TRUE(prepare_compressed_json(bytes_of(json), false, out));
    EXPECT_EQ(text_of(out), R"({"buffers": [{"byteLength": 1, "uri": "data:application/octet-stream;base64,AA==",
        "extensions": {"EXT_meshopt_compression": {"fallback": true}}}]})");
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

TEST(GltfCompressedJson, WebpDataUriBecomesOctetStream) {
    const std::string json = R"({"images": [{"uri": "data:image/webp;base64,UklG"}, {"uri": "data:image/png;base64,iVBO"}]})";
    std::vector<uint8_t> out;
    ASSERT_TRUE(prepare_compressed_json(bytes_of(json), false, out));
    EXPECT_EQ(text_of(out),
              R"({"images": [{"uri": "data:application/octet-stream;base64,UklG"}, {"uri": "data:image/png;base64,iVBO"}]})");
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
