#pragma once
// Writes Radiance .hdr files with run-length encoded scanlines, one row at a time, so a
// test can make a 16k x 8k environment of mostly constant content in a few megabytes
// of disk and almost no memory. RGBE as in Ward's format: a shared exponent e and
// mantissas m, value = m * 2^(e - 136).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace facet::test {

inline std::array<uint8_t, 4> to_rgbe(float r, float g, float b) {
    const float v = std::max(r, std::max(g, b));
    if (v < 1e-32f) return {0, 0, 0, 0};
    int e = 0;
    const float scale = std::frexp(v, &e) * 256.0f / v;
    return {uint8_t(r * scale), uint8_t(g * scale), uint8_t(b * scale), uint8_t(e + 128)};
}

inline float from_rgbe(uint8_t m, uint8_t e) { return e == 0 ? 0.0f : std::ldexp(float(m), int(e) - 136); }

// One component of a scanline: runs of 3 or more equal bytes as (128 + n, value),
// everything else as literal spans (n, n values).
inline void encode_rle(const std::vector<uint8_t>& bytes, std::vector<uint8_t>& out) {
    size_t i = 0;
    while (i < bytes.size()) {
        size_t run = 1;
        while (i + run < bytes.size() && run < 127 && bytes[i + run] == bytes[i]) ++run;
        if (run >= 3) {
            out.push_back(uint8_t(128 + run));
            out.push_back(bytes[i]);
            i += run;
            continue;
        }
        size_t start = i, n = 0;
        while (i < bytes.size() && n < 128) {
            if (i + 2 < bytes.size() && bytes[i] == bytes[i + 1] && bytes[i] == bytes[i + 2]) break;
            ++i;
            ++n;
        }
        out.push_back(uint8_t(n));
        out.insert(out.end(), bytes.begin() + long(start), bytes.begin() + long(i));
    }
}

// `row(y, rgb)` fills width * 3 floats for row y (0 = top). Width 8..32767.
inline bool write_rle_hdr(const std::string& path, uint32_t width, uint32_t height,
                          const std::function<void(uint32_t, std::vector<float>&)>& row) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return false;
    std::fprintf(f, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %u +X %u\n", height, width);
    std::vector<float> rgb(size_t(width) * 3);
    std::vector<uint8_t> component(width), line;
    for (uint32_t y = 0; y < height; ++y) {
        row(y, rgb);
        line = {2, 2, uint8_t(width >> 8), uint8_t(width & 255)};
        std::vector<std::array<uint8_t, 4>> texels(width);
        for (uint32_t x = 0; x < width; ++x) texels[x] = to_rgbe(rgb[x * 3], rgb[x * 3 + 1], rgb[x * 3 + 2]);
        for (int c = 0; c < 4; ++c) {
            for (uint32_t x = 0; x < width; ++x) component[x] = texels[x][c];
            encode_rle(component, line);
        }
        std::fwrite(line.data(), 1, line.size(), f);
    }
    return std::fclose(f) == 0;
}

// A file that is only a header declaring `width` x `height` (and a few bytes of data).
inline bool write_hdr_header_only(const std::string& path, const std::string& size_line) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return false;
    std::fprintf(f, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n%s\n", size_line.c_str());
    const uint8_t data[8] = {2, 2, 0, 8, 136, 0, 136, 0};
    std::fwrite(data, 1, sizeof data, f);
    return std::fclose(f) == 0;
}

}  // namespace facet::test
