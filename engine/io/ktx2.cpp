#include <facet/io/ktx2.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <numeric>
#include <set>
#include <system_error>

#include <facet/io/atomic_file.h>

// Written from the KTX File Format Specification 2.0 (sections named in the comments) and
// the Khronos Data Format Specification 1.3 (Basic Data Format Descriptor block).

namespace facet {

namespace {

constexpr std::byte kIdentifier[12] = {
    std::byte{0xAB}, std::byte{'K'},  std::byte{'T'},  std::byte{'X'},  std::byte{' '},  std::byte{'2'},
    std::byte{'0'},  std::byte{0xBB}, std::byte{'\r'}, std::byte{'\n'}, std::byte{0x1A}, std::byte{'\n'}};
constexpr uint64_t kHeaderSize = 48;      // identifier + nine uint32 fields
constexpr uint64_t kIndexSize = 32;       // dfd/kvd offsets and lengths (uint32), sgd (uint64)
constexpr uint64_t kLevelEntrySize = 24;  // byteOffset, byteLength, uncompressedByteLength
// Guards the size arithmetic against overflow; far beyond any Vulkan image limit.
constexpr uint32_t kMaxDimension = 1u << 20;

// Khronos Data Format Specification enumerants (khr_df.h values).
constexpr uint32_t kDfModelRgbsda = 1;
constexpr uint32_t kDfPrimariesBt709 = 1;
constexpr uint32_t kDfTransferLinear = 1;
constexpr uint32_t kDfVersion13 = 2;
constexpr uint32_t kDfQualifierSigned = 0x40;
constexpr uint32_t kDfQualifierFloat = 0x80;
constexpr uint32_t kDfChannelIds[4] = {0, 1, 2, 15};  // R, G, B, A in the RGBSDA model
// For float samples the limits are binary32 values whatever the sample's own size:
// -1.0 and 1.0 for signed formats (Data Format Specification, sampleLower/sampleUpper).
constexpr uint32_t kFloatLowerSigned = 0xBF800000u;
constexpr uint32_t kFloatUpper = 0x3F800000u;

struct FormatInfo {
    VkFormat format;
    uint32_t channels;
    uint32_t channel_bytes;  // the header's typeSize
    const char* name;
};

constexpr FormatInfo kFormats[] = {
    {VK_FORMAT_R16G16_SFLOAT, 2, 2, "VK_FORMAT_R16G16_SFLOAT"},
    {VK_FORMAT_R32G32_SFLOAT, 2, 4, "VK_FORMAT_R32G32_SFLOAT"},
    {VK_FORMAT_R16G16B16A16_SFLOAT, 4, 2, "VK_FORMAT_R16G16B16A16_SFLOAT"},
    {VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4, "VK_FORMAT_R32G32B32A32_SFLOAT"},
};

const FormatInfo* find_format(uint32_t format) {
    for (const FormatInfo& info : kFormats)
        if (static_cast<uint32_t>(info.format) == format) return &info;
    return nullptr;
}

uint64_t round_up(uint64_t value, uint64_t alignment) { return (value + alignment - 1) / alignment * alignment; }

// "Mip Level Array": without supercompression each level starts at a multiple of
// lcm(texel block size, 4).
uint64_t level_alignment(const FormatInfo& info) { return std::lcm<uint64_t>(info.channels * info.channel_bytes, 4); }

uint32_t max_levels(uint32_t width, uint32_t height) { return std::bit_width(std::max(width, height)); }

uint64_t level_bytes(const FormatInfo& info, uint32_t width, uint32_t height, uint32_t faces, uint32_t level) {
    uint64_t w = std::max<uint64_t>(1, width >> level), h = std::max<uint64_t>(1, height >> level);
    return uint64_t{faces} * w * h * info.channels * info.channel_bytes;
}

class ByteWriter {
public:
    void u32(uint32_t v) {
        for (int i = 0; i < 4; ++i) bytes.push_back(std::byte(v >> (8 * i)));
    }
    void u64(uint64_t v) {
        for (int i = 0; i < 8; ++i) bytes.push_back(std::byte(v >> (8 * i)));
    }
    void put_u64(size_t at, uint64_t v) {
        for (int i = 0; i < 8; ++i) bytes[at + i] = std::byte(v >> (8 * i));
    }
    void append(const void* data, size_t size) {
        auto p = static_cast<const std::byte*>(data);
        bytes.insert(bytes.end(), p, p + size);
    }
    void pad_to(uint64_t alignment) { bytes.resize(round_up(bytes.size(), alignment), std::byte{0}); }
    std::vector<std::byte> bytes;
};

// "Data Format Descriptor": the total size, then one Basic Data Format Descriptor block
// with one sample per channel.
std::vector<std::byte> make_dfd(const FormatInfo& info) {
    uint32_t block_size = 24 + 16 * info.channels;
    uint32_t bits = 8 * info.channel_bytes;
    ByteWriter w;
    w.u32(4 + block_size);
    w.u32(0);  // vendorId KHRONOS (17 bits), descriptorType BASICFORMAT (15 bits)
    w.u32(kDfVersion13 | (block_size << 16));
    w.u32(kDfModelRgbsda | (kDfPrimariesBt709 << 8) | (kDfTransferLinear << 16) | (0u << 24));  // flags: straight alpha
    w.u32(0);                                     // texelBlockDimension0..3 (stored minus one): 1x1x1x1
    w.u32(info.channels * info.channel_bytes);    // bytesPlane0..3
    w.u32(0);                                     // bytesPlane4..7
    for (uint32_t c = 0; c < info.channels; ++c) {
        uint32_t channel_type = kDfChannelIds[c] | kDfQualifierFloat | kDfQualifierSigned;
        w.u32((c * bits) | ((bits - 1) << 16) | (channel_type << 24));
        w.u32(0);  // samplePosition0..3
        w.u32(kFloatLowerSigned);
        w.u32(kFloatUpper);
    }
    return std::move(w.bytes);
}

// "Key/Value Data": sorted by key bytes; each entry is its length, key NUL value, padded to 4.
Result<std::vector<std::byte>> make_kvd(const std::string& path, std::vector<std::pair<std::string, std::string>> kv) {
    std::sort(kv.begin(), kv.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    ByteWriter w;
    for (size_t i = 0; i < kv.size(); ++i) {
        const auto& [key, value] = kv[i];
        if (key.empty() || key.find('\0') != std::string::npos)
            return Error{path + ": key/value key '" + key + "' is empty or contains a NUL"};
        if (i > 0 && kv[i - 1].first == key) return Error{path + ": key/value key '" + key + "' appears twice"};
        w.u32(static_cast<uint32_t>(key.size() + 1 + value.size() + 1));
        w.append(key.data(), key.size());
        w.bytes.push_back(std::byte{0});
        w.append(value.data(), value.size());
        w.bytes.push_back(std::byte{0});
        w.pad_to(4);
    }
    return std::move(w.bytes);
}

Status validate_for_writing(const std::string& path, const Ktx2Image& image,
                            std::span<const std::span<const std::byte>> levels, const FormatInfo* info) {
    if (!info) return Error{path + ": unsupported VkFormat " + std::to_string(image.format)};
    if (image.width == 0 || image.height == 0 || image.width > kMaxDimension || image.height > kMaxDimension)
        return Error{path + ": invalid size " + std::to_string(image.width) + "x" + std::to_string(image.height)};
    if (image.faces != 1 && image.faces != 6)
        return Error{path + ": faces must be 1 or 6, not " + std::to_string(image.faces)};
    if (image.faces == 6 && image.width != image.height) return Error{path + ": a cube map must be square"};
    if (image.levels == 0 || image.levels > max_levels(image.width, image.height))
        return Error{path + ": invalid level count " + std::to_string(image.levels)};
    if (levels.size() != image.levels)
        return Error{path + ": " + std::to_string(levels.size()) + " levels of data for " +
                     std::to_string(image.levels) + " levels"};
    for (uint32_t l = 0; l < image.levels; ++l) {
        uint64_t expected = level_bytes(*info, image.width, image.height, image.faces, l);
        if (levels[l].size() != expected)
            return Error{path + ": level " + std::to_string(l) + " holds " + std::to_string(levels[l].size()) +
                         " bytes, expected " + std::to_string(expected)};
    }
    return Ok{};
}

// Bounds-checked little-endian view of the file.
struct Bytes {
    const std::vector<std::byte>& data;
    uint32_t u32(uint64_t at) const {
        uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v |= uint32_t(data[at + i]) << (8 * i);
        return v;
    }
    uint64_t u64(uint64_t at) const { return u32(at) | (uint64_t{u32(at + 4)} << 32); }
    bool holds(uint64_t offset, uint64_t length) const {
        return offset <= data.size() && length <= data.size() - offset;
    }
};

std::string check_dfd(const Bytes& in, uint64_t offset, uint64_t length, const FormatInfo& info) {
    uint32_t block_size = 24 + 16 * info.channels;
    if (length < 4 + 24) return "data format descriptor too short";
    if (in.u32(offset) != length) return "data format descriptor total size disagrees with dfdByteLength";
    if (in.u32(offset + 4) != 0) return "first data format descriptor block is not the Khronos basic block";
    uint32_t size_word = in.u32(offset + 8);
    if ((size_word >> 16) != block_size || 4 + block_size > length)
        return "data format descriptor block size does not match " + std::string(info.name);
    uint32_t model_word = in.u32(offset + 12);
    if ((model_word & 0xFF) != kDfModelRgbsda) return "data format descriptor colour model is not RGBSDA";
    if ((in.u32(offset + 20) & 0xFF) != info.channels * info.channel_bytes)
        return "data format descriptor bytesPlane0 does not match " + std::string(info.name);
    uint32_t bits = 8 * info.channel_bytes;
    for (uint32_t c = 0; c < info.channels; ++c) {
        uint32_t word = in.u32(offset + 28 + 16 * c);
        uint32_t channel_type = word >> 24;
        if ((word & 0xFFFF) != c * bits || ((word >> 16) & 0xFF) != bits - 1 ||
            (channel_type & 0x0F) != kDfChannelIds[c] || !(channel_type & kDfQualifierFloat))
            return "data format descriptor sample " + std::to_string(c) + " does not match " + info.name;
    }
    return {};
}

std::string read_kvd(const Bytes& in, uint64_t offset, uint64_t length, Ktx2Image& image) {
    uint64_t end = offset + length, at = offset;
    std::set<std::string> keys;  // a key given twice has no one meaning (and would not write back)
    while (at < end) {
        if (end - at < 4) return "key/value data ends inside an entry length";
        uint64_t entry = in.u32(at);
        at += 4;
        if (entry > end - at) return "key/value entry runs past the key/value data";
        auto first = reinterpret_cast<const char*>(in.data.data() + at);
        const char* nul = static_cast<const char*>(std::memchr(first, 0, entry));
        if (!nul || nul == first) return "key/value entry has an empty or unterminated key";
        std::string key(first, nul);
        if (!keys.insert(key).second) return "key/value key '" + key + "' appears twice";
        std::string value(nul + 1, first + entry);
        if (!value.empty() && value.back() == '\0') value.pop_back();
        image.key_values.emplace_back(std::move(key), std::move(value));
        at = std::min(end, round_up(at + entry, 4));
    }
    return {};
}

Result<std::vector<std::byte>> read_whole_file(const std::string& path) {
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) return Error{path + ": cannot open: " + std::error_code(errno, std::generic_category()).message()};
    std::streamoff size = file.tellg();
    if (size < 0) return Error{path + ": cannot determine the file size"};
    std::vector<std::byte> bytes(static_cast<size_t>(size));
    file.seekg(0);
    file.read(reinterpret_cast<char*>(bytes.data()), size);
    if (!file) return Error{path + ": read failed"};
    return bytes;
}

std::string parse(const std::vector<std::byte>& data, Ktx2Image& image) {
    Bytes in{data};
    if (data.size() < kHeaderSize + kIndexSize) return "file too short for a KTX 2 header (" + std::to_string(data.size()) + " bytes)";
    if (!std::equal(std::begin(kIdentifier), std::end(kIdentifier), data.begin())) return "not a KTX 2 file (identifier mismatch)";
    uint32_t vk_format = in.u32(12), type_size = in.u32(16), width = in.u32(20), height = in.u32(24);
    uint32_t depth = in.u32(28), layers = in.u32(32), faces = in.u32(36), levels = in.u32(40), scheme = in.u32(44);
    const FormatInfo* info = find_format(vk_format);
    if (!info) return "unsupported vkFormat " + std::to_string(vk_format);
    if (type_size != info->channel_bytes) return "typeSize " + std::to_string(type_size) + " does not match " + info->name;
    if (scheme != 0) return "supercompression scheme " + std::to_string(scheme) + " is not supported";
    if (width == 0 || height == 0) return "1D or empty images are not supported";
    if (width > kMaxDimension || height > kMaxDimension) return "image size too large";
    if (depth != 0) return "3D images are not supported";
    if (layers != 0) return "array textures are not supported";
    if (faces != 1 && faces != 6) return "faceCount must be 1 or 6, not " + std::to_string(faces);
    if (faces == 6 && width != height) return "cube map faces are not square";
    if (levels == 0) levels = 1;  // "levelCount": 0 asks the loader to generate mips; level 0 is stored
    if (levels > max_levels(width, height)) return "levelCount " + std::to_string(levels) + " is too large for the size";

    uint64_t dfd_offset = in.u32(48), dfd_length = in.u32(52), kvd_offset = in.u32(56), kvd_length = in.u32(60);
    uint64_t sgd_length = in.u64(72);
    if (!in.holds(kHeaderSize + kIndexSize, kLevelEntrySize * levels)) return "file truncated inside the level index";
    if (!in.holds(dfd_offset, dfd_length)) return "data format descriptor lies outside the file";
    if (std::string problem = check_dfd(in, dfd_offset, dfd_length, *info); !problem.empty()) return problem;
    if (kvd_length > 0) {
        if (!in.holds(kvd_offset, kvd_length)) return "key/value data lies outside the file";
        if (std::string problem = read_kvd(in, kvd_offset, kvd_length, image); !problem.empty()) return problem;
    }
    if (sgd_length != 0) return "supercompression global data present without supercompression";

    image.format = info->format;
    image.width = width;
    image.height = height;
    image.faces = faces;
    image.levels = levels;
    image.level_data.resize(levels);
    for (uint32_t l = 0; l < levels; ++l) {
        uint64_t entry = kHeaderSize + kIndexSize + kLevelEntrySize * l;
        uint64_t offset = in.u64(entry), length = in.u64(entry + 8), uncompressed = in.u64(entry + 16);
        uint64_t expected = level_bytes(*info, width, height, faces, l);
        std::string level = "level " + std::to_string(l);
        if (length != expected || uncompressed != expected)
            return level + " byte length " + std::to_string(length) + " does not match the expected " + std::to_string(expected);
        if (!in.holds(offset, length)) return level + " data lies outside the file (truncated?)";
        if (offset % level_alignment(*info) != 0) return level + " offset is not aligned as the specification requires";
        auto first = data.begin() + static_cast<std::ptrdiff_t>(offset);
        image.level_data[l].assign(first, first + static_cast<std::ptrdiff_t>(length));
    }
    return {};
}

}  // namespace

uint32_t ktx2_texel_size(VkFormat format) {
    const FormatInfo* info = find_format(static_cast<uint32_t>(format));
    return info ? info->channels * info->channel_bytes : 0;
}

uint64_t ktx2_level_size(const Ktx2Image& image, uint32_t level) {
    const FormatInfo* info = find_format(static_cast<uint32_t>(image.format));
    return info ? level_bytes(*info, image.width, image.height, image.faces, level) : 0;
}

Status write_ktx2(const std::string& path, const Ktx2Image& image) {
    std::vector<std::span<const std::byte>> levels(image.level_data.begin(), image.level_data.end());
    return write_ktx2(path, image, levels);
}

Status write_ktx2(const std::string& path, const Ktx2Image& image, std::span<const std::span<const std::byte>> levels) {
    const FormatInfo* info = find_format(static_cast<uint32_t>(image.format));
    if (Status valid = validate_for_writing(path, image, levels, info); !valid) return valid;
    std::vector<std::byte> dfd = make_dfd(*info);
    Result<std::vector<std::byte>> kvd = make_kvd(path, image.key_values);
    if (!kvd) return kvd.error();

    // Everything before the levels' data, and where each level's data goes.
    ByteWriter w;
    w.append(kIdentifier, sizeof kIdentifier);
    for (uint32_t v : {uint32_t(info->format), info->channel_bytes, image.width, image.height, 0u, 0u, image.faces,
                       image.levels, 0u})
        w.u32(v);
    uint64_t dfd_offset = kHeaderSize + kIndexSize + kLevelEntrySize * image.levels;
    uint64_t kvd_offset = dfd_offset + dfd.size();
    w.u32(static_cast<uint32_t>(dfd_offset));
    w.u32(static_cast<uint32_t>(dfd.size()));
    w.u32(kvd->empty() ? 0 : static_cast<uint32_t>(kvd_offset));
    w.u32(static_cast<uint32_t>(kvd->size()));
    w.u64(0);  // sgdByteOffset
    w.u64(0);  // sgdByteLength
    size_t level_index = w.bytes.size();
    w.bytes.resize(w.bytes.size() + kLevelEntrySize * image.levels);
    w.append(dfd.data(), dfd.size());
    w.append(kvd->data(), kvd->size());
    // "Mip Level Array": smallest level first, so a streaming loader can show a low mip early.
    const uint64_t alignment = level_alignment(*info);
    std::vector<uint64_t> offsets(image.levels);
    uint64_t end = w.bytes.size();
    for (uint32_t l = image.levels; l-- > 0;) {
        end = (end + alignment - 1) / alignment * alignment;
        offsets[l] = end;
        size_t entry = level_index + kLevelEntrySize * l;
        w.put_u64(entry, end);
        w.put_u64(entry + 8, levels[l].size());
        w.put_u64(entry + 16, levels[l].size());
        end += levels[l].size();
    }

    // The levels are written from where they lie (a mapped readback buffer: no copy).
    return write_atomically(path, [&](const std::string& temp) -> Status {
        std::ofstream out(temp, std::ios::binary);
        if (!out) return Error{path + ": cannot open for writing: " + std::error_code(errno, std::generic_category()).message()};
        out.write(reinterpret_cast<const char*>(w.bytes.data()), static_cast<std::streamsize>(w.bytes.size()));
        uint64_t at = w.bytes.size();
        static const char zeros[64] = {};
        for (uint32_t l = image.levels; l-- > 0;) {
            out.write(zeros, static_cast<std::streamsize>(offsets[l] - at));
            out.write(reinterpret_cast<const char*>(levels[l].data()), static_cast<std::streamsize>(levels[l].size()));
            at = offsets[l] + levels[l].size();
        }
        out.close();
        if (!out) return Error{path + ": write failed (disk full?)"};
        return Ok{};
    });
}

Result<Ktx2Image> parse_ktx2(const std::vector<std::byte>& bytes, const std::string& path) {
    Ktx2Image image;
    if (std::string problem = parse(bytes, image); !problem.empty()) return Error{path + ": " + problem};
    return image;
}

Result<Ktx2Image> read_ktx2(const std::string& path) {
    Result<std::vector<std::byte>> data = read_whole_file(path);
    if (!data) return data.error();
    return parse_ktx2(*data, path);
}

uint16_t float_to_half(float f) {
    uint32_t x = std::bit_cast<uint32_t>(f);
    uint16_t sign = static_cast<uint16_t>((x >> 16) & 0x8000);
    uint32_t a = x & 0x7FFFFFFF;
    if (a > 0x7F800000) return sign | 0x7E00 | ((a >> 13) & 0x3FF);  // NaN: quiet, top payload bits kept
    // 65520 is halfway between 65504 (largest half, odd mantissa) and 2^16: ties go to inf.
    if (a >= 0x477FF000) return sign | 0x7C00;
    auto round_shift = [](uint32_t m, int shift) {
        uint32_t q = m >> shift, rem = m & ((1u << shift) - 1), half = 1u << (shift - 1);
        return q + ((rem > half || (rem == half && (q & 1))) ? 1 : 0);
    };
    if (a >= 0x38800000)  // normal half (>= 2^-14); a mantissa carry correctly bumps the exponent
        return static_cast<uint16_t>(sign | round_shift(a - (112u << 23), 13));
    if (a <= 0x33000000) return sign;  // <= 2^-25, half the smallest denormal: ties to even zero
    // Denormal half: value / 2^-24 = m * 2^(e - 126) with m the 24-bit significand.
    uint32_t e = a >> 23, m = (a & 0x7FFFFF) | 0x800000;
    return static_cast<uint16_t>(sign | round_shift(m, static_cast<int>(126 - e)));
}

float half_to_float(uint16_t h) {
    uint32_t sign = uint32_t(h & 0x8000) << 16, e = (h >> 10) & 0x1F, m = h & 0x3FF;
    if (e == 0) {
        float magnitude = static_cast<float>(m) * 0x1p-24f;  // exact: m < 2^10
        return sign ? -magnitude : magnitude;
    }
    if (e == 31) return std::bit_cast<float>(sign | 0x7F800000 | (m << 13));
    return std::bit_cast<float>(sign | ((e + 112) << 23) | (m << 13));
}

}  // namespace facet
