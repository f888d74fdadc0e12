#include <facet/io/image_io.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>

#include <facet/io/atomic_file.h>
#include "core/huge_pages.h"
#include "io/image_codecs.h"
#include "io/image_module_loader.h"

namespace facet {

namespace {

std::string lower_extension(const std::string& path) {
    auto dot = path.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

Status check_image_buffer(const std::string& path, uint32_t width, uint32_t height, size_t values) {
    if (values != size_t(width) * height * 4)
        return Error{path + ": pixel buffer does not match " + std::to_string(width) + "x" + std::to_string(height)};
    if (width == 0 || height == 0) return Error{path + ": an image of zero size cannot be written"};
    return Ok{};
}

// Opens `temp` and has `encode` write it; messages name `path`, the file's final name.
Status encode_image_file(const std::string& path, const std::string& temp,
                         const std::function<Status(codec::ByteSink&)>& encode) {
    std::FILE* file = std::fopen(temp.c_str(), "wb");
    if (!file) return Error{path + ": cannot open for writing: " + std::strerror(errno)};
    codec::ByteSink sink(file);
    Status written = encode(sink);
    const bool closed = std::fclose(file) == 0;  // the last buffered bytes are written here
    if (!written) return Error{path + ": " + written.error().message};
    if (!closed) return Error{path + ": write failed: " + std::strerror(errno)};
    return Ok{};
}

// Writes `temp` through the image module (OpenImageIO, which chooses the format by the
// extension); messages name `path`.
Status write_through_module(const std::string& path, const std::string& temp, uint32_t width, uint32_t height,
                            const uint8_t* rgba) {
    auto module = image_module();
    if (!module) return Error{path + ": " + module.error().message};
    // Our texels are straight (unassociated) alpha; stop OIIO from dividing by alpha.
    const FacetImageAttribute straight{"oiio:UnassociatedAlpha", nullptr, 1};
    char* reason = nullptr;
    if (!module.value()->write(temp.c_str(), width, height, 4, FACET_IMAGE_UINT8, rgba, &straight, 1, &reason))
        return Error{path + ": " + take_module_text(*module.value(), reason)};
    return Ok{};
}

}  // namespace

void preload_image_io() { (void)image_module(); }

namespace {

// The encoder of `path`'s extension (.exr or .hdr) for RGBA float texels.
Result<std::function<Status(codec::ByteSink&)>> hdr_encoder(const std::string& path, uint32_t width, uint32_t height,
                                                             std::span<const float> rgba, uint32_t threads = 0) {
    if (Status s = check_image_buffer(path, width, height, rgba.size()); !s) return s.error();
    const std::string ext = lower_extension(path);
    if (ext != ".exr" && ext != ".hdr") return Error{path + ": HDR output must be .exr or .hdr"};
    return std::function<Status(codec::ByteSink&)>([=](codec::ByteSink& out) {
        return ext == ".exr" ? codec::write_exr(out, width, height, rgba.data(), threads)
                             : codec::write_rgbe(out, width, height, rgba.data());
    });
}

}  // namespace

Status write_hdr_image(const std::string& path, uint32_t width, uint32_t height, std::span<const float> rgba) {
    auto encoder = hdr_encoder(path, width, height, rgba);
    if (!encoder) return encoder.error();
    return write_atomically(path, [&](const std::string& temp) { return encode_image_file(path, temp, *encoder); });
}

Result<std::vector<uint8_t>> encode_hdr_image(const std::string& path, uint32_t width, uint32_t height,
                                              std::span<const float> rgba, uint32_t threads) {
    auto encoder = hdr_encoder(path, width, height, rgba, threads);
    if (!encoder) return encoder.error();
    // Room for the largest file (stored EXR chunks, or RGBE rows whose run-length coding
    // grows them by a byte in 128) reserved and given huge pages before it is written.
    const size_t texels = size_t(width) * height;
    std::vector<uint8_t> bytes;
    bytes.reserve(lower_extension(path) == ".exr" ? texels * 16 + size_t(height) * 16 + 65536
                                                   : texels * 4 + texels / 32 + size_t(height) * 8 + 1024);
    advise_huge_pages(bytes.data(), bytes.capacity());
    codec::ByteSink sink(bytes);
    if (Status s = (*encoder)(sink); !s) return Error{path + ": " + s.error().message};
    return bytes;
}

Status write_ldr_image(const std::string& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba) {
    if (Status s = check_image_buffer(path, width, height, rgba.size()); !s) return s;
    return write_atomically(path, [&](const std::string& temp) {
        if (lower_extension(path) != ".png") return write_through_module(path, temp, width, height, rgba.data());
        return encode_image_file(path, temp,
                                 [&](codec::ByteSink& out) { return codec::write_png(out, width, height, rgba.data()); });
    });
}

}  // namespace facet
