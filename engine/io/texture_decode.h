#pragma once
// Decoding a large PNG or JPEG held in memory a band of rows at a time (OpenImageIO
// over the bytes), box-downsampled while it is read (io/box_downsample.h): peak memory
// is the 8-bit output plus a few source rows, not the decoded source. Means of sRGB
// textures are taken in linear light, as the GPU's mip blits of an _SRGB image do.
#include <cstddef>
#include <cstdint>
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

}  // namespace facet
