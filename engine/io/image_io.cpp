#include <facet/io/image_io.h>

#include <algorithm>
#include <initializer_list>
#include <memory>
#include <vector>

#include <facet/io/atomic_file.h>
#include "io/image_module_loader.h"

namespace facet {

namespace {

std::string lower_extension(const std::string& path) {
    auto dot = path.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// Writes `path` (a temporary name; messages name `final_path`) through the image module.
Status write_image_file(const std::string& final_path, const std::string& path, uint32_t width, uint32_t height,
                        uint32_t channels, FacetImagePixels pixels, const void* data,
                        std::initializer_list<FacetImageAttribute> attributes) {
    auto module = image_module();
    if (!module) return Error{final_path + ": " + module.error().message};
    char* reason = nullptr;
    if (!module.value()->write(path.c_str(), width, height, channels, pixels, data, attributes.begin(),
                               attributes.size(), &reason))
        return Error{final_path + ": " + take_module_text(*module.value(), reason)};
    return Ok{};
}

}  // namespace

void preload_image_io() { (void)image_module(); }

Status write_hdr_image(const std::string& path, uint32_t width, uint32_t height, std::span<const float> rgba) {
    if (rgba.size() != size_t(width) * height * 4)
        return Error{path + ": pixel buffer does not match " + std::to_string(width) + "x" + std::to_string(height)};
    const std::string ext = lower_extension(path);
    if (ext != ".exr" && ext != ".hdr")
        return Error{path + ": HDR output must be .exr or .hdr"};
    return write_atomically(path, [&](const std::string& temp) -> Status {
        if (ext == ".hdr") {
            std::vector<float> rgb(size_t(width) * height * 3);
            for (size_t i = 0; i < size_t(width) * height; ++i)
                for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = rgba[i * 4 + c];
            return write_image_file(path, temp, width, height, 3, FACET_IMAGE_FLOAT, rgb.data(), {});
        }
        // A fixed capture date: the same texels give the same file (reproducible bakes);
        // when and how a file was made is recorded in its .json beside it.
        return write_image_file(path, temp, width, height, 4, FACET_IMAGE_FLOAT, rgba.data(),
                                {{"compression", "zip", 0}, {"DateTime", "1970:01:01 00:00:00", 0}});
    });
}

Status write_ldr_image(const std::string& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba) {
    if (rgba.size() != size_t(width) * height * 4)
        return Error{path + ": pixel buffer does not match " + std::to_string(width) + "x" + std::to_string(height)};
    return write_atomically(path, [&](const std::string& temp) -> Status {
        // Our texels are straight (unassociated) alpha; stop OIIO from dividing by alpha.
        // zlib's fastest level: a 1024x512 preview in ~1/4 of the default's time, the file
        // at most ~1.3x as large.
        return write_image_file(path, temp, width, height, 4, FACET_IMAGE_UINT8, rgba.data(),
                                {{"oiio:UnassociatedAlpha", nullptr, 1}, {"png:compressionLevel", nullptr, 1}});
    });
}

}  // namespace facet
