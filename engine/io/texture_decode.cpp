#include "io/texture_decode.h"

#include <algorithm>
#include <cmath>
#include <list>
#include <mutex>
#include <optional>
#include <unordered_map>

#include <facet/core/hash.h>

#include "io/box_downsample.h"
#include "io/image_module_loader.h"

namespace facet {

namespace {

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double c) { return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

uint8_t to_byte(double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

}  // namespace

Result<Rgba8Image> decode_texture_rows(const uint8_t* bytes, size_t size, const ImageHeader& header, uint32_t width,
                                       uint32_t height, bool srgb) {
    auto module = image_module();
    if (!module) return Error{"could not be decoded: " + module.error().message};
    const FacetImageModule& decoder = *module.value();
    // glTF's alpha is straight: the module keeps it so (oiio:UnassociatedAlpha).
    const char* name = header.format == "png" ? "texture.png" : header.format == "webp" ? "texture.webp" : "texture.jpg";
    char* reason = nullptr;
    ImageReader in(decoder.open_memory(bytes, size, name, &reason), {&decoder});
    if (!in) return Error{"could not be decoded: " + take_module_text(decoder, reason)};
    FacetImageSpec spec;
    decoder.spec(in.get(), &spec);
    if (uint32_t(spec.width) != header.width || uint32_t(spec.height) != header.height || spec.channels < 1 ||
        spec.channels > 4)
        return Error{"could not be decoded: the decoder disagrees with the header about its size or channels"};
    const uint32_t src_w = header.width, src_h = header.height, channels = uint32_t(spec.channels);
    const bool has_alpha = channels == 2 || channels == 4;
    const bool premultiplied = has_alpha && header.format == "webp";

    // Source values are 8 or 16 bit: a table per code turns them into linear light.
    const uint32_t codes = header.bytes_per_channel == 2 ? 65536 : 256;
    std::vector<float> to_linear(codes);
    for (uint32_t i = 0; i < codes; ++i) {
        const double v = double(i) / (codes - 1);
        to_linear[i] = float(srgb ? srgb_to_linear(v) : v);
    }

    Rgba8Image out{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
    auto store = [&](uint32_t y, auto value) {
        uint8_t* row = &out.rgba[size_t(y) * width * 4];
        for (uint32_t x = 0; x < width; ++x)
            for (uint32_t c = 0; c < 4; ++c) {
                const double v = value(x, c);
                row[x * 4 + c] = to_byte(srgb && c < 3 ? linear_to_srgb(v) : v);
            }
    };
    std::optional<BoxDownsampler> box;
    if (width != src_w || height != src_h)
        box.emplace(src_w, src_h, width, height, 4, RowWeights::uniform,
                    [&](uint32_t y, const double* rgba) { store(y, [&](uint32_t x, uint32_t c) { return rgba[x * 4 + c]; }); });

    constexpr uint32_t kBandRows = 16;
    const uint32_t band = std::min(kBandRows, src_h);
    std::vector<float> raw(size_t(src_w) * channels * band);
    std::vector<float> rgba(size_t(src_w) * 4);
    for (uint32_t y0 = 0; y0 < src_h; y0 += band) {
        const uint32_t y1 = std::min(src_h, y0 + band);
        if (!decoder.read_rows(in.get(), spec.y + int(y0), spec.y + int(y1), raw.data(), &reason))
            return Error{"could not be decoded: " + take_module_text(decoder, reason)};
        for (uint32_t y = y0; y < y1; ++y) {
            float* r = &raw[size_t(y - y0) * src_w * channels];
            for (uint32_t x = 0; x < src_w; ++x) {
                float* t = r + size_t(x) * channels;
                // OpenImageIO 2.4's WebP reader premultiplies colour by alpha whatever
                // oiio:UnassociatedAlpha says; glTF wants it straight.
                if (premultiplied && t[channels - 1] > 0.0f)
                    for (uint32_t c = 0; c + 1 < channels; ++c) t[c] = std::min(1.0f, t[c] / t[channels - 1]);
                auto code = [&](float v) { return to_linear[std::clamp(uint32_t(std::lround(v * (codes - 1))), 0u, codes - 1)]; };
                const float grey = code(t[0]);
                float* o = &rgba[size_t(x) * 4];
                o[0] = grey;
                o[1] = channels >= 3 ? code(t[1]) : grey;
                o[2] = channels >= 3 ? code(t[2]) : grey;
                o[3] = has_alpha ? t[channels - 1] : 1.0f;
            }
            if (box) box->add_row(rgba.data());
            else store(y, [&](uint32_t x, uint32_t c) { return double(rgba[size_t(x) * 4 + c]); });
        }
    }
    in.reset();
    return out;
}

namespace {

struct DecodeKey {
    uint64_t content_hash = 0, size = 0;
    TextureDecodeSettings settings;
    bool operator==(const DecodeKey& o) const {
        return content_hash == o.content_hash && size == o.size && settings.width == o.settings.width &&
               settings.height == o.settings.height && settings.srgb == o.settings.srgb &&
               settings.decoder == o.settings.decoder;
    }
};

struct DecodeKeyHash {
    size_t operator()(const DecodeKey& k) const {
        Hash64 h;
        h.add(&k.content_hash, sizeof k.content_hash).add(&k.size, sizeof k.size);
        h.add(&k.settings.width, sizeof k.settings.width).add(&k.settings.height, sizeof k.settings.height);
        const uint32_t rest[2] = {k.settings.srgb ? 1u : 0u, k.settings.decoder};
        return size_t(h.add(rest, sizeof rest).value());
    }
};

class DecodeCache {
public:
    std::optional<Rgba8Image> find(const DecodeKey& key) {
        std::lock_guard lock(mutex_);
        auto it = index_.find(key);
        if (it == index_.end()) return std::nullopt;
        ++stats_.hits;
        order_.splice(order_.begin(), order_, it->second);  // most recently used first
        return it->second->image;
    }
    void keep(const DecodeKey& key, const Rgba8Image& image) {
        std::lock_guard lock(mutex_);
        ++stats_.decodes;
        const uint64_t bytes = image.rgba.size();
        if (bytes > stats_.capacity_bytes / 8 || index_.count(key)) return;
        order_.push_front({key, image});
        index_[key] = order_.begin();
        stats_.bytes_kept += bytes;
        evict_to(stats_.capacity_bytes);
    }
    void set_capacity(uint64_t bytes) {
        std::lock_guard lock(mutex_);
        stats_.capacity_bytes = bytes;
        evict_to(bytes);
    }
    TextureCacheStats stats() const {
        std::lock_guard lock(mutex_);
        return stats_;
    }

private:
    struct Entry {
        DecodeKey key;
        Rgba8Image image;
    };
    void evict_to(uint64_t bytes) {
        while (stats_.bytes_kept > bytes && !order_.empty()) {
            stats_.bytes_kept -= order_.back().image.rgba.size();
            index_.erase(order_.back().key);
            order_.pop_back();
            ++stats_.evictions;
        }
    }
    mutable std::mutex mutex_;
    std::list<Entry> order_;
    std::unordered_map<DecodeKey, std::list<Entry>::iterator, DecodeKeyHash> index_;
    TextureCacheStats stats_{0, 0, 0, 0, 256ull << 20};
};

DecodeCache& decode_cache() {
    static DecodeCache cache;
    return cache;
}

}  // namespace

Rgba8Image decode_texture_cached(std::span<const uint8_t> bytes, const TextureDecodeSettings& settings,
                                 const std::function<Rgba8Image()>& decode) {
    DecodeKey key;
    key.content_hash = Hash64().add(bytes.data(), bytes.size()).value();
    key.size = bytes.size();
    key.settings = settings;
    if (auto kept = decode_cache().find(key)) return std::move(*kept);
    Rgba8Image image = decode();
    decode_cache().keep(key, image);
    return image;
}

TextureCacheStats texture_cache_stats() { return decode_cache().stats(); }

void set_texture_cache_capacity(uint64_t bytes) { decode_cache().set_capacity(bytes); }

}  // namespace facet
