#pragma once
// Small glTF files written by the tests themselves: a JSON document and one external
// .bin in a temporary folder, built accessor by accessor.
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <facet/scene/gltf_loader.h>

namespace facet::test {

// glTF component types.
constexpr int kByte = 5120, kUbyte = 5121, kShort = 5122, kUshort = 5123, kUint = 5125, kFloat = 5126;

struct GltfTempDir {
    std::filesystem::path path;
    explicit GltfTempDir(const std::string& tag) {
        path = std::filesystem::temp_directory_path() / ("facet_" + tag + "_" + std::to_string(::getpid()));
        std::filesystem::create_directories(path);
    }
    ~GltfTempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

inline void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

// Each view() appends a bufferView of the bytes given; each accessor() an accessor.
struct GltfBuilder {
    std::string bin;
    std::vector<std::string> views, accessors;

    template <class T>
    int view(const std::vector<T>& data) {
        while (bin.size() % 4 != 0) bin.push_back('\0');
        const size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(T));
        views.push_back(R"({"buffer": 0, "byteOffset": )" + std::to_string(offset) + R"(, "byteLength": )" +
                        std::to_string(data.size() * sizeof(T)) + "}");
        return int(views.size() - 1);
    }
    // An accessor of `count` elements; `view` -1 leaves bufferView out. `extra`: more
    // members, each starting with a comma (", \"normalized\": true").
    int accessor(int view_index, int component_type, const char* type, size_t count, const std::string& extra = "") {
        std::string text = "{";
        if (view_index >= 0) text += R"("bufferView": )" + std::to_string(view_index) + ", ";
        text += R"("componentType": )" + std::to_string(component_type) + R"(, "count": )" + std::to_string(count) +
                R"(, "type": ")" + type + "\"" + extra + "}";
        accessors.push_back(text);
        return int(accessors.size() - 1);
    }
    // Both at once: the data in its own view, `count` elements.
    template <class T>
    int add(const std::vector<T>& data, int component_type, const char* type, size_t count,
            const std::string& extra = "") {
        return accessor(view(data), component_type, type, count, extra);
    }

    static std::string join(const std::vector<std::string>& items) {
        std::string out;
        for (const std::string& item : items) out += (out.empty() ? "" : ",\n    ") + item;
        return out;
    }
    // `members`: the rest of the top-level object (meshes, nodes, ...), no trailing comma.
    std::string json(const std::string& bin_name, const std::string& members) const {
        return "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"buffers\": [{\"uri\": \"" + bin_name +
               "\", \"byteLength\": " + std::to_string(bin.size()) + "}],\n  \"bufferViews\": [\n    " + join(views) +
               "],\n  \"accessors\": [\n    " + join(accessors) + "],\n  " + members + "\n}\n";
    }
    // Writes NAME.gltf and NAME.bin into `dir`; returns the .gltf's path.
    std::string write(const GltfTempDir& dir, const std::string& name, const std::string& members) const {
        write_bytes(dir.file(name + ".bin"), bin);
        write_bytes(dir.file(name + ".gltf"), json(name + ".bin", members));
        return dir.file(name + ".gltf");
    }
};

// Loading `path` fails with one message that starts with the path and names `phrase`.
inline void expect_error(const std::string& path, const std::string& phrase) {
    Result<Scene> scene = load_gltf(path);
    ASSERT_FALSE(scene.ok()) << path;
    const std::string& message = scene.error().message;
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(phrase), std::string::npos) << "expected '" << phrase << "' in: " << message;
}

}  // namespace facet::test
