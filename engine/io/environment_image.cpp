#include <facet/io/environment_image.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>

#include <facet/core/hash.h>
#include "core/huge_pages.h"
#include "io/box_downsample.h"
#include "io/exr_header.h"
#include "io/image_codecs.h"
#include "io/image_module_loader.h"

namespace facet {

namespace {

// Rows read at once from a scanline file: a multiple of the 16-row chunks of ZIP and
// PIZ compressed EXRs, so no chunk is decompressed twice.
constexpr uint32_t kBandRows = 32;
constexpr uint64_t kMaxBandBytes = uint64_t(256) << 20;

const char* describe(float v) { return std::isnan(v) ? "NaN" : std::isinf(v) ? "Inf" : "negative"; }

std::string size_text(uint64_t w, uint64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

// One source row as RGB, checked (or sanitised) texel by texel.
struct RowChecker {
    const std::string& path;
    uint32_t width;
    int channels;
    bool sanitize;
    uint64_t sanitized = 0;
    std::vector<float> rgb;

    std::optional<Error> convert(const float* raw, uint32_t y) {
        rgb.resize(size_t(width) * 3);
        for (uint32_t x = 0; x < width; ++x) {
            bool replaced = false;
            for (int c = 0; c < 3; ++c) {
                float v = raw[size_t(x) * channels + (channels == 1 ? 0 : c)];
                if (!(std::isfinite(v) && v >= 0)) {
                    if (!sanitize)
                        return Error{path + ": texel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                                     "RGB"[c] + " is " + describe(v) + " (" + std::to_string(v) +
                                     "); radiance must be finite and non-negative (sanitising replaces such texels)"};
                    replaced = true;
                    v = 0.0f;
                }
                rgb[size_t(x) * 3 + c] = v;
            }
            sanitized += replaced;
        }
        return std::nullopt;
    }
};

// The file's rows in order from the top, each `channels` floats a texel; an Error from
// `row` ends the reading with it.
using EnvironmentRow = std::function<std::optional<Error>(const float* raw, uint32_t y)>;
using EnvironmentRows = std::function<Status(const EnvironmentRow& row)>;

// Reads the file a band of rows at a time and hands each row to `row` (raw channels).
Status read_bands(const FacetImageModule& module, FacetImageReader& in, const FacetImageSpec& spec,
                  const std::string& path, const EnvironmentRow& row) {
    const uint32_t w = uint32_t(spec.width), h = uint32_t(spec.height);
    const bool tiled = spec.tile_width > 0;
    const uint32_t band = tiled ? uint32_t(std::max(spec.tile_height, 1)) : std::min(kBandRows, h);
    const uint64_t row_bytes = uint64_t(w) * spec.channels * sizeof(float);
    if (row_bytes * band > kMaxBandBytes)
        return Error{path + ": rows of " + std::to_string(band) + " (its tile height) at width " + std::to_string(w) +
                     " would take " + std::to_string(row_bytes * band >> 20) + " MiB to read, more than the limit of " +
                     std::to_string(kMaxBandBytes >> 20) + " MiB"};
    std::vector<float> buffer(size_t(row_bytes * std::min(band, h) / sizeof(float)));
    for (uint32_t y0 = 0; y0 < h; y0 += band) {
        const uint32_t y1 = std::min(h, y0 + band);
        char* reason = nullptr;
        if (!module.read_rows(&in, spec.y + int(y0), spec.y + int(y1), buffer.data(), &reason))
            return Error{path + ": the image data is damaged or truncated: " + take_module_text(module, reason)};
        for (uint32_t y = y0; y < y1; ++y)
            if (auto e = row(buffer.data() + size_t(y - y0) * w * spec.channels, y)) return *e;
    }
    return Ok{};
}

// What every file shares once its header is read: the size limits (before anything is
// allocated), the texel checks, downsampling while reading, and the content hash.
Result<EnvironmentImage> decode_environment(const std::string& path, uint64_t w, uint64_t h, int channels,
                                            const EnvironmentLoadOptions& options, const EnvironmentRows& read) {
    if (w == 0 || h == 0) return Error{path + ": the image has zero size"};
    if (w > kMaxEnvironmentSide || h > kMaxEnvironmentSide || w * h > kMaxEnvironmentTexels)
        return Error{path + ": " + size_text(w, h) + " is larger than an environment may be (at most " +
                     std::to_string(kMaxEnvironmentSide) + " texels a side and " + size_text(65536, 32768) +
                     " texels in all); refused before reading it"};
    if (channels != 1 && channels != 3 && channels != 4)
        return Error{path + ": " + std::to_string(channels) + " channels; an environment needs 1 (grey), 3 or 4"};

    EnvironmentImage env;
    env.source_width = uint32_t(w);
    env.source_height = uint32_t(h);
    const uint32_t max_width = std::max(options.max_width, 1u);
    const Size2 size = fit_within(env.source_width, env.source_height, max_width, std::max(max_width / 2, 1u));
    env.width = size.width;
    env.height = size.height;
    const size_t values = size_t(env.width) * env.height * 4;
    env.rgba.reserve(values);
    advise_huge_pages(env.rgba.data(), values * sizeof(float));
    env.rgba.assign(values, 1.0f);

    RowChecker checker{path, env.source_width, channels, options.sanitize};
    auto store = [&](uint32_t y, auto value) {
        float* out = &env.rgba[size_t(y) * env.width * 4];
        for (uint32_t x = 0; x < env.width; ++x)
            for (int c = 0; c < 3; ++c) out[size_t(x) * 4 + c] = float(value(x, c));
    };
    std::optional<BoxDownsampler> box;
    if (env.downsampled())
        box.emplace(env.source_width, env.source_height, env.width, env.height, 3, RowWeights::equirect_solid_angle,
                    [&](uint32_t y, const double* rgb) { store(y, [&](uint32_t x, int c) { return rgb[x * 3 + c]; }); });
    Status status = read([&](const float* raw, uint32_t y) -> std::optional<Error> {
        if (auto e = checker.convert(raw, y)) return e;
        if (box) box->add_row(checker.rgb.data());
        else store(y, [&](uint32_t x, int c) { return checker.rgb[x * 3 + c]; });
        return std::nullopt;
    });
    if (!status) return status.error();
    env.sanitized_texels = checker.sanitized;

    Hash64 hash;
    hash.add(&env.width, sizeof env.width).add(&env.height, sizeof env.height);
    hash.add_bulk(env.rgba.data(), env.rgba.size() * sizeof(float));
    env.content_hash = hash.hex();
    return env;
}

}  // namespace

Result<EnvironmentImage> load_environment(const std::string& path, const EnvironmentLoadOptions& options) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return Error{path + ": no such file"};
    if (std::filesystem::is_directory(path, ec)) return Error{path + ": is a directory, not an image"};
    // Radiance files (by their first line) are read here, without the image module;
    // those this reader declines go to the module with every other format.
    auto rgbe = codec::RgbeReader::open(path);
    if (!rgbe) return Error{path + ": cannot read the image: " + rgbe.error().message};
    if (std::optional<codec::RgbeReader>& in = *rgbe; in)
        return decode_environment(path, in->width(), in->height(), 3, options, [&](const EnvironmentRow& row) -> Status {
            std::vector<float> rgb(size_t(in->width()) * 3);
            for (uint32_t y = 0; y < uint32_t(in->height()); ++y) {
                if (Status s = in->read_row(rgb.data()); !s)
                    return Error{path + ": the image data is damaged or truncated: " + s.error().message};
                if (auto e = row(rgb.data(), y)) return *e;
            }
            return Ok{};
        });

    if (std::string problem = check_exr_attribute_sizes(path); !problem.empty()) return Error{path + ": " + problem};
    auto module = image_module();
    if (!module) return Error{path + ": " + module.error().message};
    // Opening reads the header only: the size is known before any texel is.
    char* reason = nullptr;
    ImageReader in(module.value()->open_file(path.c_str(), &reason), {module.value()});
    if (!in) {
        std::string text = take_module_text(*module.value(), reason);
        if (text.empty()) text = "not an image OpenImageIO can read";
        return Error{path + ": cannot read the image: " + text};
    }
    FacetImageSpec spec;
    module.value()->spec(in.get(), &spec);
    if (spec.depth > 1) return Error{path + ": a volume image (depth " + std::to_string(spec.depth) + ")"};
    return decode_environment(path, uint64_t(std::max(spec.width, 0)), uint64_t(std::max(spec.height, 0)),
                              spec.channels, options, [&](const EnvironmentRow& row) {
                                  return read_bands(*module.value(), *in, spec, path, row);
                              });
}

}  // namespace facet
