#pragma once
// Equirectangular environments from files (.hdr, read by Facet's own decoder,
// io/image_codecs.h; .exr and anything else OpenImageIO reads as floating point), any size and aspect, checked texel by texel: NaN, Inf or
// negative radiance is an error naming the file and the first bad texel, unless the
// caller asks for sanitising (then such texels become 0 and are counted).
//
// Large files (README, "Large inputs"): the header is read first, and a size beyond
// the hard limits below is refused before anything is allocated. A file wider than
// `max_width` (or taller than half of it) is downsampled while it is read, a band of
// rows at a time, with the solid-angle box filter of io/box_downsample.h, so peak
// memory is the output (16 bytes a texel: 128 MiB at the default 4096 x 2048) plus one
// band of source rows (32 rows, or one row of tiles, of at most 256 MiB), whatever the
// file's size. Every source texel is still checked.
#include <cstdint>
#include <string>
#include <vector>

#include <facet/core/result.h>

namespace facet {

// The hard limits: 65536 texels a side and 2^31 texels (65536 x 32768), far beyond any
// published environment (the largest are 24k x 12k) yet small enough that reading one
// band of rows stays bounded.
constexpr uint32_t kMaxEnvironmentSide = 65536;
constexpr uint64_t kMaxEnvironmentTexels = uint64_t(1) << 31;
// Wider files are downsampled to fit max_width x max_width / 2 (128 MiB as RGBA32F).
constexpr uint32_t kDefaultMaxEnvironmentWidth = 4096;

struct EnvironmentImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rgba;       // linear radiance, row 0 = top row of the file (+Y)
    std::string content_hash;      // of the decoded texels and size (16 hex digits)
    uint64_t sanitized_texels = 0;  // source texels replaced when sanitising
    uint32_t source_width = 0, source_height = 0;  // the file's size
    bool downsampled() const { return width != source_width || height != source_height; }
};

struct EnvironmentLoadOptions {
    bool sanitize = false;
    uint32_t max_width = kDefaultMaxEnvironmentWidth;  // the height may be up to half of it
};

Result<EnvironmentImage> load_environment(const std::string& path, const EnvironmentLoadOptions& options = {});

}  // namespace facet
