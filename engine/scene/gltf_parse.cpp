#include "scene/gltf_parse.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>

#include <facet/core/units.h>
#include "scene/gltf_decompress_json.h"
#include "scene/gltf_errors.h"
#include "scene/gltf_extensions.h"

namespace facet::gltf_detail {

namespace {

namespace fs = std::filesystem;

constexpr uint64_t kMaxFileBytes = uint64_t(INT_MAX);  // tinygltf takes 32-bit sizes

std::string trim(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
}

bool is_glb(const std::string& path, const std::vector<uint8_t>& bytes) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext == ".glb" || (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0);
}

uint32_t read_glb_u32(const uint8_t* p) {
    uint32_t value;
    std::memcpy(&value, p, 4);  // GLB is little-endian, as are the hosts we build for
    return value;
}

// tinygltf checks the chunks too, but says "Invalid glTF binary." for everything. The
// chunk lengths are checked here before tinygltf copies the BIN chunk into a buffer.
void check_glb_header(const std::vector<uint8_t>& bytes) {
    if (bytes.size() < 20) fail("truncated .glb: " + std::to_string(bytes.size()) + " bytes, less than its header");
    if (read_glb_u32(&bytes[4]) != 2) fail(".glb version " + std::to_string(read_glb_u32(&bytes[4])) + " is not 2");
    uint32_t length = read_glb_u32(&bytes[8]);
    if (length > bytes.size())
        fail("truncated .glb: its header says " + std::to_string(length) + " bytes, the file has " +
             std::to_string(bytes.size()));
    const uint64_t bin_at = 20 + uint64_t(read_glb_u32(&bytes[12]));
    if (bin_at > length) fail("truncated .glb: the JSON chunk runs past the end");
    if (bin_at + 8 <= length && bin_at + 8 + uint64_t(read_glb_u32(&bytes[bin_at])) > length)
        fail("truncated .glb: its BIN chunk declares " + std::to_string(read_glb_u32(&bytes[bin_at])) +
             " bytes, more than the file holds after its JSON");
}


// Every external file's size against the budget before tinygltf reads it.
bool read_within_budget(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    FileBudget& budget = *static_cast<FileBudget*>(user);
    std::error_code ec;
    const uint64_t size = fs::file_size(path, ec);
    if (!ec && budget.used + size > budget.limit) {
        budget.refusal = fs::path(path).filename().string() + " is " + format_bytes(size) + "; with the " +
                         format_bytes(budget.used) + " read before it the model exceeds its limit of " +
                         format_bytes(budget.limit) + " of files";
        if (err) *err = budget.refusal;
        return false;
    }
    if (!tinygltf::ReadWholeFile(out, err, path, nullptr)) return false;
    budget.used += out->size();
    return true;
}

// tinygltf decodes images while it parses, before anything is validated, and for an
// image in a bufferView it would read the view without checking it against its
// buffer. So this callback only keeps the encoded bytes of uri images (a vector
// tinygltf owns, so safe to read); decoding happens after validation.
bool keep_encoded_image(tinygltf::Image* image, int index, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void* user) {
    if (image->bufferView >= 0 || size < 0) return true;
    (*static_cast<EncodedImages*>(user))[index].assign(bytes, bytes + size);
    return true;
}

}  // namespace

std::vector<uint8_t> read_file(const std::string& path, FileBudget& budget) {
    std::error_code ec;
    if (!fs::exists(path, ec)) fail("file not found");
    if (!fs::is_regular_file(path, ec)) fail("not a regular file");
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) fail("cannot open file");
    std::streamoff size = in.tellg();
    if (size < 0) fail("cannot read file");
    if (uint64_t(size) > budget.limit)
        fail("the file is " + format_bytes(uint64_t(size)) + ", more than the limit of " + format_bytes(budget.limit) +
             " a model may read");
    if (uint64_t(size) > kMaxFileBytes) fail("file is larger than 2 GiB");
    budget.used += uint64_t(size);
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) fail("cannot read file");
    return bytes;
}

tinygltf::Model parse(const std::string& path, const std::vector<uint8_t>& bytes, EncodedImages& encoded,
                      FileBudget& budget) {
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keep_encoded_image, &encoded);
    loader.SetFsCallbacks({tinygltf::FileExists, tinygltf::ExpandFilePath, read_within_budget, tinygltf::WriteWholeFile,
                           &budget});
    std::string err, warn;
    std::string base_dir = fs::path(path).parent_path().string();
    bool ok = false;
    try {
        std::vector<uint8_t> prepared;  // compressed files' JSON as tinygltf takes it
        const bool glb = is_glb(path, bytes);
        if (glb) check_glb_header(bytes);
        const std::vector<uint8_t>& input = prepare_compressed_json(bytes, glb, prepared) ? prepared : bytes;
        if (glb) {
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, input.data(), unsigned(input.size()), base_dir);
        } else {
            ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(input.data()),
                                            unsigned(input.size()), base_dir);
        }
    } catch (const std::exception& e) {  // the JSON library may throw past tinygltf
        ok = false;
        err = e.what();
    }
    // A refused image is only a warning to tinygltf; the budget's reason wins either way.
    if (!budget.refusal.empty()) fail(budget.refusal);
    if (!ok) fail("glTF parse failed: " + trim(err.empty() ? warn : err));
    apply_extensions(model);  // required extensions checked, compressed meshes decoded
    return model;
}

}  // namespace facet::gltf_detail
