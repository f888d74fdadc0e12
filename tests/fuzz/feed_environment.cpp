#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "feed.h"
#include <facet/io/environment_image.h>
#include "io/exr_header.h"

namespace facet::fuzz {

namespace {

// load_environment takes up to 4 GiB of texels by design (the large-input limits and
// their tests own that policy), so a 100-byte header declaring 16000x16000 texels makes it
// allocate gigabytes: the fuzzer's 2 GB and 10 s limits would report the design, not a
// bug. Inputs declaring more texels than this are skipped once their header is read.
constexpr uint64_t kMaxTexels = uint64_t(1) << 20;

void configure_oiio() {
    OIIO::attribute("threads", 1);  // reproducible timing, no pool per input
    OIIO::attribute("exr_threads", 1);
}

bool declares_huge_image(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        OIIO::geterror();  // clears the message, which load_environment reports itself
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    return uint64_t(std::max(spec.width, 0)) * uint64_t(std::max(spec.height, 0)) > kMaxTexels;
}

bool starts_with(Bytes input, const char* magic, size_t size) {
    return input.size() >= size && std::memcmp(input.data(), magic, size) == 0;
}

// By magic, as a user's file would be named; anything else gets a name OpenImageIO
// does not know, so that every reader it has may try it (load_environment takes them all).
std::string file_name(Bytes input) {
    if (starts_with(input, "#?", 2)) return "env.hdr";
    if (starts_with(input, "\x76\x2f\x31\x01", 4)) return "env.exr";
    if (starts_with(input, "\x89PNG", 4)) return "env.png";
    return "env.image";
}

// By its start: the rest of a message may quote the file (an attribute name, say).
bool is_texel_error(const Error& error, const std::string& path) {
    return error.message.rfind(path + ": texel (", 0) == 0;
}

void check_image(const EnvironmentImage& env, bool sanitized) {
    FACET_FUZZ_EXPECT(env.width > 0 && env.height > 0, "zero size accepted");
    FACET_FUZZ_EXPECT(env.rgba.size() == size_t(env.width) * env.height * 4, "size and texels disagree");
    FACET_FUZZ_EXPECT(sanitized || env.sanitized_texels == 0, "texels replaced without sanitising");
    for (size_t i = 0; i < env.rgba.size(); i += 4) {
        for (int c = 0; c < 3; ++c)
            FACET_FUZZ_EXPECT(std::isfinite(env.rgba[i + c]) && env.rgba[i + c] >= 0.0f,
                              "texel " + std::to_string(i / 4) + " is NaN, Inf or negative");
        FACET_FUZZ_EXPECT(env.rgba[i + 3] == 1.0f, "alpha is not 1");
    }
    FACET_FUZZ_EXPECT(env.content_hash.size() == 16, "no content hash");
}

}  // namespace

bool feed_environment(Bytes input) {
    static const bool configured = (configure_oiio(), true);
    (void)configured;
    const std::string path = write_input(input, file_name(input));
    // OpenEXR reads the header (and allocates what it declares) in the probe too.
    if (check_exr_attribute_sizes(path).empty() && declares_huge_image(path)) return false;
    Result<EnvironmentImage> strict = load_environment(path, {.sanitize = false});
    Result<EnvironmentImage> sanitized = load_environment(path, {.sanitize = true});
    if (strict) check_image(*strict, false);
    else expect_names_file(strict.error(), path);
    if (sanitized) check_image(*sanitized, true);
    else expect_names_file(sanitized.error(), path);
    // Sanitising changes only what the texel check refuses.
    if (strict) {
        FACET_FUZZ_EXPECT(sanitized && sanitized->sanitized_texels == 0 && sanitized->rgba == strict->rgba,
                          "sanitising changed a clean image");
    } else if (is_texel_error(strict.error(), path)) {
        FACET_FUZZ_EXPECT(sanitized && sanitized->sanitized_texels > 0,
                          "a texel error that sanitising does not repair: " + strict.error().message);
    } else {
        FACET_FUZZ_EXPECT(!sanitized, "sanitising accepted a file refused for another reason: " + strict.error().message);
    }
    return strict.ok();
}

}  // namespace facet::fuzz
