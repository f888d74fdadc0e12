#pragma once
// Decoding a large PNG or JPEG held in memory a band of rows at a time (OpenImageIO
// over the bytes), box-downsampled while it is read (io/box_downsample.h): peak memory
// is the 8-bit output plus a few source rows, not the decoded source. Means of sRGB
// textures are taken in linear light, as the GPU's mip blits of an _SRGB image do.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <facet/core/result.h>
#include "io/image_header.h"

namespace facet {

struct Rgba8Image {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;  // row 0 = the file's top row
};

// `header` as read_image_header() gave it; `width` x `height` at most the source's
// (equal: decoded as it is). Errors carry the decoder's reason, not a file name.
Result<Rgba8Image> decode_texture_rows(const uint8_t* bytes, size_t size, const ImageHeader& header, uint32_t width,
                                       uint32_t height, bool srgb);

// Decoded textures kept by content, process-wide: a viewer loading the same model again
// (another environment chosen) and a bench rendering it again decode nothing twice. The
// key is the encoded bytes' content (64-bit FNV-1a and their size) and what decides the
// result (the kept size, sRGB means, the decoder); the cache holds at most its capacity
// in decoded bytes, least recently used out first, and no image over an eighth of it
// (a large texture is not kept twice in memory at its peak). Thread-safe; a decode
// runs outside the lock.
struct TextureDecodeSettings {
    uint32_t width = 0, height = 0;  // as kept
    bool srgb = false;
    uint32_t decoder = 0;  // which decoder (the caller's numbering): another decoder, another result
};
// `decode` runs on a miss; what it throws passes through and nothing is kept.
Rgba8Image decode_texture_cached(std::span<const uint8_t> bytes, const TextureDecodeSettings& settings,
                                 const std::function<Rgba8Image()>& decode);

struct TextureCacheStats {
    uint64_t decodes = 0;  // misses: `decode` called
    uint64_t hits = 0;
    uint64_t evictions = 0;
    uint64_t bytes_kept = 0;
    uint64_t capacity_bytes = 0;
};
TextureCacheStats texture_cache_stats();
// Default 256 MiB; 0 keeps nothing. Evicts down to the new capacity at once.
void set_texture_cache_capacity(uint64_t bytes);

}  // namespace facet
