#pragma once
// The declared size of a PNG, JPEG or WebP held in memory, read from its header alone
// (PNG's IHDR, JPEG's start-of-frame marker, WebP's first chunk), so that a texture's
// cost is known, and an
// absurd one refused, before any decoder allocates for it.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace facet {

struct ImageHeader {
    std::string format;  // "png", "jpeg" or "webp"
    uint32_t width = 0, height = 0;
    uint32_t channels = 0;           // as decoded: grey 1, grey + alpha 2, RGB 3, RGBA (or palette) 4
    uint32_t bytes_per_channel = 1;  // 2 for 16-bit PNG
    // Decodable a row at a time: not an interlaced PNG, not a progressive JPEG (whose
    // decoders hold the whole image).
    bool row_by_row = true;
};

// Nothing when the bytes are not a PNG, JPEG or WebP, or the header is cut short.
std::optional<ImageHeader> read_image_header(const uint8_t* bytes, size_t size);

}  // namespace facet
