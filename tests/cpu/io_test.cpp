// Image files, atomic writes and JSON metadata.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <vector>

#include <facet/core/hash.h>
#include <facet/io/atomic_file.h>
#include <facet/io/image_io.h>
#include <facet/io/json_writer.h>

namespace facet {
namespace {

namespace fs = std::filesystem;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_io_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    size_t file_count() const { return std::distance(fs::directory_iterator(path), fs::directory_iterator()); }
};

std::vector<float> read_back(const std::string& path, int& width, int& height, int& channels) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // compare stored values, not premultiplied ones
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    width = spec.width;
    height = spec.height;
    channels = spec.nchannels;
    std::vector<float> pixels(size_t(width) * height * channels);
    in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data());
    return pixels;
}

TEST(ImageIo, ExrKeepsFloatRgbaExactly) {
    TempDir dir;
    const uint32_t w = 5, h = 3;
    std::vector<float> rgba(w * h * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = 1e-3f * float(i * i) + (i % 7 == 0 ? 4.5e4f : 0.0f);
    const std::string path = (dir.path / "a.exr").string();
    ASSERT_TRUE(write_hdr_image(path, w, h, rgba));
    int rw, rh, rc;
    auto back = read_back(path, rw, rh, rc);
    ASSERT_EQ(rw, 5);
    ASSERT_EQ(rh, 3);
    ASSERT_EQ(rc, 4);
    EXPECT_EQ(back, rgba);
    EXPECT_EQ(dir.file_count(), 1u) << "no temporary left behind";
}

TEST(ImageIo, HdrKeepsRgbWithinRgbePrecision) {
    TempDir dir;
    const uint32_t w = 4, h = 2;
    std::vector<float> rgba(w * h * 4, 1.0f);
    rgba[0] = 40000.0f;
    rgba[5] = 0.25f;
    const std::string path = (dir.path / "a.hdr").string();
    ASSERT_TRUE(write_hdr_image(path, w, h, rgba));
    int rw, rh, rc;
    auto back = read_back(path, rw, rh, rc);
    ASSERT_EQ(rc, 3);
    EXPECT_NEAR(back[0], 40000.0f, 40000.0f / 128);  // RGBE: 8-bit mantissa
    EXPECT_NEAR(back[4], 0.25f, 0.25f / 128);
}

TEST(ImageIo, PngRoundTrip) {
    TempDir dir;
    std::vector<uint8_t> rgba(2 * 2 * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = uint8_t(i * 17);
    const std::string path = (dir.path / "a.png").string();
    ASSERT_TRUE(write_ldr_image(path, 2, 2, rgba));
    int rw, rh, rc;
    auto back = read_back(path, rw, rh, rc);
    ASSERT_EQ(back.size(), rgba.size());
    for (size_t i = 0; i < rgba.size(); ++i) EXPECT_NEAR(back[i] * 255.0f, rgba[i], 0.01f);
}

TEST(ImageIo, BadOutputsAreClearErrorsAndLeaveNothing) {
    TempDir dir;
    std::vector<float> rgba(4, 1.0f);
    auto wrong_ext = write_hdr_image((dir.path / "a.png").string(), 1, 1, rgba);
    ASSERT_FALSE(wrong_ext);
    EXPECT_NE(wrong_ext.error().message.find("a.png"), std::string::npos);
    auto wrong_size = write_hdr_image((dir.path / "b.exr").string(), 2, 2, rgba);
    ASSERT_FALSE(wrong_size);
    auto missing_dir = write_hdr_image((dir.path / "no/such/dir/c.exr").string(), 1, 1, rgba);
    ASSERT_FALSE(missing_dir);
    EXPECT_NE(missing_dir.error().message.find("c.exr"), std::string::npos) << missing_dir.error().message;
    EXPECT_EQ(dir.file_count(), 0u);
}

TEST(AtomicFile, FailedWriteKeepsTheOldFile) {
    TempDir dir;
    const std::string path = (dir.path / "keep.txt").string();
    ASSERT_TRUE(write_text_file(path, "old"));
    Status failed = write_atomically(path, [](const std::string& temp) -> Status {
        std::ofstream(temp) << "half";
        return Error{"simulated failure"};
    });
    ASSERT_FALSE(failed);
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(text, "old");
    EXPECT_EQ(dir.file_count(), 1u);
}

TEST(AtomicFile, EnsureDirectoryReportsAFileInTheWay) {
    TempDir dir;
    const std::string file = (dir.path / "plain").string();
    ASSERT_TRUE(write_text_file(file, "x"));
    auto status = ensure_directory(file);
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().message.find("not a directory"), std::string::npos);
    EXPECT_TRUE(ensure_directory((dir.path / "a/b/c").string()));
}

// Hash64::add_bulk (environments' content hashes): the same bytes the same value; every
// one-bit change of a buffer (in whole 32-byte groups and in the tail), a byte more, or
// FNV's add() of the same bytes gives another.
TEST(Hash64, BulkHashSeesEveryBitAndTheLength) {
    std::vector<unsigned char> bytes(1000);
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>((i * 131) >> 3);
    auto bulk = [](const std::vector<unsigned char>& b) { return Hash64{}.add_bulk(b.data(), b.size()).value(); };
    const uint64_t original = bulk(bytes);
    EXPECT_EQ(bulk(bytes), original);
    EXPECT_NE(Hash64{}.add(bytes.data(), bytes.size()).value(), original);
    std::set<uint64_t> seen{original};
    for (size_t i = 0; i < bytes.size(); ++i)
        for (int bit = 0; bit < 8; ++bit) {
            bytes[i] ^= static_cast<unsigned char>(1u << bit);
            EXPECT_TRUE(seen.insert(bulk(bytes)).second) << "byte " << i << " bit " << bit;
            bytes[i] ^= static_cast<unsigned char>(1u << bit);
        }
    EXPECT_EQ(seen.size(), 1u + bytes.size() * 8);
    bytes.push_back(0);
    EXPECT_EQ(seen.count(bulk(bytes)), 0u) << "a trailing zero byte";
}

TEST(JsonWriter, WritesNestedValuesAndEscapes) {
    JsonWriter json;
    json.begin_object()
        .value("name", "a \"quoted\"\nline")
        .value("time_ms", 1.5)
        .value("count", 3)
        .value("flag", true)
        .value("nan", std::nan(""))
        .begin_array("passes")
        .begin_object()
        .value("pass", "sky")
        .end_object()
        .end_array()
        .begin_array("empty")
        .end_array()
        .end_object();
    const std::string expected =
        "{\n  \"name\": \"a \\\"quoted\\\"\\nline\",\n  \"time_ms\": 1.5,\n  \"count\": 3,\n  \"flag\": true,\n"
        "  \"nan\": null,\n  \"passes\": [\n    {\n      \"pass\": \"sky\"\n    }\n  ],\n  \"empty\": []\n}\n";
    EXPECT_EQ(json.str(), expected);
}

}  // namespace
}  // namespace facet
