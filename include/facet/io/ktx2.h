#pragma once
// KTX 2.0 files (Khronos "KTX File Format Specification", version 2.0), written and read
// by Facet's own code: uncompressed float formats, 2D or cube, any number of mip levels,
// no supercompression — the shape the Khronos glTF IBL sampler writes, so that glTF
// viewers load what facet-bake produces.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <facet/core/result.h>

namespace facet {

struct Ktx2Image {
    // R16G16_SFLOAT, R32G32_SFLOAT, R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT.
    VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT;
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t faces = 1;   // 1 (2D) or 6 (cube, Vulkan order +X,-X,+Y,-Y,+Z,-Z); 6 needs width == height
    uint32_t levels = 1;  // mip levels present, level 0 = full size
    // level_data[l]: faces * max(1, width >> l) * max(1, height >> l) texels, tightly
    // packed, face 0 first, row 0 first within a face.
    std::vector<std::vector<std::byte>> level_data;
    // Written sorted by key (the specification requires byte order); values are stored
    // NUL-terminated and read back without the NUL.
    std::vector<std::pair<std::string, std::string>> key_values;
};

// Bytes of one texel of a supported format; 0 for formats this module does not handle.
uint32_t ktx2_texel_size(VkFormat format);

// Bytes level `level` of `image` must hold (from format, size, faces).
uint64_t ktx2_level_size(const Ktx2Image& image, uint32_t level);

// Writes atomically (no partial file under `path` on failure). Errors name the file and
// the reason (unsupported format, level size mismatch, cannot write, ...).
Status write_ktx2(const std::string& path, const Ktx2Image& image);
// The same with the levels' bytes where they lie (a mapped readback buffer, say) instead
// of image.level_data, which is not read.
Status write_ktx2(const std::string& path, const Ktx2Image& image, std::span<const std::span<const std::byte>> levels);

// Validates the whole file before trusting any offset or length; a truncated, corrupt or
// unsupported file gives an Error naming the file and the problem.
Result<Ktx2Image> read_ktx2(const std::string& path);
// The same from the file's bytes, already read (`path` names it in errors).
Result<Ktx2Image> parse_ktx2(const std::vector<std::byte>& bytes, const std::string& path);

// IEEE 754 binary32 <-> binary16, rounding to nearest even; infinities, NaNs (kept
// quiet, top payload bits kept) and denormals handled. For converting RGBA32F to RGBA16F.
uint16_t float_to_half(float f);
float half_to_float(uint16_t h);

}  // namespace facet
