#pragma once
// Image files through OpenImageIO: linear HDR (.exr, .hdr) and 8-bit previews (.png).
#include <cstdint>
#include <span>
#include <string>

#include <facet/core/result.h>

namespace facet {

// Linear RGBA float texels, row 0 = top row of the file. .exr keeps 32-bit float RGBA;
// .hdr (RGBE) keeps RGB. Written atomically; the error names the file and the reason.
Status write_hdr_image(const std::string& path, uint32_t width, uint32_t height,
                       std::span<const float> rgba);

// Loads the module that reads and writes image files (OpenImageIO and its libraries:
// about 0.3 s of CPU) now, so that the first read or write does not pay for it; run on a
// worker thread, it overlaps other work. Thread-safe; a failure to load is left to that
// first read or write to report.
void preload_image_io();

// 8-bit RGBA (already tone-mapped and encoded), e.g. a .png preview. Written atomically.
Status write_ldr_image(const std::string& path, uint32_t width, uint32_t height,
                       std::span<const uint8_t> rgba);

}  // namespace facet
