#pragma once
// Image files: linear HDR (.exr, .hdr) and 8-bit previews (.png), written by Facet's own
// encoders (no OpenImageIO, so writing loads no image module).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <facet/core/result.h>

namespace facet {

// Linear RGBA float texels, row 0 = top row of the file. .exr keeps 32-bit float RGBA
// (ZIP compressed); .hdr (RGBE) keeps RGB. Written atomically; the error names the file
// and the reason.
Status write_hdr_image(const std::string& path, uint32_t width, uint32_t height,
                       std::span<const float> rgba);

// The bytes write_hdr_image(path, ...) writes (.exr or .hdr by `path`'s extension), made
// in memory: a program encodes a file ahead of the moment it writes it
// (write_binary_file). An .exr's compression runs on `threads` threads (0: one per core,
// up to 4, as write_hdr_image; 1: the calling thread only, for work beside other work);
// the bytes are the same. Errors name `path`.
Result<std::vector<uint8_t>> encode_hdr_image(const std::string& path, uint32_t width, uint32_t height,
                                              std::span<const float> rgba, uint32_t threads = 0);

// Loads the module that reads image files other than Radiance .hdr (OpenImageIO and its
// libraries: about 0.3 s of CPU) now, so that the first such read does not pay for it;
// run on a worker thread, it overlaps other work. Writing .exr, .hdr and .png never needs
// it. Thread-safe; a failure to load is left to that first read to report.
void preload_image_io();

// 8-bit RGBA (already tone-mapped and encoded), straight alpha. Written atomically: a
// .png by Facet's encoder (zlib level 1, run-length matches), any other extension (.jpg,
// .tif, ...) in the format it names through the image module.
Status write_ldr_image(const std::string& path, uint32_t width, uint32_t height,
                       std::span<const uint8_t> rgba);

}  // namespace facet
