#pragma once
// Internal to the glTF loader: how its checks report a malformed file.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

namespace facet::gltf_detail {

// Far beyond any real asset: refusing such counts up front keeps a forged file from
// turning into a multi-gigabyte allocation.
constexpr uint64_t kMaxElements = uint64_t(1) << 28;

// Checks throw this and load_gltf turns it into Error{"<path>: <reason>"}, which keeps
// each of the many checks to one line.
struct LoadError {
    std::string reason;
};

[[noreturn]] inline void fail(std::string reason) { throw LoadError{std::move(reason)}; }

inline std::string label(const char* kind, size_t index, const std::string& name) {
    if (name.empty()) return std::string(kind) + " " + std::to_string(index);
    return std::string(kind) + " '" + name + "'";
}

inline bool in_range(int index, size_t size) { return index >= 0 && size_t(index) < size; }

}  // namespace facet::gltf_detail
