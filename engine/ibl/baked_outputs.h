#pragma once
// What bake_environment, save() and load() share: building a BakedEnvironment's images
// from texels, reading them back and the names of formats.
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <facet/gpu/resources.h>
#include <facet/ibl/baked_environment.h>

namespace facet {

// Every level of an image, its layers one after another (KTX2's level layout).
using Levels = std::vector<std::vector<std::byte>>;

struct BakedEnvironmentAccess {
    static BakedEnvironment make(Context& context) {
        BakedEnvironment b;
        b.context_ = &context;
        return b;
    }
    static Image& environment(BakedEnvironment& b) { return b.environment_; }
    static Image& cube(BakedEnvironment& b) { return b.cube_; }
    static Image& specular(BakedEnvironment& b) { return b.specular_; }
    static Image& irradiance(BakedEnvironment& b) { return b.irradiance_; }
    static Image& lut(BakedEnvironment& b) { return b.lut_; }
    static Sampler& cube_sampler(BakedEnvironment& b) { return b.cube_sampler_; }
    static std::vector<float>& sh9(BakedEnvironment& b) { return b.sh9_; }
    static std::vector<DiskLight>& lights(BakedEnvironment& b) { return b.lights_; }
    static Image& preview(BakedEnvironment& b) { return b.preview_; }
    static EncodedEnvironment& encoded(BakedEnvironment& b) { return b.encoded_; }
    static BakeMetadata& metadata(BakedEnvironment& b) { return b.metadata_; }
};

// The layout every image of a BakedEnvironment is left in.
inline constexpr VkImageLayout kBakedLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// Every level and layer of `image`, which is in `layout` and is left in it.
Levels read_levels(Context& context, const Image& image, VkImageLayout layout);
// Every level of several images (each in `layout`, left in it), read back in one
// submission and left in the mapped staging buffer, which the spans point into and which
// lives as long as any copy of the ReadBack (writers on other threads share it).
struct ReadBack {
    std::shared_ptr<Buffer> staging;
    std::vector<std::vector<std::span<const std::byte>>> levels;  // per image (none for a null image)
};
ReadBack read_back(Context& context, std::span<const Image* const> images, VkImageLayout layout);

// A sampled image of `desc` holding `levels`, left in kBakedLayout.
Image make_baked_image(Context& context, const ImageDesc& desc, const Levels& levels, const std::string& name);

// "R16G16B16A16_SFLOAT" / "R32G32B32A32_SFLOAT" (bake.json's names) and back (UNDEFINED: unknown).
const char* format_name(VkFormat format);
VkFormat parse_format_name(const std::string& name);

}  // namespace facet
