#include "io/exr_header.h"

#include <cstdint>
#include <fstream>

namespace facet {

namespace {

constexpr uint32_t kMagic = 20000630;        // 0x76, 0x2f, 0x31, 0x01
constexpr uint32_t kMultipartFlag = 0x1000;  // several headers, the list ending with an empty one
// OpenEXR reads names up to this long whatever the version's long-names flag says.
constexpr size_t kMaxName = 255;

bool read_u32(std::istream& in, uint32_t& value) {
    unsigned char bytes[4];
    if (!in.read(reinterpret_cast<char*>(bytes), 4)) return false;
    value = uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16 | uint32_t(bytes[3]) << 24;
    return true;
}

// A NUL-terminated string of at most `max` bytes; false past the end or when longer.
bool read_name(std::istream& in, size_t max, std::string& name) {
    name.clear();
    for (char c; in.get(c);) {
        if (c == '\0') return true;
        if (name.size() == max) return false;
        name += c;
    }
    return false;
}

// For the message: the name is the file's bytes, control characters included.
std::string printable(std::string text) {
    for (char& c : text)
        if (c < 0x20 || c == 0x7f) c = '?';
    return text;
}

}  // namespace

std::string check_exr_attribute_sizes(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) return {};
    const uint64_t file_size = uint64_t(std::streamoff(in.tellg()));
    in.seekg(0);
    uint32_t magic = 0, version = 0;
    if (!read_u32(in, magic) || magic != kMagic || !read_u32(in, version)) return {};
    std::string name, type;
    // Anything malformed other than a size is left to OpenEXR to report.
    while (true) {
        while (true) {
            if (!read_name(in, kMaxName, name)) return {};
            if (name.empty()) break;  // the end of this header
            uint32_t size = 0;
            if (!read_name(in, kMaxName, type) || !read_u32(in, size)) return {};
            const uint64_t at = uint64_t(std::streamoff(in.tellg()));
            if (uint64_t(size) > file_size - at)
                return "the EXR header attribute '" + printable(name) + "' declares " + std::to_string(int32_t(size)) +
                       " bytes, more than the file holds (" + std::to_string(file_size) + " bytes)";
            in.seekg(std::streamoff(size), std::ios::cur);
        }
        if (!(version & kMultipartFlag) || in.peek() == 0 || !in) return {};
    }
}

}  // namespace facet
