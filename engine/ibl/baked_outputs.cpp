#include "ibl/baked_outputs.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include <facet/gpu/transfer.h>
#include <facet/io/ktx2.h>
#include "core/guarded.h"

namespace facet {

namespace {

// The largest finite RGBA16F value; larger ones round to infinity (from 65520 on) or
// down to it, either way not the value baked.
constexpr float kHalfMax = 65504.0f;

}  // namespace

Levels read_levels(Context& context, const Image& image, VkImageLayout layout) {
    Levels levels;
    const ImageDesc& d = image.desc();
    for (uint32_t m = 0; m < d.mip_levels; ++m) {
        std::vector<std::byte> level;
        for (uint32_t layer = 0; layer < d.array_layers; ++layer) {
            auto bytes = or_throw(read_image(context, image, m, layer, layout));
            level.insert(level.end(), bytes.begin(), bytes.end());
        }
        levels.push_back(std::move(level));
    }
    return levels;
}

Image make_baked_image(Context& context, const ImageDesc& desc, const Levels& levels, const std::string& name) {
    Image image = or_throw(Image::create(
        context, desc, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, name));
    for (uint32_t m = 0; m < desc.mip_levels; ++m) {
        const size_t layer_bytes = levels[m].size() / desc.array_layers;
        for (uint32_t layer = 0; layer < desc.array_layers; ++layer)
            or_throw(upload_image(context, image, m, layer,
                                  std::span<const std::byte>(levels[m].data() + layer * layer_bytes, layer_bytes),
                                  VK_IMAGE_LAYOUT_UNDEFINED, kBakedLayout));
    }
    return image;
}

size_t count_bad_values(const Levels& rgba32f, uint32_t first_level) {
    size_t bad = 0;
    for (size_t m = first_level; m < rgba32f.size(); ++m) {
        const size_t n = rgba32f[m].size() / sizeof(float);
        for (size_t i = 0; i < n; ++i) {
            float v;
            std::memcpy(&v, rgba32f[m].data() + i * sizeof(float), sizeof v);
            bad += !std::isfinite(v) || v < 0;
        }
    }
    return bad;
}

Stored store_levels(const Levels& rgba32f, VkFormat requested, uint32_t first_level, const std::string& what) {
    Stored out;
    out.levels = rgba32f;
    for (size_t m = 0; m < out.levels.size() && m < first_level; ++m)
        std::fill(out.levels[m].begin(), out.levels[m].end(), std::byte{0});
    if (requested != VK_FORMAT_R16G16B16A16_SFLOAT) {
        out.format = VK_FORMAT_R32G32B32A32_SFLOAT;
        return out;
    }
    float peak = 0;
    for (const auto& level : out.levels)
        for (size_t i = 0; i < level.size() / sizeof(float); ++i) {
            float v;
            std::memcpy(&v, level.data() + i * sizeof(float), sizeof v);
            peak = std::max(peak, std::abs(v));
        }
    if (peak > kHalfMax) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "%s kept in R32G32B32A32_SFLOAT: its largest value, %.4g, exceeds R16G16B16A16_SFLOAT's "
                      "65504",
                      what.c_str(), double(peak));
        out.format = VK_FORMAT_R32G32B32A32_SFLOAT;
        out.note = text;
        return out;
    }
    out.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    for (auto& level : out.levels) {
        const size_t n = level.size() / sizeof(float);
        std::vector<std::byte> half(n * 2);
        for (size_t i = 0; i < n; ++i) {
            float v;
            std::memcpy(&v, level.data() + i * sizeof(float), sizeof v);
            const uint16_t h = float_to_half(v);
            std::memcpy(half.data() + i * 2, &h, 2);
        }
        level = std::move(half);
    }
    return out;
}

const char* format_name(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R16G16B16A16_SFLOAT: return "R16G16B16A16_SFLOAT";
        case VK_FORMAT_R32G32B32A32_SFLOAT: return "R32G32B32A32_SFLOAT";
        default: return "unsupported";
    }
}

VkFormat parse_format_name(const std::string& name) {
    if (name == "R16G16B16A16_SFLOAT") return VK_FORMAT_R16G16B16A16_SFLOAT;
    if (name == "R32G32B32A32_SFLOAT") return VK_FORMAT_R32G32B32A32_SFLOAT;
    return VK_FORMAT_UNDEFINED;
}

}  // namespace facet
