#pragma once
// Sizes as people read them in messages.
#include <cstdint>
#include <string>

namespace facet {

std::string format_bytes(uint64_t bytes);  // "1.5 GiB", "12 MiB", "640 KiB"

}  // namespace facet
