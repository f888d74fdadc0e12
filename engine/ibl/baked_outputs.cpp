#include "ibl/baked_outputs.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include <facet/gpu/transfer.h>
#include <facet/io/ktx2.h>

namespace facet {


Levels read_levels(Context& context, const Image& image, VkImageLayout layout) {
    Levels levels;
    const ImageDesc& d = image.desc();
    for (uint32_t m = 0; m < d.mip_levels; ++m) {
        std::vector<std::byte> level;
        for (uint32_t layer = 0; layer < d.array_layers; ++layer) {
            auto bytes = read_image(context, image, m, layer, layout);
            level.insert(level.end(), bytes.begin(), bytes.end());
        }
        levels.push_back(std::move(level));
    }
    return levels;
}

Image make_baked_image(Context& context, const ImageDesc& desc, const Levels& levels, const std::string& name) {
    Image image(context, desc,
                VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, name);
    for (uint32_t m = 0; m < desc.mip_levels; ++m) {
        const size_t layer_bytes = levels[m].size() / desc.array_layers;
        for (uint32_t layer = 0; layer < desc.array_layers; ++layer)
            upload_image(context, image, m, layer,
                         std::span<const std::byte>(levels[m].data() + layer * layer_bytes, layer_bytes),
                         VK_IMAGE_LAYOUT_UNDEFINED, kBakedLayout);
    }
    return image;
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
