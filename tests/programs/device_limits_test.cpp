// Sizes asked for on the command line against what the device holds: cube faces, LUTs,
// frames and environments too large are refused with one clear message naming the
// image and the limit, before anything is created, instead of a validation error or an
// allocation of gigabytes. Unit checks with made-up limits, then the programs.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include <facet/gpu/device_limits.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/render/frame_budget.h>
#include "support/gpu_test.h"
#include "support/process.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

DeviceLimits small_device() {
    DeviceLimits l;
    l.device_name = "a small GPU";
    l.max_image_2d = 4096;
    l.max_image_cube = 2048;
    l.max_framebuffer = 4096;
    l.max_allocation_bytes = uint64_t(256) << 20;
    l.heap_bytes = uint64_t(512) << 20;
    l.sample_counts = VK_SAMPLE_COUNT_1_BIT | VK_SAMPLE_COUNT_4_BIT;
    return l;
}

ImageDesc desc(uint32_t w, uint32_t h, bool cube = false, uint32_t mips = 1) {
    ImageDesc d;
    d.width = w;
    d.height = h;
    d.cube = cube;
    d.array_layers = cube ? 6 : 1;
    d.mip_levels = mips;
    return d;
}

TEST(DeviceLimits, ImageBytesCountEveryLevelLayerAndSample) {
    EXPECT_EQ(image_bytes(desc(4, 2)), 4u * 2 * 16);
    EXPECT_EQ(image_bytes(desc(4, 4, true, 3)), (16u + 4 + 1) * 6 * 16);
    ImageDesc msaa = desc(8, 8);
    msaa.samples = VK_SAMPLE_COUNT_4_BIT;
    msaa.format = VK_FORMAT_D32_SFLOAT;
    EXPECT_EQ(image_bytes(msaa), 8u * 8 * 4 * 4);
    EXPECT_EQ(format_bytes(uint64_t(3) << 29), "1.5 GiB");
    EXPECT_EQ(format_bytes(uint64_t(12) << 20), "12 MiB");
}

TEST(DeviceLimits, EachLimitIsNamed) {
    const DeviceLimits l = small_device();
    EXPECT_TRUE(check_images_fit(l, {{"a", desc(4096, 2048)}}));
    auto message = [&](const std::vector<NamedImage>& images, uint64_t buffers = 0) {
        Status s = check_images_fit(l, images, buffers);
        return s ? std::string("fits") : s.error().message;
    };
    EXPECT_EQ(message({{"the cube", desc(4096, 4096, true)}}),
              "the cube (4096x4096 cube) is larger than the device allows on a small GPU: maxImageDimensionCube is 2048");
    EXPECT_EQ(message({{"the map", desc(8192, 4096)}}),
              "the map (8192x4096) is larger than the device allows on a small GPU: maxImageDimension2D is 4096");
    EXPECT_EQ(message({{"the LUT", desc(4096, 4096, false, 13)}}),
              "the LUT (4096x4096, 13 mips) needs 341 MiB, more than one allocation may hold on a small GPU "
              "(maxMemoryAllocationSize 256 MiB)");
    EXPECT_EQ(message({{"one", desc(2048, 2048)}, {"two", desc(2048, 4096)}}, uint64_t(1) << 20), "fits");
    std::vector<NamedImage> many(8, {"tile", desc(2048, 2048)});
    EXPECT_EQ(message(many), "fits") << "exactly the heap";
    many.push_back({"one more", desc(16, 16)});
    EXPECT_EQ(message(many), "the images need 512 MiB of GPU memory together (the largest, tile, 2048x2048: 64 MiB), "
                             "more than the device's largest memory heap on a small GPU (512 MiB)");
    ImageDesc eight = desc(64, 64);
    eight.samples = VK_SAMPLE_COUNT_8_BIT;
    EXPECT_EQ(message({{"MSAA colour", eight, true}}),
              "MSAA colour (64x64, 8 samples): the device does not render 8 samples on a small GPU (it offers 1, 4)");
    DeviceLimits narrow = l;
    narrow.max_framebuffer = 1024;
    Status target = check_images_fit(narrow, {{"the frame", desc(2048, 16), true}});
    ASSERT_FALSE(target);
    EXPECT_EQ(target.error().message, "the frame (2048x16) is larger than a framebuffer may be on a small GPU (1024)");
}

TEST(DeviceLimits, FrameTargetsFollowTheSettings) {
    FrameSettings s;
    s.width = 100;
    s.height = 50;
    s.samples = 4;
    s.skybox = true;
    s.views = {View::normal, View::D};
    const std::vector<NamedImage> images = frame_target_images(s);
    uint64_t total = 0;
    for (const NamedImage& i : images) total += image_bytes(i.desc);
    // HDR 16 + MSAA colour 64 + depth 16 + display 4 + composite 16 + 2 views x (16 + 4) bytes a pixel.
    EXPECT_EQ(total, uint64_t(100) * 50 * (16 + 64 + 16 + 4 + 16 + 2 * 20));
}

class DeviceLimitsGpu : public test::GpuTest {};

// The render graph's own check, behind every program: a transient image the device
// cannot hold stops the run before anything is allocated.
TEST_F(DeviceLimitsGpu, AGraphTooLargeForTheDeviceStopsBeforeAllocating) {
    const DeviceLimits l = device_limits(ctx());
    EXPECT_GE(l.max_image_2d, 4096u);
    EXPECT_GT(l.max_allocation_bytes, 0u);
    EXPECT_GT(l.heap_bytes, 0u);
    CompiledGraph compiled;
    PhysicalResource huge;
    huge.name = "huge target";
    huge.image_desc = desc(l.max_image_2d + 1, 4);
    huge.image_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    compiled.physical_images.push_back(huge);
    Status fits = check_graph_fits(ctx(), compiled);
    ASSERT_FALSE(fits);
    EXPECT_NE(fits.error().message.find("huge target (" + std::to_string(l.max_image_2d + 1) +
                                        "x4) is larger than the device allows"),
              std::string::npos)
        << fits.error().message;
    GraphRun run(ctx(), compiled);
    Status prepared = Ok{};
    EXPECT_NO_THROW(prepared = run.prepare());
    ASSERT_FALSE(prepared.ok()) << "GraphRun allocated an image larger than the device allows";
    EXPECT_NE(prepared.error().message.find("render graph: huge target"), std::string::npos)
        << prepared.error().message;
}

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_device_limits_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

TEST(DeviceLimitsPrograms, OversizedCubesAndFramesFailBeforeAnythingIsCreated) {
    TempDir dir;
    const std::string bake_out = dir.file("bake");
    test::Ran bake = test::run_command(std::string(FACET_BAKE_PATH) + " builtin:white --width 64 --size 8192 --out " +
                                       bake_out);
    EXPECT_EQ(bake.status, 1) << bake.output;
    EXPECT_NE(bake.output.find("facet-bake: error: image-based lighting: the environment cube (faces of 8192)"),
              std::string::npos)
        << bake.output;
    EXPECT_NE(bake.output.find("(--size, --irradiance-size and --lut-size set these)"), std::string::npos);
    EXPECT_EQ(bake.output.find("VUID"), std::string::npos) << "no validation error";
    EXPECT_FALSE(fs::exists(bake_out)) << "nothing written";

    const std::string render_out = dir.file("frame.png");
    test::Ran render = test::run_command(std::string(FACET_RENDER_PATH) +
                                         " --model builtin:sphere --env builtin:white --env-width 64 --width 16384"
                                         " --height 16384 --samples 4 --out " + render_out);
    EXPECT_EQ(render.status, 1) << render.output;
    EXPECT_NE(render.output.find("facet-render: error: a 16384x16384 frame with 4 samples and 0 views does not fit: "),
              std::string::npos)
        << render.output;
    EXPECT_EQ(render.output.find("VUID"), std::string::npos) << "no validation error";
    EXPECT_FALSE(fs::exists(render_out));

    test::Ran ibl = test::run_command(std::string(FACET_RENDER_PATH) +
                                      " --model builtin:sphere --env builtin:white --env-width 64 --ibl-size 8192"
                                      " --width 32 --height 32 --out " + render_out);
    EXPECT_EQ(ibl.status, 1) << ibl.output;
    EXPECT_NE(ibl.output.find("facet-render: error: image-based lighting: "), std::string::npos) << ibl.output;
    EXPECT_FALSE(fs::exists(render_out));
}

// An MSAA count the device does not offer is an error, not a validation message.
TEST(DeviceLimitsPrograms, UnsupportedSampleCountsAreRefused) {
    const DeviceLimits l = device_limits(test::gpu());
    uint32_t unsupported = 0;
    for (uint32_t n : {2u, 8u})
        if (!(l.sample_counts & n)) unsupported = n;
    if (!unsupported) GTEST_SKIP() << l.device_name << " renders 2 and 8 samples";
    TempDir dir;
    test::Ran r = test::run_command(std::string(FACET_RENDER_PATH) +
                                    " --model builtin:sphere --env none --width 32 --height 32 --samples " +
                                    std::to_string(unsupported) + " --out " + dir.file("a.png"));
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("the device does not render " + std::to_string(unsupported) + " samples"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("VUID"), std::string::npos) << "no validation error";
    EXPECT_FALSE(fs::exists(dir.file("a.png")));
}

TEST(DeviceLimitsPrograms, BuiltInEnvironmentsStayWithinTheEnvironmentWidth) {
    test::Ran bake = test::run_command(std::string(FACET_BAKE_PATH) + " builtin:sky --width 8192 --out /nonexistent");
    EXPECT_EQ(bake.status, 2) << bake.output;
    EXPECT_NE(bake.output.find("--width 8192 is above --max-env-width 4096"), std::string::npos) << bake.output;
    test::Ran render = test::run_command(std::string(FACET_RENDER_PATH) + " --env-width 8192 --out /nonexistent.png");
    EXPECT_EQ(render.status, 2) << render.output;
    EXPECT_NE(render.output.find("--env-width 8192 is above --max-env-width 4096"), std::string::npos) << render.output;
    test::Ran zero = test::run_command(std::string(FACET_RENDER_PATH) + " --max-env-width 0 --out /nonexistent.png");
    EXPECT_EQ(zero.status, 2) << zero.output;
    EXPECT_NE(zero.output.find("--max-env-width"), std::string::npos) << zero.output;
}

}  // namespace
}  // namespace facet
