// The pieces large inputs rely on, without a GPU: the box downsampler (exact boxes for
// integer ratios, fractional edges otherwise, the mean kept: uniformly for textures and
// by solid angle for equirectangular maps), fitting a size inside a limit, and reading a
// PNG's or JPEG's declared size from its header alone.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "io/box_downsample.h"
#include "io/image_header.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

std::vector<double> downsample(const std::vector<float>& src, uint32_t sw, uint32_t sh, uint32_t dw, uint32_t dh,
                               uint32_t channels, RowWeights weights) {
    std::vector<double> out(size_t(dw) * dh * channels, -1.0);
    std::vector<uint32_t> order;
    BoxDownsampler box(sw, sh, dw, dh, channels, weights, [&](uint32_t row, const double* values) {
        order.push_back(row);
        std::copy(values, values + size_t(dw) * channels, out.begin() + long(size_t(row) * dw * channels));
    });
    for (uint32_t y = 0; y < sh; ++y) box.add_row(&src[size_t(y) * sw * channels]);
    EXPECT_EQ(order.size(), dh);
    for (uint32_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i) << "rows are emitted once, in order";
    return out;
}

std::vector<float> pattern(uint32_t w, uint32_t h, uint32_t channels) {
    std::vector<float> v(size_t(w) * h * channels);
    for (size_t i = 0; i < v.size(); ++i) v[i] = float((i * 2654435761u) % 1000) / 10.0f;
    return v;
}

TEST(BoxDownsampler, AnIntegerRatioIsThePlainBox) {
    const uint32_t w = 12, h = 8, f = 4;
    const std::vector<float> src = pattern(w, h, 2);
    const std::vector<double> out = downsample(src, w, h, w / f, h / f, 2, RowWeights::uniform);
    for (uint32_t y = 0; y < h / f; ++y)
        for (uint32_t x = 0; x < w / f; ++x)
            for (uint32_t c = 0; c < 2; ++c) {
                double sum = 0;
                for (uint32_t j = 0; j < f; ++j)
                    for (uint32_t i = 0; i < f; ++i) sum += src[((y * f + j) * w + x * f + i) * 2 + c];
                EXPECT_NEAR(out[(y * (w / f) + x) * 2 + c], sum / (f * f), 1e-9);
            }
}

TEST(BoxDownsampler, FractionalRatiosKeepTheMean) {
    const uint32_t w = 37, h = 23;
    const std::vector<float> src = pattern(w, h, 1);
    double src_mean = 0;
    for (float v : src) src_mean += v;
    src_mean /= src.size();
    for (auto [dw, dh] : {std::pair{5u, 3u}, {36u, 22u}, {1u, 1u}, {37u, 7u}, {10u, 23u}}) {
        const std::vector<double> out = downsample(src, w, h, dw, dh, 1, RowWeights::uniform);
        // Output texels cover equal areas, so their plain mean is the source's.
        double mean = 0;
        for (double v : out) mean += v;
        EXPECT_NEAR(mean / out.size(), src_mean, 1e-9) << dw << "x" << dh;
    }
}

TEST(BoxDownsampler, EquirectangularRowsKeepTheSolidAngleMean) {
    const uint32_t w = 40, h = 30;
    const std::vector<float> src = pattern(w, h, 1);
    auto sphere_mean = [](const auto& values, uint32_t width, uint32_t height) {
        double sum = 0;
        for (uint32_t y = 0; y < height; ++y) {
            const double band = (std::cos(std::numbers::pi * y / height) - std::cos(std::numbers::pi * (y + 1) / height)) / 2;
            for (uint32_t x = 0; x < width; ++x) sum += band * values[size_t(y) * width + x] / width;
        }
        return sum;
    };
    for (auto [dw, dh] : {std::pair{20u, 15u}, {8u, 4u}, {7u, 11u}, {1u, 1u}}) {
        const std::vector<double> out = downsample(src, w, h, dw, dh, 1, RowWeights::equirect_solid_angle);
        EXPECT_NEAR(sphere_mean(out, dw, dh), sphere_mean(src, w, h), 1e-9) << dw << "x" << dh;
    }
    // A constant map stays constant, poles included.
    const std::vector<double> flat = downsample(std::vector<float>(w * h, 3.0f), w, h, 9, 7, 1,
                                                RowWeights::equirect_solid_angle);
    for (double v : flat) EXPECT_NEAR(v, 3.0, 1e-12);
}

TEST(BoxDownsampler, FitWithinKeepsTheAspect) {
    auto fit = [](uint32_t w, uint32_t h, uint32_t mw, uint32_t mh) {
        const Size2 s = fit_within(w, h, mw, mh);
        return std::pair{s.width, s.height};
    };
    EXPECT_EQ(fit(16384, 8192, 4096, 2048), (std::pair{4096u, 2048u}));
    EXPECT_EQ(fit(1024, 512, 4096, 2048), (std::pair{1024u, 512u}));
    EXPECT_EQ(fit(8192, 8192, 4096, 2048), (std::pair{2048u, 2048u}));
    EXPECT_EQ(fit(8192, 8192, 4096, 4096), (std::pair{4096u, 4096u}));
    EXPECT_EQ(fit(65536, 2, 4096, 4096), (std::pair{4096u, 1u}));
    EXPECT_EQ(fit(5000, 2500, 4096, 2048), (std::pair{4096u, 2048u}));
}

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_box_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

std::string bytes_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

TEST(ImageHeader, ReadsPngAndJpegSizesWithoutDecoding) {
    TempDir dir;
    struct Case {
        const char* name;
        int w, h, channels;
        OIIO::TypeDesc type;
        const char* attribute;
        uint32_t expected_channels, bytes;
        bool row_by_row;
    };
    const Case cases[] = {
        {"rgb.png", 300, 20, 3, OIIO::TypeDesc::UINT8, nullptr, 3, 1, true},
        {"grey16.png", 7, 5, 1, OIIO::TypeDesc::UINT16, nullptr, 1, 2, true},
        {"rgba.png", 9, 4, 4, OIIO::TypeDesc::UINT8, nullptr, 4, 1, true},
        {"baseline.jpg", 333, 17, 3, OIIO::TypeDesc::UINT8, nullptr, 3, 1, true},
        {"progressive.jpg", 65, 40, 3, OIIO::TypeDesc::UINT8, "jpeg:progressive", 3, 1, false},
        {"grey.jpg", 10, 12, 1, OIIO::TypeDesc::UINT8, nullptr, 1, 1, true},
    };
    for (const Case& c : cases) {
        const std::string path = dir.file(c.name);
        auto out = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(c.w, c.h, c.channels, c.type);
        if (c.attribute) spec.attribute(c.attribute, 1);
        ASSERT_TRUE(out->open(path, spec));
        std::vector<uint16_t> pixels(size_t(c.w) * c.h * c.channels, 100);
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, pixels.data()));
        out->close();
        const std::string bytes = bytes_of(path);
        auto header = read_image_header(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
        ASSERT_TRUE(header) << c.name;
        EXPECT_EQ(header->width, uint32_t(c.w)) << c.name;
        EXPECT_EQ(header->height, uint32_t(c.h)) << c.name;
        EXPECT_EQ(header->channels, c.expected_channels) << c.name;
        EXPECT_EQ(header->bytes_per_channel, c.bytes) << c.name;
        EXPECT_EQ(header->row_by_row, c.row_by_row) << c.name;
    }
    const std::string png = bytes_of(dir.file("rgb.png"));
    for (size_t cut : {size_t(0), size_t(7), size_t(20), size_t(32)})
        EXPECT_FALSE(read_image_header(reinterpret_cast<const uint8_t*>(png.data()), cut)) << cut << " bytes";
    const std::string jpeg = bytes_of(dir.file("baseline.jpg"));
    EXPECT_FALSE(read_image_header(reinterpret_cast<const uint8_t*>(jpeg.data()), 40)) << "cut before its frame";
    const std::string text = "GIF89a and so on";
    EXPECT_FALSE(read_image_header(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

}  // namespace
}  // namespace facet
