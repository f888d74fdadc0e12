#pragma once
// Equirectangular environments from files (.hdr, .exr and anything else OpenImageIO
// reads as floating point), any size and aspect, checked texel by texel: NaN, Inf or
// negative radiance is an error naming the file and the first bad texel, unless the
// caller asks for sanitising (then such texels become 0 and are counted).
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace facet {

struct EnvironmentImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rgba;       // linear radiance, row 0 = top row of the file (+Y)
    std::string content_hash;      // of the decoded texels and size (16 hex digits)
    uint64_t sanitized_texels = 0;  // texels replaced when sanitising
};

struct EnvironmentLoadOptions {
    bool sanitize = false;
};

Result<EnvironmentImage> load_environment(const std::string& path, const EnvironmentLoadOptions& options = {});

}  // namespace facet
