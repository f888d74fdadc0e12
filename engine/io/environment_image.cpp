#include "io/environment_image.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>

#include "core/hash.h"
#include "io/exr_header.h"

namespace facet {

namespace {

const char* describe(float v) { return std::isnan(v) ? "NaN" : std::isinf(v) ? "Inf" : "negative"; }

}  // namespace

Result<EnvironmentImage> load_environment(const std::string& path, const EnvironmentLoadOptions& options) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return Error{path + ": no such file"};
    if (std::filesystem::is_directory(path, ec)) return Error{path + ": is a directory, not an image"};
    if (std::string problem = check_exr_attribute_sizes(path); !problem.empty()) return Error{path + ": " + problem};
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::string reason = OIIO::geterror();
        if (reason.empty()) reason = "not an image OpenImageIO can read";
        return Error{path + ": cannot read the image: " + reason};
    }
    const OIIO::ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0) return Error{path + ": the image has zero size"};
    const int channels = spec.nchannels;
    if (channels != 1 && channels != 3 && channels != 4)
        return Error{path + ": " + std::to_string(channels) + " channels; an environment needs 1 (grey), 3 or 4"};
    // Refuse sizes whose float copy alone would exceed 4 GiB, before allocating it.
    const uint64_t texels = uint64_t(spec.width) * uint64_t(spec.height);
    if (texels * 16 > (4ull << 30))
        return Error{path + ": " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     " is larger than the 4 GiB an environment may take"};
    std::vector<float> raw(texels * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data())) {
        std::string reason = in->geterror();
        return Error{path + ": the image data is damaged or truncated: " + reason};
    }
    in->close();

    EnvironmentImage env;
    env.width = static_cast<uint32_t>(spec.width);
    env.height = static_cast<uint32_t>(spec.height);
    env.rgba.resize(texels * 4);
    for (uint64_t i = 0; i < texels; ++i) {
        float rgb[3];
        bool replaced = false;
        for (int c = 0; c < 3; ++c) rgb[c] = raw[i * channels + (channels == 1 ? 0 : c)];
        for (int c = 0; c < 3; ++c) {
            float v = rgb[c];
            if (std::isfinite(v) && v >= 0) continue;
            if (!options.sanitize) {
                const uint64_t x = i % env.width, y = i / env.width;
                return Error{path + ": texel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                             "RGB"[c] + " is " + describe(v) + " (" + std::to_string(v) +
                             "); radiance must be finite and non-negative (sanitising replaces such texels)"};
            }
            replaced = true;
            rgb[c] = 0.0f;
        }
        env.sanitized_texels += replaced;
        for (int c = 0; c < 3; ++c) env.rgba[i * 4 + c] = rgb[c];
        env.rgba[i * 4 + 3] = 1.0f;
    }
    Hash64 h;
    h.add(&env.width, sizeof env.width).add(&env.height, sizeof env.height);
    h.add(env.rgba.data(), env.rgba.size() * sizeof(float));
    env.content_hash = h.hex();
    return env;
}

}  // namespace facet
