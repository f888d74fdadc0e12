#include "scene/gltf_images.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>

#include "io/box_downsample.h"
#include "io/texture_decode.h"
#include "scene/gltf_accessors.h"
#include <facet/core/units.h>
#include "scene/gltf_errors.h"

namespace facet::gltf_detail {

namespace {

namespace fs = std::filesystem;

// Larger images, or any that is downsampled, are decoded row by row: stb_image (through
// tinygltf) holds the whole image several times over, and tinygltf's size arithmetic
// is in int.
constexpr uint32_t kWholeDecodeMaxSide = 4096;

std::string image_name(const tinygltf::Image& image, size_t index) {
    if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) return fs::path(image.uri).filename().string();
    if (!image.name.empty()) return image.name;
    return "image " + std::to_string(index);
}

std::string size_text(uint64_t w, uint64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

std::span<const uint8_t> image_bytes(const tinygltf::Model& model, size_t index, const EncodedImages& encoded,
                                     const std::string& where) {
    const tinygltf::Image& image = model.images[index];
    std::span<const uint8_t> bytes;
    if (image.bufferView >= 0) {
        if (!in_range(image.bufferView, model.bufferViews.size()))
            fail(where + ": bufferView " + std::to_string(image.bufferView) + " out of range");
        const tinygltf::BufferView& view = model.bufferViews[size_t(image.bufferView)];  // validated
        bytes = {model.buffers[size_t(view.buffer)].data.data() + view.byteOffset, view.byteLength};
    } else if (auto it = encoded.find(int(index)); it != encoded.end()) {
        bytes = it->second;
    } else {
        fail(where + ": cannot read '" + image.uri + "'");
    }
    if (bytes.empty() || bytes.size() > size_t(INT_MAX)) fail(where + " could not be decoded: it is empty or too large");
    return bytes;
}

bool decoded_row_by_row(const ImagePlan& plan) {
    return plan.header.format == "webp" ||  // EXT_texture_webp: OpenImageIO decodes it, stb_image cannot
           plan.width != plan.header.width || plan.height != plan.header.height ||
           std::max(plan.header.width, plan.header.height) > kWholeDecodeMaxSide;
}

// stb_image through tinygltf, as every texture up to 4096 is decoded.
TextureImage decode_whole(std::span<const uint8_t> bytes, size_t index, const std::string& where) {
    tinygltf::Image decoded;
    std::string err, warn;
    if (!tinygltf::LoadImageData(&decoded, int(index), &err, &warn, 0, 0, bytes.data(), int(bytes.size()), nullptr))
        fail(where + " could not be decoded (PNG or JPEG expected)");
    size_t channels = size_t(decoded.component);
    size_t bytes_per_channel = decoded.bits == 16 ? 2 : 1;
    size_t pixels = size_t(decoded.width) * size_t(decoded.height);
    if (decoded.width <= 0 || decoded.height <= 0 || channels < 1 || channels > 4 ||
        (decoded.bits != 8 && decoded.bits != 16) || decoded.image.size() != pixels * channels * bytes_per_channel)
        fail(where + " could not be decoded: unexpected decoder output");
    TextureImage out;
    out.width = uint32_t(decoded.width);
    out.height = uint32_t(decoded.height);
    out.rgba.resize(pixels * 4);
    for (size_t p = 0; p < pixels; ++p) {
        uint8_t texel[4] = {0, 0, 0, 255};
        for (size_t c = 0; c < channels; ++c) {
            size_t at = (p * channels + c) * bytes_per_channel;
            texel[c] = bytes_per_channel == 2 ? uint8_t((load<uint16_t>(&decoded.image[at]) * 255u + 32767u) / 65535u)
                                              : decoded.image[at];
        }
        // Grey (and grey + alpha) images replicate their value into RGB.
        if (channels <= 2) {
            if (channels == 2) texel[3] = texel[1];
            texel[1] = texel[2] = texel[0];
        }
        std::memcpy(&out.rgba[p * 4], texel, 4);
    }
    return out;
}

}  // namespace

std::vector<ImagePlan> plan_images(const tinygltf::Model& model, const EncodedImages& encoded, const Scene& scene,
                                   const GltfLimits& limits) {
    std::vector<ImagePlan> plans(model.images.size());
    for (const Material& m : scene.materials)
        for (const TextureRef& colour : {m.base_color_texture, m.emissive_texture})
            if (colour.valid() && size_t(colour.image) < plans.size()) plans[size_t(colour.image)].srgb = true;
    uint64_t total_bytes = 0;
    uint32_t downsampled = 0;
    for (size_t i = 0; i < plans.size(); ++i) {
        ImagePlan& plan = plans[i];
        plan.name = image_name(model.images[i], i);
        const std::string where = "image '" + plan.name + "'";
        const std::span<const uint8_t> bytes = image_bytes(model, i, encoded, where);
        auto header = read_image_header(bytes.data(), bytes.size());
        if (!header) fail(where + " could not be decoded (PNG or JPEG expected)");
        plan.header = *header;
        const uint64_t w = header->width, h = header->height;
        if (w == 0 || h == 0) fail(where + " could not be decoded: its header declares a zero size");
        if (w > kMaxTextureSide || h > kMaxTextureSide || w * h > kMaxTexturePixels)
            fail(where + ": " + size_text(w, h) + " is larger than a texture may be (at most " +
                 std::to_string(kMaxTextureSide) + " a side and " + size_text(16384, 16384) +
                 " pixels); refused before decoding");
        const Size2 kept = fit_within(header->width, header->height, limits.max_texture_size, limits.max_texture_size);
        plan.width = kept.width;
        plan.height = kept.height;
        downsampled += kept.width != header->width || kept.height != header->height;
        const uint64_t whole = w * h * header->channels * 2;  // PNG rows or JPEG coefficients, 2 bytes at most
        if (decoded_row_by_row(plan) && !header->row_by_row && whole > kMaxWholeDecodeBytes)
            fail(where + ": " + size_text(w, h) + (header->format == "png" ? " interlaced PNG" : " progressive JPEG") +
                 " is decoded whole (up to " + format_bytes(whole) + "), more than the limit of " +
                 format_bytes(kMaxWholeDecodeBytes) + " for an image that large; save it non-" +
                 (header->format == "png" ? "interlaced" : "progressive") + " or smaller");
        total_bytes += uint64_t(kept.width) * kept.height * 4 * 4 / 3;
    }
    if (total_bytes > limits.max_texture_bytes)
        fail("its " + std::to_string(plans.size()) + " textures need " + format_bytes(total_bytes) +
             " as RGBA8 with mips" + (downsampled ? " (after downsampling to at most " +
                                                        std::to_string(limits.max_texture_size) + ")" : std::string()) +
             ", more than the limit of " + format_bytes(limits.max_texture_bytes) +
             "; a smaller maximum texture size fits them");
    return plans;
}

TextureImage decode_image(const tinygltf::Model& model, size_t index, const EncodedImages& encoded,
                          const ImagePlan& plan) {
    const std::string where = "image '" + plan.name + "'";
    const std::span<const uint8_t> bytes = image_bytes(model, index, encoded, where);
    // The same bytes decoded the same way before (this model loaded again): kept by content.
    const bool rows = decoded_row_by_row(plan);
    const TextureDecodeSettings settings{plan.width, plan.height, plan.srgb, rows ? 1u : 0u};
    Rgba8Image decoded = decode_texture_cached(bytes, settings, [&]() -> Rgba8Image {
        if (rows) {
            auto image = decode_texture_rows(bytes.data(), bytes.size(), plan.header, plan.width, plan.height, plan.srgb);
            if (!image) fail(where + " " + image.error().message);
            return std::move(image).value();
        }
        TextureImage whole = decode_whole(bytes, index, where);
        if (whole.width != plan.header.width || whole.height != plan.header.height)
            fail(where + " could not be decoded: the decoder disagrees with the header about its size");
        return Rgba8Image{whole.width, whole.height, std::move(whole.rgba)};
    });
    TextureImage out;
    out.width = decoded.width;
    out.height = decoded.height;
    out.rgba = std::move(decoded.rgba);
    out.name = plan.name;
    out.source_width = plan.header.width;
    out.source_height = plan.header.height;
    return out;
}

}  // namespace facet::gltf_detail
