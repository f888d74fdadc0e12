#pragma once
// What bake_environment, save() and load() share: building a BakedEnvironment's images
// from texels, reading them back, the storage-format rule and the names of formats.
#include <cstddef>
#include <string>
#include <vector>

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
    static std::vector<uint8_t>& preview(BakedEnvironment& b) { return b.preview_; }
    static BakeMetadata& metadata(BakedEnvironment& b) { return b.metadata_; }
};

// The layout every image of a BakedEnvironment is left in.
inline constexpr VkImageLayout kBakedLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// Every level and layer of `image`, which is in `layout` and is left in it.
Levels read_levels(Context& context, const Image& image, VkImageLayout layout);

// A sampled image of `desc` holding `levels`, left in kBakedLayout.
Image make_baked_image(Context& context, const ImageDesc& desc, const Levels& levels, const std::string& name);

// RGBA32F levels of an output -> the storage format: RGBA16F when `requested` asks for it
// and every value fits (|v| <= 65504), else RGBA32F, with a sentence in `note` saying why.
// Levels below `first_level` (not computed: no lookup reads them) become zeros.
struct Stored {
    VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
    Levels levels;
    std::string note;  // empty unless RGBA16F was asked for and could not hold the values
};
Stored store_levels(const Levels& rgba32f, VkFormat requested, uint32_t first_level, const std::string& what);

// NaN, Inf or negative values among RGBA32F levels from `first_level` on.
size_t count_bad_values(const Levels& rgba32f, uint32_t first_level = 0);

// "R16G16B16A16_SFLOAT" / "R32G32B32A32_SFLOAT" (bake.json's names) and back (UNDEFINED: unknown).
const char* format_name(VkFormat format);
VkFormat parse_format_name(const std::string& name);

}  // namespace facet
