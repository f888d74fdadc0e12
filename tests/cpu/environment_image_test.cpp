// Loading environments: real files, odd sizes, and every way a file can be bad.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <facet/io/environment_image.h>
#include <facet/io/image_io.h>

namespace facet {
namespace {

namespace fs = std::filesystem;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_env_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

void write_float_image(const std::string& path, int w, int h, int channels, const std::vector<float>& data) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, data.data()));
    out->close();
}

TEST(EnvironmentImage, LoadsTheSharedEnvironments) {
    for (const char* name : {"studio_small_03_1k.hdr", "venice_sunset_1k.hdr", "empty_warehouse_01_1k.hdr",
                             "royal_esplanade_1k.hdr"}) {
        const std::string path = std::string(FACET_SHARED_DATA_DIR) + "/env/" + name;
        auto env = load_environment(path);
        ASSERT_TRUE(env) << env.error().message;
        EXPECT_EQ(env->width, 1024u) << name;
        EXPECT_EQ(env->height, 512u) << name;
        EXPECT_EQ(env->rgba.size(), 1024u * 512u * 4u);
        EXPECT_EQ(env->sanitized_texels, 0u);
        EXPECT_EQ(env->content_hash.size(), 16u);
        double max_value = 0;
        for (float v : env->rgba) max_value = std::max(max_value, double(v));
        EXPECT_GT(max_value, 1.0) << name << " is high dynamic range";
    }
}

TEST(EnvironmentImage, TinyOddAndGreyInputsLoad) {
    TempDir dir;
    write_float_image(dir.file("one.exr"), 1, 1, 3, {2.0f, 3.0f, 4.0f});
    auto one = load_environment(dir.file("one.exr"));
    ASSERT_TRUE(one) << one.error().message;
    EXPECT_EQ(one->rgba, (std::vector<float>{2.0f, 3.0f, 4.0f, 1.0f}));
    write_float_image(dir.file("wide.exr"), 6, 2, 4, std::vector<float>(6 * 2 * 4, 0.5f));
    auto wide = load_environment(dir.file("wide.exr"));
    ASSERT_TRUE(wide);
    EXPECT_EQ(wide->width, 6u);
    EXPECT_EQ(wide->height, 2u);
    write_float_image(dir.file("grey.exr"), 2, 1, 1, {0.25f, 7.0f});
    auto grey = load_environment(dir.file("grey.exr"));
    ASSERT_TRUE(grey);
    EXPECT_EQ(grey->rgba, (std::vector<float>{0.25f, 0.25f, 0.25f, 1.0f, 7.0f, 7.0f, 7.0f, 1.0f}));
    // The hash follows the content.
    EXPECT_NE(one->content_hash, grey->content_hash);
    EXPECT_EQ(load_environment(dir.file("one.exr"))->content_hash, one->content_hash);
}

TEST(EnvironmentImage, BadTexelsNameTheFileAndTheFirstTexel) {
    TempDir dir;
    std::vector<float> data(4 * 2 * 3, 1.0f);
    data[(1 * 4 + 2) * 3 + 1] = std::numeric_limits<float>::quiet_NaN();  // (2, 1) G
    data[(1 * 4 + 3) * 3 + 0] = -1.0f;
    write_float_image(dir.file("nan.exr"), 4, 2, 3, data);
    auto env = load_environment(dir.file("nan.exr"));
    ASSERT_FALSE(env);
    const std::string& m = env.error().message;
    EXPECT_NE(m.find("nan.exr"), std::string::npos) << m;
    EXPECT_NE(m.find("(2, 1) channel G is NaN"), std::string::npos) << m;

    auto sanitized = load_environment(dir.file("nan.exr"), {true});
    ASSERT_TRUE(sanitized) << sanitized.error().message;
    EXPECT_EQ(sanitized->sanitized_texels, 2u);
    EXPECT_EQ(sanitized->rgba[(1 * 4 + 2) * 4 + 1], 0.0f);
    EXPECT_EQ(sanitized->rgba[(1 * 4 + 3) * 4 + 0], 0.0f);

    data.assign(data.size(), 1.0f);
    data[5] = std::numeric_limits<float>::infinity();
    write_float_image(dir.file("inf.exr"), 4, 2, 3, data);
    auto inf = load_environment(dir.file("inf.exr"));
    ASSERT_FALSE(inf);
    EXPECT_NE(inf.error().message.find("(1, 0) channel B is Inf"), std::string::npos) << inf.error().message;
}

TEST(EnvironmentImage, UnreadableFilesAreClearErrors) {
    TempDir dir;
    auto missing = load_environment(dir.file("missing.hdr"));
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find("missing.hdr: no such file"), std::string::npos);

    std::ofstream(dir.file("text.hdr")) << "this is not an image\n";
    auto text = load_environment(dir.file("text.hdr"));
    ASSERT_FALSE(text);
    EXPECT_NE(text.error().message.find("text.hdr: cannot read the image"), std::string::npos) << text.error().message;

    std::ofstream(dir.file("empty.exr"));
    auto empty = load_environment(dir.file("empty.exr"));
    ASSERT_FALSE(empty);
    EXPECT_NE(empty.error().message.find("empty.exr"), std::string::npos) << empty.error().message;

    // A real HDR cut short.
    const std::string source = std::string(FACET_SHARED_DATA_DIR) + "/env/studio_small_03_1k.hdr";
    std::ifstream in(source, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(dir.file("cut.hdr"), std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 3));
    auto cut = load_environment(dir.file("cut.hdr"));
    ASSERT_FALSE(cut);
    EXPECT_NE(cut.error().message.find("cut.hdr"), std::string::npos) << cut.error().message;

    write_float_image(dir.file("two.exr"), 2, 2, 2, std::vector<float>(8, 1.0f));
    auto two = load_environment(dir.file("two.exr"));
    ASSERT_FALSE(two);
    EXPECT_NE(two.error().message.find("2 channels"), std::string::npos) << two.error().message;

    auto directory = load_environment(dir.path.string());
    ASSERT_FALSE(directory);
    EXPECT_NE(directory.error().message.find("directory"), std::string::npos);
}

}  // namespace
}  // namespace facet
