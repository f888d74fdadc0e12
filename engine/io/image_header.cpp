#include "io/image_header.h"

#include <cstring>

namespace facet {

namespace {

uint32_t be16(const uint8_t* p) { return uint32_t(p[0]) << 8 | p[1]; }
uint32_t be32(const uint8_t* p) { return be16(p) << 16 | be16(p + 2); }

std::optional<ImageHeader> png_header(const uint8_t* bytes, size_t size) {
    // Signature, then IHDR, which the format requires to come first.
    if (size < 33 || std::memcmp(bytes + 12, "IHDR", 4) != 0 || be32(bytes + 8) != 13) return std::nullopt;
    ImageHeader h;
    h.format = "png";
    h.width = be32(bytes + 16);
    h.height = be32(bytes + 20);
    const uint8_t depth = bytes[24], colour = bytes[25], interlace = bytes[28];
    switch (colour) {
    case 0: h.channels = 1; break;
    case 2: h.channels = 3; break;
    case 3: h.channels = 4; break;  // palette: RGB, or RGBA with a tRNS chunk
    case 4: h.channels = 2; break;
    case 6: h.channels = 4; break;
    default: return std::nullopt;
    }
    h.bytes_per_channel = depth == 16 ? 2 : 1;
    h.row_by_row = interlace == 0;
    return h;
}

std::optional<ImageHeader> jpeg_header(const uint8_t* bytes, size_t size) {
    size_t at = 2;
    while (at + 4 <= size) {
        if (bytes[at] != 0xFF) return std::nullopt;
        const uint8_t marker = bytes[at + 1];
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // no length
            at += 2;
            continue;
        }
        const size_t length = be16(bytes + at + 2);
        if (length < 2) return std::nullopt;
        // Start of frame: every SOFn but DHT (C4), JPG (C8) and DAC (CC).
        const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (frame) {
            if (at + 10 > size || length < 8) return std::nullopt;
            ImageHeader h;
            h.format = "jpeg";
            h.height = be16(bytes + at + 5);
            h.width = be16(bytes + at + 7);
            h.channels = bytes[at + 9] == 1 ? 1 : 3;
            // Progressive (C2, C6, CA, CE) keeps every coefficient until the last scan.
            h.row_by_row = !(marker == 0xC2 || marker == 0xC6 || marker == 0xCA || marker == 0xCE);
            return h;
        }
        if (marker == 0xDA || marker == 0xD9) return std::nullopt;  // scan data before any frame
        at += 2 + length;
    }
    return std::nullopt;
}

uint32_t le16(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8; }
uint32_t le24(const uint8_t* p) { return le16(p) | uint32_t(p[2]) << 16; }

// RIFF "WEBP" with its first chunk: VP8 (lossy), VP8L (lossless) or VP8X (extended).
std::optional<ImageHeader> webp_header(const uint8_t* bytes, size_t size) {
    if (size < 30) return std::nullopt;
    ImageHeader h;
    h.format = "webp";
    h.row_by_row = false;  // libwebp decodes the whole image
    const uint8_t* chunk = bytes + 12;
    const uint8_t* data = bytes + 20;
    if (std::memcmp(chunk, "VP8 ", 4) == 0) {
        if (data[3] != 0x9D || data[4] != 0x01 || data[5] != 0x2A) return std::nullopt;  // key frame start code
        h.width = le16(data + 6) & 0x3FFF;
        h.height = le16(data + 8) & 0x3FFF;
        h.channels = 3;
    } else if (std::memcmp(chunk, "VP8L", 4) == 0) {
        if (data[0] != 0x2F) return std::nullopt;
        const uint32_t bits = le16(data + 1) | le16(data + 3) << 16;
        h.width = (bits & 0x3FFF) + 1;
        h.height = ((bits >> 14) & 0x3FFF) + 1;
        h.channels = (bits >> 28) & 1 ? 4 : 3;
    } else if (std::memcmp(chunk, "VP8X", 4) == 0) {
        h.width = le24(data + 4) + 1;
        h.height = le24(data + 7) + 1;
        h.channels = data[0] & 0x10 ? 4 : 3;
    } else {
        return std::nullopt;
    }
    return h;
}

}  // namespace

std::optional<ImageHeader> read_image_header(const uint8_t* bytes, size_t size) {
    static const uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (size >= 8 && std::memcmp(bytes, png_signature, 8) == 0) return png_header(bytes, size);
    if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return jpeg_header(bytes, size);
    if (size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0)
        return webp_header(bytes, size);
    return std::nullopt;
}

}  // namespace facet
