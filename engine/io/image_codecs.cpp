#include "io/image_codecs.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <climits>
#include <cstring>
#include <functional>
#include <string_view>
#include <thread>
#include <utility>

namespace facet::codec {

static_assert(std::endian::native == std::endian::little,
              "the EXR writer stores floats and offsets as they lie in memory: little-endian, as the format");

namespace {

Status write_failed() { return Error{std::string("write failed: ") + std::strerror(errno)}; }

void store_be32(uint8_t* out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out[i] = uint8_t(v >> (24 - 8 * i));
}

template <class T>
void append_le(std::vector<uint8_t>& out, T v) {
    const size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(&out[at], &v, sizeof(T));
}

}  // namespace

bool ByteSink::put(const void* bytes, size_t size) {
    if (file_) return std::fwrite(bytes, 1, size, file_) == size;
    const auto* from = static_cast<const uint8_t*>(bytes);
    memory_->insert(memory_->end(), from, from + size);
    return true;
}

bool ByteSink::patch(uint64_t offset, const void* bytes, size_t size) {
    if (file_)
        return offset <= uint64_t(LONG_MAX) && std::fseek(file_, long(offset), SEEK_SET) == 0 &&
               std::fwrite(bytes, 1, size, file_) == size && std::fseek(file_, 0, SEEK_END) == 0;
    if (offset > memory_->size() || size > memory_->size() - offset) return false;
    std::memcpy(memory_->data() + offset, bytes, size);
    return true;
}

namespace {

// ---- PNG ----

// A chunk: length, type, data, and the CRC-32 of type and data.
bool put_png_chunk(ByteSink& out, const char* type, const uint8_t* data, size_t size) {
    uint8_t head[8], tail[4];
    store_be32(head, uint32_t(size));
    std::memcpy(head + 4, type, 4);
    uLong crc = crc32(crc32(0, nullptr, 0), head + 4, 4);
    if (size) crc = crc32(crc, data, uInt(size));
    store_be32(tail, uint32_t(crc));
    return out.put(head, 8) && (size == 0 || out.put(data, size)) && out.put(tail, 4);
}

struct DeflateStream {
    z_stream z{};
    bool open = false;
    // window_bits 15: a zlib stream (RFC 1950); -15: raw deflate (RFC 1951).
    DeflateStream(int level, int window_bits, int strategy) {
        open = deflateInit2(&z, level, Z_DEFLATED, window_bits, 8, strategy) == Z_OK;
    }
    ~DeflateStream() {
        if (open) deflateEnd(&z);
    }
};


// How many runs an encoder splits its `units` (rows, chunks) into: `parts` when given,
// else one a core (up to 4) for images of at least `min_bytes` whose runs get at least
// `min_units` each, else one; never more than `units`.
uint32_t part_count(uint32_t parts, uint32_t units, size_t bytes, size_t min_bytes, uint32_t min_units) {
    const uint32_t cores = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
    if (parts == 0) parts = bytes < min_bytes ? 1u : std::min(cores, units / min_units);
    return std::max(1u, std::min(parts, units));
}

// work(k, first, last) for each of the `parts` runs of [0, units): run 0 on this thread
// (an encoder's first run may write straight to its sink), the others on threads of their own.
void run_in_parts(uint32_t parts, uint32_t units, const std::function<void(uint32_t, uint32_t, uint32_t)>& work) {
    auto first = [&](uint32_t k) { return uint32_t(uint64_t(units) * k / parts); };
    std::vector<std::thread> helpers;
    for (uint32_t k = 1; k < parts; ++k) helpers.emplace_back(work, k, first(k), first(k + 1));
    work(0, 0, first(1));
    for (std::thread& t : helpers) t.join();
}

// One part of a PNG's image data: rows [y0, y1) Sub-filtered and deflated as raw deflate
// (no zlib header or check value), ended with a sync flush (byte-aligned, so that the next
// part's blocks follow) or, for the last part, with the final block.
struct PngPart {
    std::vector<uint8_t> deflated;
    uLong adler = 1;  // adler32 of the filtered rows
    size_t filtered_bytes = 0;
    bool failed = false;
};

void deflate_png_rows(const uint8_t* rgba, uint32_t width, uint32_t y0, uint32_t y1, bool last, PngPart& part) {
    // Run-length matches only (Z_RLE): a tone-mapped photograph's Sub-filtered rows hold
    // few longer matches. royal_esplanade_1k's 1024x512 preview 21 ms and 0.91 MB instead
    // of 26 ms and 0.97 MB with zlib's default matching, builtin:sky's 21 KB instead of 29.
    DeflateStream stream(1, -15, Z_RLE);
    if (!stream.open) {
        part.failed = true;
        return;
    }
    z_stream& z = stream.z;
    const size_t row_bytes = size_t(width) * 4;
    std::vector<uint8_t> row(row_bytes + 1);
    part.deflated.resize(size_t(deflateBound(&z, uLong((row_bytes + 1) * (y1 - y0)))) + 16);
    z.next_out = part.deflated.data();
    z.avail_out = uInt(part.deflated.size());
    for (uint32_t y = y0; y < y1 && !part.failed; ++y) {
        // Sub: each byte less the same channel of the texel to its left. Against no
        // filter (royal_esplanade_1k's 1024x512 preview): 25 ms instead of 33, 0.97 MB
        // instead of 1.21 (OpenImageIO's adaptive filters: 38 ms, 0.93 MB).
        const uint8_t* src = rgba + size_t(y) * row_bytes;
        row[0] = 1;
        for (size_t i = 0; i < row_bytes; ++i) row[1 + i] = uint8_t(src[i] - (i >= 4 ? src[i - 4] : 0));
        part.adler = adler32(part.adler, row.data(), uInt(row.size()));
        part.filtered_bytes += row.size();
        z.next_in = row.data();
        z.avail_in = uInt(row.size());
        const int flush = y + 1 < y1 ? Z_NO_FLUSH : (last ? Z_FINISH : Z_SYNC_FLUSH);
        const int result = ::deflate(&z, flush);
        // deflateBound leaves room for everything: the input is always taken whole.
        if (result == Z_STREAM_ERROR || z.avail_in != 0 || (flush == Z_FINISH && result != Z_STREAM_END))
            part.failed = true;
    }
    part.deflated.resize(part.deflated.size() - z.avail_out);
}

}  // namespace

Status write_png(ByteSink& out, uint32_t width, uint32_t height, const uint8_t* rgba, uint32_t parts) {
    if (width == 0 || height == 0 || width > INT32_MAX || height > INT32_MAX || width > (UINT32_MAX - 1) / 4)
        return Error{std::to_string(width) + "x" + std::to_string(height) + " is not a size a PNG can hold"};
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    // Bit depth 8, colour type 6 (RGBA), compression method 0 (deflate), filter method 0,
    // no interlace.
    uint8_t ihdr[13] = {0, 0, 0, 0, 0, 0, 0, 0, 8, 6, 0, 0, 0};
    store_be32(ihdr, width);
    store_be32(ihdr + 4, height);
    if (!out.put(signature, 8) || !put_png_chunk(out, "IHDR", ihdr, 13)) return write_failed();

    // The zlib stream (RFC 1950) of the filtered rows, deflated in parts on as many threads
    // as there are cores (up to 4) for images of 256 KiB or more: each part's raw deflate
    // ends byte-aligned and the next one follows (RFC 1951 blocks concatenate); the check
    // value is the parts' adler32s combined. royal_esplanade_1k's 1024x512 preview in two
    // parts: 26 bytes larger (the second part starts without the first's window).
    parts = part_count(parts, height, size_t(width) * 4 * height, size_t(1) << 18, 64);
    std::vector<PngPart> deflated(parts);
    run_in_parts(parts, height, [&](uint32_t k, uint32_t y0, uint32_t y1) {
        deflate_png_rows(rgba, width, y0, y1, k + 1 == parts, deflated[k]);
    });
    // CMF 0x78 (deflate, 32 KiB window), FLG 0x01 (fastest; the header's check bits).
    std::vector<uint8_t> idat = {0x78, 0x01};
    uLong adler = 1;
    for (const PngPart& part : deflated) {
        if (part.failed) return Error{"zlib failed while deflating (out of memory)"};
        adler = adler32_combine(adler, part.adler, z_off_t(part.filtered_bytes));
    }
    // IDAT chunks of at most 256 KiB.
    constexpr size_t kIdatBytes = size_t(1) << 18;
    auto put_idat = [&](const uint8_t* data, size_t size) {
        while (size > 0) {
            const size_t take = std::min(size, kIdatBytes - idat.size());
            idat.insert(idat.end(), data, data + take);
            data += take;
            size -= take;
            if (idat.size() == kIdatBytes) {
                if (!put_png_chunk(out, "IDAT", idat.data(), idat.size())) return false;
                idat.clear();
            }
        }
        return true;
    };
    uint8_t check[4];
    store_be32(check, uint32_t(adler));
    for (const PngPart& part : deflated)
        if (!put_idat(part.deflated.data(), part.deflated.size())) return write_failed();
    if (!put_idat(check, 4) || (!idat.empty() && !put_png_chunk(out, "IDAT", idat.data(), idat.size())) ||
        !put_png_chunk(out, "IEND", nullptr, 0))
        return write_failed();
    return Ok{};
}

// ---- OpenEXR ----

namespace {

constexpr uint32_t kExrMagic = 20000630;
constexpr uint32_t kExrZipRows = 16;  // rows a ZIP_COMPRESSION chunk holds

void append_exr_attribute(std::vector<uint8_t>& out, std::string_view name, std::string_view type,
                          const std::vector<uint8_t>& value) {
    out.insert(out.end(), name.begin(), name.end());
    out.push_back(0);
    out.insert(out.end(), type.begin(), type.end());
    out.push_back(0);
    append_le(out, int32_t(value.size()));
    out.insert(out.end(), value.begin(), value.end());
}

std::vector<uint8_t> exr_header_bytes(uint32_t width, uint32_t height) {
    std::vector<uint8_t> h;
    append_le(h, kExrMagic);
    append_le(h, uint32_t(2));  // version 2; single part, scanlines, short names
    std::vector<uint8_t> v;
    for (char name : {'A', 'B', 'G', 'R'}) {  // chlist: sorted by name
        v.push_back(uint8_t(name));
        v.push_back(0);
        append_le(v, int32_t(2));  // pixel type FLOAT
        v.insert(v.end(), {0, 0, 0, 0});  // pLinear 0, three reserved bytes
        append_le(v, int32_t(1));  // x sampling
        append_le(v, int32_t(1));  // y sampling
    }
    v.push_back(0);
    append_exr_attribute(h, "channels", "chlist", v);
    append_exr_attribute(h, "compression", "compression", {3});  // ZIP_COMPRESSION
    v.clear();
    for (int32_t c : {0, 0, int32_t(width) - 1, int32_t(height) - 1}) append_le(v, c);
    append_exr_attribute(h, "dataWindow", "box2i", v);
    append_exr_attribute(h, "displayWindow", "box2i", v);
    append_exr_attribute(h, "lineOrder", "lineOrder", {0});  // INCREASING_Y
    v.clear();
    append_le(v, 1.0f);
    append_exr_attribute(h, "pixelAspectRatio", "float", v);
    append_exr_attribute(h, "screenWindowWidth", "float", v);
    v.clear();
    append_le(v, 0.0f);
    append_le(v, 0.0f);
    append_exr_attribute(h, "screenWindowCenter", "v2f", v);
    h.push_back(0);  // end of the header
    return h;
}

// ZIP_COMPRESSION's preprocessing: the bytes split into those at even and those at odd
// offsets (one after the other), then each byte replaced by its difference from the one
// before plus 128 (mod 256), the first kept.
void exr_zip_predict(const std::vector<uint8_t>& raw, std::vector<uint8_t>& out) {
    const size_t n = raw.size(), half = (n + 1) / 2;
    out.resize(n);
    if (n == 0) return;
    // Each output from the input alone (no running value), so that the loops vectorise.
    const uint8_t* in = raw.data();
    uint8_t* to = out.data();
    to[0] = in[0];
    for (size_t i = 1; i < half; ++i) to[i] = uint8_t(in[2 * i] - in[2 * i - 2] + 128);
    if (n > 1) to[half] = uint8_t(in[1] - in[2 * (half - 1)] + 128);
    for (size_t i = 1; half + i < n; ++i) to[half + i] = uint8_t(in[2 * i + 1] - in[2 * i - 1] + 128);
}

}  // namespace

namespace {

// The chunks [first, last) of an EXR (ZIP_COMPRESSION, kExrZipRows rows each), each with its
// y and byte count, put to `out` (the first part: straight to the file) or kept in `kept`
// with their sizes (the other parts, put after it). One deflate state for every chunk
// (reset, not made again: ~0.3 MB of state each).
struct ExrPart {
    std::vector<uint8_t> kept;
    std::vector<uint32_t> sizes;  // each chunk's bytes, its y and byte count included
    Status status = Ok{};
};

void compress_exr_chunks(uint32_t width, uint32_t height, const float* rgba, uint32_t first, uint32_t last,
                         ByteSink* out, ExrPart& part) {
    DeflateStream zip(kExrZipLevel, 15, Z_DEFAULT_STRATEGY);
    if (!zip.open) {
        part.status = Error{"zlib cannot start deflating (out of memory)"};
        return;
    }
    ByteSink kept(part.kept);
    ByteSink& to = out ? *out : kept;
    std::vector<uint8_t> raw, predicted, packed, chunk;
    for (uint32_t k = first; k < last; ++k) {
        const uint32_t y0 = k * kExrZipRows, y1 = std::min(height, y0 + kExrZipRows);
        // Each row: every channel's values in turn, in the channel list's order.
        raw.resize(size_t(y1 - y0) * width * 16);
        uint8_t* at = raw.data();
        for (uint32_t y = y0; y < y1; ++y)
            for (int c : {3, 2, 1, 0}) {
                const float* from = rgba + size_t(y) * width * 4 + c;
                for (uint32_t x = 0; x < width; ++x, at += 4) std::memcpy(at, from + size_t(x) * 4, 4);
            }
        exr_zip_predict(raw, predicted);
        z_stream& z = zip.z;
        packed.resize(deflateBound(&z, uLong(predicted.size())));
        if (deflateReset(&z) != Z_OK) {
            part.status = Error{"zlib failed while compressing"};
            return;
        }
        z.next_in = predicted.data();
        z.avail_in = uInt(predicted.size());
        z.next_out = packed.data();
        z.avail_out = uInt(packed.size());
        if (::deflate(&z, Z_FINISH) != Z_STREAM_END) {
            part.status = Error{"zlib failed while compressing"};
            return;
        }
        const size_t packed_size = packed.size() - z.avail_out;
        // A chunk that compression does not shrink is stored as it is (readers tell the
        // two apart by its size).
        const bool shrunk = packed_size < raw.size();
        const uint8_t* data = shrunk ? packed.data() : raw.data();
        const size_t size = shrunk ? packed_size : raw.size();
        chunk.clear();
        append_le(chunk, int32_t(y0));
        append_le(chunk, int32_t(size));
        if (!to.put(chunk.data(), chunk.size()) || !to.put(data, size)) {
            part.status = write_failed();
            return;
        }
        part.sizes.push_back(uint32_t(chunk.size() + size));
    }
}

}  // namespace

Status write_exr(ByteSink& out, uint32_t width, uint32_t height, const float* rgba, uint32_t parts) {
    // A chunk's byte count is an int32.
    if (width == 0 || height == 0 || height > INT32_MAX || uint64_t(width) * kExrZipRows * 16 > INT32_MAX)
        return Error{std::to_string(width) + "x" + std::to_string(height) + " is not a size this EXR writer takes"};
    const std::vector<uint8_t> header = exr_header_bytes(width, height);
    const uint32_t chunks = (height + kExrZipRows - 1) / kExrZipRows;
    std::vector<uint64_t> offsets(chunks);
    if (!out.put(header.data(), header.size()) || !out.put(offsets.data(), offsets.size() * 8)) return write_failed();

    // The chunks in `parts` runs, one a thread: the first goes straight to `out`, the
    // others are kept in memory and put after it.
    parts = part_count(parts, chunks, size_t(width) * height * 16, size_t(1) << 20, 4);
    std::vector<ExrPart> compressed(parts);
    run_in_parts(parts, chunks, [&](uint32_t k, uint32_t first, uint32_t last) {
        compress_exr_chunks(width, height, rgba, first, last, k == 0 ? &out : nullptr, compressed[k]);
    });
    uint64_t at = header.size() + offsets.size() * 8;
    size_t k = 0;
    for (const ExrPart& part : compressed) {
        if (!part.status) return part.status;
        if (&part != &compressed[0] && !out.put(part.kept.data(), part.kept.size())) return write_failed();
        for (uint32_t size : part.sizes) {
            offsets[k++] = at;
            at += size;
        }
    }
    if (!out.patch(header.size(), offsets.data(), offsets.size() * 8)) return write_failed();
    return Ok{};
}

// ---- Radiance RGBE: writing ----

namespace {

constexpr uint32_t kRleMinWidth = 8, kRleMaxWidth = 0x7fff;
// The largest value RGBE holds: mantissa 255, exponent byte 255 (255 * 2^(255 - 136)).
constexpr float kMaxRgbe = 255.0f * 0x1p119f;

// Ward's conversion: the largest channel's frexp sets the shared exponent.
void to_rgbe(const float* rgb, uint8_t out[4]) {
    float c[3];
    for (int i = 0; i < 3; ++i) c[i] = rgb[i] > 0 ? std::min(rgb[i], kMaxRgbe) : 0.0f;  // NaN: 0
    const float v = std::max({c[0], c[1], c[2]});
    if (v < 1e-32f) {
        std::memset(out, 0, 4);
        return;
    }
    int e = 0;
    const double scale = std::frexp(double(v), &e) * 256.0 / v;
    for (int i = 0; i < 3; ++i) out[i] = uint8_t(c[i] * scale);
    out[3] = uint8_t(e + 128);
}

// One component of a row: runs of 3 to 127 equal bytes as (128 + n, byte), the bytes
// between them as literal spans (n <= 128, then n bytes).
void append_rle(const uint8_t* bytes, size_t n, std::vector<uint8_t>& out) {
    size_t i = 0;
    while (i < n) {
        size_t run = 1;
        while (i + run < n && run < 127 && bytes[i + run] == bytes[i]) ++run;
        if (run >= 3) {
            out.push_back(uint8_t(128 + run));
            out.push_back(bytes[i]);
            i += run;
            continue;
        }
        const size_t start = i;
        while (i < n && i - start < 128 && !(i + 2 < n && bytes[i] == bytes[i + 1] && bytes[i] == bytes[i + 2])) ++i;
        out.push_back(uint8_t(i - start));
        out.insert(out.end(), bytes + start, bytes + i);
    }
}

}  // namespace

Status write_rgbe(ByteSink& out, uint32_t width, uint32_t height, const float* rgba) {
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " +
                               std::to_string(width) + "\n";
    if (!out.put(header.data(), header.size())) return write_failed();
    const bool rle = width >= kRleMinWidth && width <= kRleMaxWidth;
    std::vector<uint8_t> texels(size_t(width) * 4), components(rle ? size_t(width) * 4 : 0), line;
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) to_rgbe(rgba + (size_t(y) * width + x) * 4, &texels[size_t(x) * 4]);
        if (!rle) {
            if (!out.put(texels.data(), texels.size())) return write_failed();
            continue;
        }
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 4; ++c) components[size_t(c) * width + x] = texels[size_t(x) * 4 + c];
        line = {2, 2, uint8_t(width >> 8), uint8_t(width & 0xff)};
        for (int c = 0; c < 4; ++c) append_rle(&components[size_t(c) * width], width, line);
        if (!out.put(line.data(), line.size())) return write_failed();
    }
    return Ok{};
}

// ---- Radiance RGBE: reading ----

namespace {

constexpr size_t kRgbeReadAhead = size_t(1) << 16;
constexpr size_t kRgbeMaxHeaderLine = size_t(1) << 16;

// A decimal count of at most 19 digits (below 2^63).
bool parse_rgbe_count(std::string_view text, uint64_t& value) {
    if (text.empty() || text.size() > 19) return false;
    value = 0;
    for (char c : text) {
        if (c < '0' || c > '9') return false;
        value = value * 10 + uint64_t(c - '0');
    }
    return true;
}

// 2^(e - 136) for each exponent byte e, 0 for e = 0; each m * 2^(e - 136) is exact in float.
struct RgbeScale {
    float value[256];
    RgbeScale() {
        value[0] = 0.0f;
        for (int e = 1; e < 256; ++e) value[e] = std::ldexp(1.0f, e - 136);
    }
};

}  // namespace

bool RgbeReader::fill() {
    if (at_ < end_) return true;
    at_ = 0;
    end_ = std::fread(buffer_.data(), 1, buffer_.size(), file_.get());
    return end_ > 0;
}

bool RgbeReader::read(uint8_t* dst, size_t size) {
    while (size > 0) {
        if (!fill()) return false;
        const size_t n = std::min(size, end_ - at_);
        std::memcpy(dst, &buffer_[at_], n);
        at_ += n;
        dst += n;
        size -= n;
    }
    return true;
}

Result<std::optional<RgbeReader>> RgbeReader::open(const std::string& path) {
    RgbeReader r;
    r.file_.reset(std::fopen(path.c_str(), "rb"));
    if (!r.file_) return Error{std::string("cannot open it: ") + std::strerror(errno)};
    r.buffer_.resize(kRgbeReadAhead);
    // A header line, without its '\n'. `ended`: the file ends first; a line longer than
    // kRgbeMaxHeaderLine declines the file.
    bool ended = false, too_long = false;
    auto line = [&](std::string& text) {
        text.clear();
        for (uint8_t c; r.read(&c, 1);) {
            if (c == '\n') return true;
            if (text.size() == kRgbeMaxHeaderLine) return !(too_long = true);
            text += char(c);
        }
        return !(ended = true);
    };
    std::string text;
    uint8_t magic[2];
    if (!r.read(magic, 2) || magic[0] != '#' || magic[1] != '?') return std::optional<RgbeReader>();
    if (!line(text) && too_long) return std::optional<RgbeReader>();
    if (text != "RADIANCE" && text != "RGBE") return std::optional<RgbeReader>();
    bool rgbe = false, other_format = false;
    while (line(text) && !text.empty()) {
        if (text.rfind("FORMAT=", 0) != 0) continue;  // comments, EXPOSURE, GAMMA, ...: not applied
        if (text == "FORMAT=32-bit_rle_rgbe") rgbe = true;
        else other_format = true;
    }
    if (too_long) return std::optional<RgbeReader>();
    if (ended) return Error{"the Radiance header is cut short (no blank line ends it)"};
    if (!rgbe || other_format) return std::optional<RgbeReader>();
    if (!line(text)) {
        if (too_long) return std::optional<RgbeReader>();
        return Error{"the Radiance header ends before its size line (-Y height +X width)"};
    }
    // "-Y H +X W": rows from the top, texels from the left; other orders are declined.
    const size_t space = text.find(' ', 3);
    if (text.rfind("-Y ", 0) != 0 || space == std::string::npos || text.compare(space, 4, " +X ") != 0 ||
        !parse_rgbe_count(std::string_view(text).substr(3, space - 3), r.height_) ||
        !parse_rgbe_count(std::string_view(text).substr(space + 4), r.width_))
        return std::optional<RgbeReader>();
    return std::optional<RgbeReader>(std::move(r));
}

Status RgbeReader::read_row(float* rgb) {
    static const RgbeScale scale;
    const size_t w = size_t(width_);
    texels_.resize(w * 4);
    Status row = Ok{};
    uint8_t first[4];
    if (w < kRleMinWidth || w > kRleMaxWidth) row = read_old_row(nullptr);
    else if (!read(first, 4)) row = Error{"cut short (the file ends)"};
    else if (first[0] != 2 || first[1] != 2 || (first[2] & 0x80)) row = read_old_row(first);
    else if (const size_t declared = size_t(first[2]) << 8 | first[3]; declared != w)
        row = Error{"it declares width " + std::to_string(declared) + ", not the header's " + std::to_string(w)};
    else row = read_rle_row();
    if (!row) return Error{"row " + std::to_string(row_) + " of " + std::to_string(height_) + ": " + row.error().message};
    const uint8_t *r = &texels_[0], *g = &texels_[w], *b = &texels_[2 * w], *e = &texels_[3 * w];
    for (size_t x = 0; x < w; ++x) {
        const float f = scale.value[e[x]];
        rgb[x * 3 + 0] = float(r[x]) * f;
        rgb[x * 3 + 1] = float(g[x]) * f;
        rgb[x * 3 + 2] = float(b[x]) * f;
    }
    ++row_;
    return Ok{};
}

// Each component in turn: a byte n > 128 and a value (a run of n - 128), or a byte
// 1 <= n <= 128 and n values.
Status RgbeReader::read_rle_row() {
    const size_t w = size_t(width_);
    for (size_t c = 0; c < 4; ++c) {
        uint8_t* out = &texels_[c * w];
        for (size_t x = 0; x < w;) {
            uint8_t code[2];
            if (!read(code, 2)) return Error{"cut short (the file ends)"};
            const bool run = code[0] > 128;
            const size_t n = run ? code[0] - 128 : code[0];
            if (n == 0 || n > w - x)
                return Error{"a " + std::string(run ? "run" : "span") + " of " + std::to_string(n) + " at texel " +
                             std::to_string(x) + " of component " + std::to_string(c) + " (width " +
                             std::to_string(w) + ")"};
            if (run) {
                std::memset(out + x, code[1], n);
            } else {
                out[x] = code[1];
                if (n > 1 && !read(out + x + 1, n - 1)) return Error{"cut short (the file ends)"};
            }
            x += n;
        }
    }
    return Ok{};
}

// Texels of four bytes (the first already read when `first` is not null); a texel
// 1, 1, 1, n repeats the one before.
Status RgbeReader::read_old_row(const uint8_t* first) {
    const size_t w = size_t(width_);
    int shift = 0;
    for (size_t x = 0; x < w;) {
        uint8_t t[4];
        if (first) std::memcpy(t, std::exchange(first, nullptr), 4);
        else if (!read(t, 4)) return Error{"cut short (the file ends)"};
        if (t[0] == 1 && t[1] == 1 && t[2] == 1) {
            const uint64_t n = uint64_t(t[3]) << shift;
            if (x == 0 || n > w - x)
                return Error{"a repeat of " + std::to_string(n) + " texels at texel " + std::to_string(x) + " (width " +
                             std::to_string(w) + ")"};
            for (size_t c = 0; c < 4; ++c) std::memset(&texels_[c * w + x], texels_[c * w + x - 1], size_t(n));
            x += size_t(n);
            shift = std::min(shift + 8, 32);  // any count shifted by 32 passes every row's end
        } else {
            for (size_t c = 0; c < 4; ++c) texels_[c * w + x] = t[c];
            ++x;
            shift = 0;
        }
    }
    return Ok{};
}

}  // namespace facet::codec
