#pragma once
// 64-bit FNV-1a: content keys for caches and bake outputs (not cryptographic).
#include <cstdint>
#include <string>
#include <string_view>

namespace facet {

struct Hash64 {
    std::uint64_t state = 0xcbf29ce484222325ull;

    Hash64& add(const void* data, std::size_t size);
    Hash64& add(std::string_view text) { return add(text.data(), text.size()); }
    std::uint64_t value() const { return state; }
    std::string hex() const;  // 16 lowercase hex digits
};

}  // namespace facet
