#include "scene/gltf_decompress_json.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <string_view>

namespace facet::gltf_detail {

namespace {

// A minimal JSON walker: only spans of values are needed, not their meaning. Every
// function returns npos on malformed text, and the caller then leaves the file alone.
constexpr size_t npos = std::string_view::npos;

size_t skip_space(std::string_view s, size_t i) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
    return i;
}

// s[i] == '"': the index past the closing quote.
size_t skip_string(std::string_view s, size_t i) {
    for (++i; i < s.size(); ++i) {
        if (s[i] == '\\') ++i;
        else if (s[i] == '"') return i + 1;
    }
    return npos;
}

// The index past the value starting at i (after spaces); depth-limited so that a forged
// file cannot exhaust the stack.
size_t skip_value(std::string_view s, size_t i, int depth = 0) {
    i = skip_space(s, i);
    if (i >= s.size() || depth > 64) return npos;
    if (s[i] == '"') return skip_string(s, i);
    if (s[i] == '{' || s[i] == '[') {
        const char close = s[i] == '{' ? '}' : ']';
        i = skip_space(s, i + 1);
        if (i < s.size() && s[i] == close) return i + 1;
        while (i < s.size()) {
            if (close == '}') {
                if (s[i] != '"') return npos;
                i = skip_space(s, skip_string(s, i));
                if (i >= s.size() || s[i] != ':') return npos;
                ++i;
            }
            i = skip_space(s, skip_value(s, i, depth + 1));
            if (i >= s.size()) return npos;
            if (s[i] == close) return i + 1;
            if (s[i] != ',') return npos;
            i = skip_space(s, i + 1);
        }
        return npos;
    }
    while (i < s.size() && std::strchr(",}] \t\n\r", s[i]) == nullptr) ++i;  // number, true, false, null
    return i;
}

struct Member {
    std::string_view key;
    size_t value = 0, end = 0;  // the value's span in the text
};

// The members of the object starting at `at` (after spaces), or false.
bool members(std::string_view s, size_t at, std::vector<Member>& out) {
    size_t i = skip_space(s, at);
    if (i >= s.size() || s[i] != '{') return false;
    i = skip_space(s, i + 1);
    if (i < s.size() && s[i] == '}') return true;
    while (i < s.size() && s[i] == '"') {
        const size_t key_end = skip_string(s, i);
        if (key_end == npos) return false;
        Member m;
        m.key = s.substr(i + 1, key_end - i - 2);
        i = skip_space(s, key_end);
        if (i >= s.size() || s[i] != ':') return false;
        m.value = skip_space(s, i + 1);
        m.end = skip_value(s, m.value);
        if (m.end == npos) return false;
        out.push_back(m);
        i = skip_space(s, m.end);
        if (i < s.size() && s[i] == '}') return true;
        if (i >= s.size() || s[i] != ',') return false;
        i = skip_space(s, i + 1);
    }
    return false;
}

const Member* find(const std::vector<Member>& list, std::string_view key) {
    for (const Member& m : list)
        if (m.key == key) return &m;
    return nullptr;
}

bool is_fallback(std::string_view s, const std::vector<Member>& buffer) {
    const Member* extensions = find(buffer, "extensions");
    std::vector<Member> ext, meshopt;
    if (!extensions || !members(s, extensions->value, ext)) return false;
    const Member* m = find(ext, "EXT_meshopt_compression");
    if (!m || !members(s, m->value, meshopt)) return false;
    const Member* fallback = find(meshopt, "fallback");
    return fallback && s.substr(fallback->value, fallback->end - fallback->value) == "true";
}

// A non-negative integer value's digits, or -1.
int64_t integer(std::string_view s, const Member& m) {
    const std::string_view digits = s.substr(m.value, m.end - m.value);
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != npos) return -1;
    return std::stoll(std::string(digits));
}

struct Edit {
    size_t at = 0, erase = 0;
    std::string insert;
};

// Calls f(index, start) for each element of the array value of `member` (objects only).
template <class F>
bool for_each_object(std::string_view s, const Member* member, F f) {
    if (!member || s[member->value] != '[') return member == nullptr;
    size_t i = skip_space(s, member->value + 1);
    for (int64_t index = 0; i < member->end && s[i] == '{'; ++index) {
        if (!f(index, i)) return false;
        i = skip_space(s, skip_value(s, i));
        if (i < member->end && s[i] == ',') i = skip_space(s, i + 1);
    }
    return true;
}

void fallback_buffers(std::string_view s, const std::vector<Member>& top, std::vector<Edit>& edits) {
    for_each_object(s, find(top, "buffers"), [&](int64_t, size_t at) {
        std::vector<Member> buffer;
        if (!members(s, at, buffer)) return false;
        const Member* length = find(buffer, "byteLength");
        if (!length || !is_fallback(s, buffer)) return true;
        const std::string one_byte = "\"data:application/octet-stream;base64,AA==\"";
        if (const Member* uri = find(buffer, "uri")) {  // a fallback file (gltfpack -cf): not read either
            edits.push_back({length->value, length->end - length->value, "1"});
            edits.push_back({uri->value, uri->end - uri->value, one_byte});
        } else {
            edits.push_back({length->value, length->end - length->value, "1, \"uri\": " + one_byte});
        }
        return true;
    });
}

void draco_indices(std::string_view s, const std::vector<Member>& top, std::vector<Edit>& edits) {
    std::map<int64_t, int64_t> view_of;  // indices accessor -> the primitive's Draco bufferView
    for_each_object(s, find(top, "meshes"), [&](int64_t, size_t at) {
        std::vector<Member> mesh;
        if (!members(s, at, mesh)) return false;
        return for_each_object(s, find(mesh, "primitives"), [&](int64_t, size_t p) {
            std::vector<Member> primitive, extensions, draco;
            if (!members(s, p, primitive)) return false;
            const Member* indices = find(primitive, "indices");
            const Member* ext = find(primitive, "extensions");
            if (!indices || !ext || !members(s, ext->value, extensions)) return true;
            const Member* d = find(extensions, "KHR_draco_mesh_compression");
            if (!d || !members(s, d->value, draco)) return true;
            const Member* view = find(draco, "bufferView");
            if (view && integer(s, *indices) >= 0 && integer(s, *view) >= 0)
                view_of[integer(s, *indices)] = integer(s, *view);
            return true;
        });
    });
    if (view_of.empty()) return;
    for_each_object(s, find(top, "accessors"), [&](int64_t index, size_t at) {
        std::vector<Member> accessor;
        if (!members(s, at, accessor)) return false;
        auto it = view_of.find(index);
        if (it != view_of.end() && !find(accessor, "bufferView"))
            edits.push_back({at + 1, 0,
                             "\"bufferView\": " + std::to_string(it->second) + (accessor.empty() ? "" : ", ")});
        return true;
    });
}

constexpr std::string_view kWebpUri = "\"data:image/webp;base64,";

void webp_data_uris(std::string_view s, std::vector<Edit>& edits) {
    for (size_t at = s.find(kWebpUri); at != npos; at = s.find(kWebpUri, at + 1))
        edits.push_back({at, kWebpUri.size(), "\"data:application/octet-stream;base64,"});
}

// The JSON with the rewrites applied, or empty if none applies.
std::string rewrite(std::string_view s) {
    std::vector<Member> top;
    const bool meshopt = s.find("\"fallback\"") != npos, draco = s.find("KHR_draco_mesh_compression") != npos;
    const bool webp = s.find(kWebpUri) != npos;
    if ((!meshopt && !draco && !webp) || !members(s, 0, top)) return {};
    std::vector<Edit> edits;
    if (meshopt) fallback_buffers(s, top, edits);
    if (draco) draco_indices(s, top, edits);
    if (webp) webp_data_uris(s, edits);
    if (edits.empty()) return {};
    std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.at < b.at; });
    std::string out;
    size_t copied = 0;
    for (const Edit& e : edits) {
        out.append(s.substr(copied, e.at - copied));
        out.append(e.insert);
        copied = e.at + e.erase;
    }
    out.append(s.substr(copied));
    return out;
}

uint32_t read_u32(const uint8_t* p) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

void append_u32(std::vector<uint8_t>& out, uint32_t v) {
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    out.insert(out.end(), p, p + 4);
}

}  // namespace

bool prepare_compressed_json(const std::vector<uint8_t>& file, bool glb, std::vector<uint8_t>& out) {
    if (!glb) {
        const std::string json = rewrite({reinterpret_cast<const char*>(file.data()), file.size()});
        if (json.empty()) return false;
        out.assign(json.begin(), json.end());
        return true;
    }
    // GLB: 12-byte header, then the JSON chunk (length, type, bytes), then the rest as is.
    if (file.size() < 20 || read_u32(&file[16]) != 0x4E4F534Au) return false;
    const uint64_t json_length = read_u32(&file[12]);
    if (20 + json_length > file.size()) return false;
    std::string json = rewrite({reinterpret_cast<const char*>(&file[20]), size_t(json_length)});
    if (json.empty()) return false;
    while (json.size() % 4 != 0) json.push_back(' ');  // chunks stay 4-byte aligned
    const size_t rest = 20 + size_t(json_length);
    const uint64_t total = read_u32(&file[8]);  // the header's length; bytes past it stay past it
    if (total < rest || total > file.size() || total - rest + 20 + json.size() > UINT32_MAX) return false;
    out.clear();
    out.reserve(20 + json.size() + file.size() - rest);
    out.insert(out.end(), file.begin(), file.begin() + 8);  // magic, version
    append_u32(out, uint32_t(total - rest + 20 + json.size()));
    append_u32(out, uint32_t(json.size()));
    append_u32(out, 0x4E4F534Au);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    out.insert(out.end(), file.begin() + long(rest), file.end());
    return true;
}

}  // namespace facet::gltf_detail
