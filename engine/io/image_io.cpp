#include <facet/io/image_io.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>
#include <vector>

#include <facet/io/atomic_file.h>

namespace facet {

namespace {

std::string lower_extension(const std::string& path) {
    auto dot = path.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

Status write_with_oiio(const std::string& final_path, const std::string& path, const OIIO::ImageSpec& spec,
                       const void* pixels) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return Error{final_path + ": cannot write this format: " + OIIO::geterror()};
    if (!out->open(path, spec)) return Error{final_path + ": cannot open for writing: " + out->geterror()};
    if (!out->write_image(spec.format, pixels)) {
        std::string reason = out->geterror();
        out->close();
        return Error{final_path + ": write failed: " + reason};
    }
    if (!out->close()) return Error{final_path + ": write failed: " + out->geterror()};
    return Ok{};
}

}  // namespace

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
            OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::FLOAT);
            return write_with_oiio(path, temp, spec, rgb.data());
        }
        OIIO::ImageSpec spec(int(width), int(height), 4, OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "zip");
        // A fixed capture date: the same texels give the same file (reproducible bakes);
        // when and how a file was made is recorded in its .json beside it.
        spec.attribute("DateTime", "1970:01:01 00:00:00");
        return write_with_oiio(path, temp, spec, rgba.data());
    });
}

Status write_ldr_image(const std::string& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba) {
    if (rgba.size() != size_t(width) * height * 4)
        return Error{path + ": pixel buffer does not match " + std::to_string(width) + "x" + std::to_string(height)};
    return write_atomically(path, [&](const std::string& temp) -> Status {
        OIIO::ImageSpec spec(int(width), int(height), 4, OIIO::TypeDesc::UINT8);
        // Our texels are straight (unassociated) alpha; stop OIIO from dividing by alpha.
        spec.attribute("oiio:UnassociatedAlpha", 1);
        return write_with_oiio(path, temp, spec, rgba.data());
    });
}

}  // namespace facet
