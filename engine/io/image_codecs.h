#pragma once
// Facet's own encoders for the files it writes (PNG previews, OpenEXR and Radiance
// environments) and a decoder for Radiance environments, written from the formats'
// specifications: a bake of builtin:sky or of a .hdr file then never loads the image
// module (io/image_module.h: OpenImageIO and ~260 libraries, ~0.4 s of CPU a process).
// Every other file is read through the module. deflate and CRC-32 are zlib's.
// Messages are reasons without the file's name, which the caller adds.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <facet/core/result.h>

namespace facet::codec {

// Where an encoder's bytes go: an open file, or memory (a file's bytes made ahead of
// writing it, e.g. on another thread). patch() rewrites bytes already put, then puts go on
// at the end (the EXR offset table). A false return is a failed write (errno says why).
class ByteSink {
public:
    explicit ByteSink(std::FILE* file) : file_(file) {}
    explicit ByteSink(std::vector<uint8_t>& memory) : memory_(&memory) {}
    bool put(const void* bytes, size_t size);
    bool patch(uint64_t offset, const void* bytes, size_t size);

private:
    std::FILE* file_ = nullptr;
    std::vector<uint8_t>* memory_ = nullptr;
};

// PNG (W3C, "Portable Network Graphics Specification", 2nd ed.): 8-bit RGBA with
// straight alpha (colour type 6), rows top first, each row filtered with Sub (filter
// type 1), deflated at zlib level 1 with run-length matches only (Z_RLE), in `parts` runs
// of rows on as many threads (0: one per core, up to 4, for images of 256 KiB or more).
Status write_png(ByteSink& out, uint32_t width, uint32_t height, const uint8_t* rgba, uint32_t parts = 0);

// OpenEXR ("OpenEXR File Layout"): one part of scanlines, channels A, B, G, R as 32-bit
// float (every bit of the input kept), ZIP_COMPRESSION (16 rows a chunk), increasing y.
// No date or other varying attribute: the same texels make the same bytes. `out` must be
// a seekable file or memory (the offset table is written last).
// zlib level 1: builtin:sky's 1024x512 environment in 25 ms and 551 KB, royal_esplanade_1k's
// in 66 ms and 2.33 MB; at level 4, OpenEXR's own (the sizes OpenImageIO's files had),
// 36 ms and 523 KB, 87 ms and 2.18 MB.
// The chunks are compressed in `parts` runs on as many threads (0: one per core, up to 4,
// for images of 1 MiB or more); the bytes are the same whatever the parts.
constexpr int kExrZipLevel = 1;
Status write_exr(ByteSink& out, uint32_t width, uint32_t height, const float* rgba, uint32_t parts = 0);

// Radiance RGBE (Ward, "Real Pixels", Graphics Gems II, 1991): RGB of the RGBA input
// (alpha dropped), header "#?RADIANCE", FORMAT=32-bit_rle_rgbe, "-Y H +X W", rows
// run-length encoded per component when 8 <= width <= 32767 (flat otherwise).
// Channels that are negative or NaN are written as 0, values above the largest RGBE
// (255 * 2^119) as it.
Status write_rgbe(ByteSink& out, uint32_t width, uint32_t height, const float* rgba);

// A Radiance file read a row at a time, so memory is one row whatever the file's size.
class RgbeReader {
public:
    // Reads the header. Nothing when the file is not one this reader takes, which the
    // caller leaves to the image module: no "#?RADIANCE" or "#?RGBE" line first, a FORMAT
    // other than 32-bit_rle_rgbe (or none), a size line other than "-Y H +X W" (rows in
    // another order), a header line over 64 KiB. An Error when the file cannot be opened
    // or its header ends before the size line.
    static Result<std::optional<RgbeReader>> open(const std::string& path);

    // As declared: the caller checks them before reading rows (the reader keeps 4 bytes
    // a texel of one row).
    uint64_t width() const { return width_; }
    uint64_t height() const { return height_; }

    // The next row (top first) as width() RGB floats, each m * 2^(e - 136) exactly, 0 when
    // e is 0, as OpenImageIO 2.4 decodes them. Rows are new-style run-length encoded (per
    // component), flat, or old-style (a texel 1, 1, 1, n repeats the one before n << s
    // times, s growing by 8 for each such texel in a row, as Radiance's own reader does;
    // OpenImageIO 2.4 reads those texels as values). An Error says which row is damaged
    // or cut short, and how.
    Status read_row(float* rgb);

private:
    struct FileCloser {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    bool fill();
    bool read(uint8_t* dst, size_t size);
    Status read_rle_row();
    Status read_old_row(const uint8_t* first);

    std::unique_ptr<std::FILE, FileCloser> file_;
    std::vector<uint8_t> buffer_;  // bytes read ahead from file_
    size_t at_ = 0, end_ = 0;
    uint64_t width_ = 0, height_ = 0;
    uint64_t row_ = 0;
    std::vector<uint8_t> texels_;  // the row's R, G, B and E bytes, component after component
};

}  // namespace facet::codec
