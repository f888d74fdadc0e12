#pragma once
// The memory layout glslang gave a struct, read from the SPIR-V it compiled: member
// names and Offset decorations, and the ArrayStride of an array of it. The tests compare
// it with the C++ mirror of the struct (offsetof, sizeof), so neither side is restated.
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace facet::test {

struct SpirvStructLayout {
    std::map<std::string, uint32_t> offsets;  // member name -> byte offset
    std::optional<uint32_t> array_stride;     // of an array (or runtime array) of the struct
};

inline std::string spirv_string(std::span<const uint32_t> words, size_t first, size_t end) {
    std::string s;
    for (size_t i = first; i < end; ++i)
        for (int b = 0; b < 4; ++b) {
            char c = char((words[i] >> (8 * b)) & 0xffu);
            if (c == '\0') return s;
            s.push_back(c);
        }
    return s;
}

// The layout of the struct type named `name` (OpName); empty when there is none. glslang
// emits one type per layout (a buffer's copy is decorated, a local copy is not): the
// decorated one is taken.
inline std::optional<SpirvStructLayout> spirv_struct_layout(std::span<const uint32_t> words, const std::string& name) {
    constexpr uint32_t op_name = 5, op_member_name = 6, op_decorate = 71, op_member_decorate = 72,
                       op_type_array = 28, op_type_runtime_array = 29;
    constexpr uint32_t decoration_array_stride = 6, decoration_offset = 35;
    struct Found {
        std::map<uint32_t, std::string> member_names;
        std::map<uint32_t, uint32_t> member_offsets;
        std::vector<uint32_t> arrays;
    };
    std::map<uint32_t, Found> found;  // by type id
    std::map<uint32_t, uint32_t> strides;
    for (int pass = 0; pass < 2; ++pass)
        for (size_t at = 5; at < words.size();) {
            const uint32_t count = words[at] >> 16, op = words[at] & 0xffffu;
            if (count == 0 || at + count > words.size()) return std::nullopt;
            if (pass == 0 && op == op_name && spirv_string(words, at + 2, at + count) == name) found[words[at + 1]];
            if (pass == 1) {
                if (op == op_member_name && found.count(words[at + 1]))
                    found[words[at + 1]].member_names[words[at + 2]] = spirv_string(words, at + 3, at + count);
                if (op == op_member_decorate && found.count(words[at + 1]) && words[at + 3] == decoration_offset)
                    found[words[at + 1]].member_offsets[words[at + 2]] = words[at + 4];
                if (op == op_decorate && words[at + 2] == decoration_array_stride)
                    strides[words[at + 1]] = words[at + 3];
                if ((op == op_type_array || op == op_type_runtime_array) && found.count(words[at + 2]))
                    found[words[at + 2]].arrays.push_back(words[at + 1]);
            }
            at += count;
        }
    for (auto& [id, f] : found) {
        if (f.member_offsets.empty()) continue;
        SpirvStructLayout layout;
        for (const auto& [member, offset] : f.member_offsets)
            if (f.member_names.count(member)) layout.offsets[f.member_names[member]] = offset;
        for (uint32_t array : f.arrays)
            if (strides.count(array)) layout.array_stride = strides[array];
        return layout;
    }
    return std::nullopt;
}

}  // namespace facet::test
