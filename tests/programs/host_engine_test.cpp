// examples/host_engine, the proof of the embedding API: a program with its own instance,
// device, queue, images and matrices renders DamagedHelmet with two frames in flight under
// the validation layer with synchronization validation. It must report no validation
// message (object tracking included: every Facet object destroyed before the host's
// device), no device allocation or image after the first frame of each slot, and an image
// equal to facet-render's for the same camera within 1/255 on 99.9% of the values.
#include <gtest/gtest.h>

#include "support/output_files.h"
#include "support/process.h"

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace {

namespace fs = std::filesystem;

std::vector<unsigned char> pixels(const fs::path& path, int* width = nullptr) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    if (width) *width = spec.width;
    std::vector<unsigned char> p(size_t(spec.width) * spec.height * spec.nchannels);
    in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, p.data());
    return p;
}

}  // namespace

TEST(HostEngine, RendersLikeFacetRenderWithNoValidationMessageAndNoSteadyAllocation) {
    facet::test::TempDir dir("host_engine");
    const std::string model = std::string(FACET_SHARED_DATA_DIR) + "/models/DamagedHelmet.glb";
    const std::string env = std::string(FACET_SHARED_DATA_DIR) + "/env/venice_sunset_1k.hdr";
    const facet::test::Ran host = facet::test::run_command(
        std::string(FACET_HOST_ENGINE_PATH) + " --validation --model " + model + " --env " + env +
        " --width 320 --height 240 --frames 5 --bake-dir " + (dir / "bake").string() + " --out " +
        (dir / "host.png").string());
    ASSERT_EQ(host.status, 0) << host.output;
    EXPECT_NE(host.output.find("device allocations after the first 2 frames: 0, images: 0"), std::string::npos)
        << host.output;
    EXPECT_NE(host.output.find("host_engine: 0 validation messages"), std::string::npos) << host.output;
    EXPECT_EQ(host.output.find("Validation"), std::string::npos) << host.output;
    EXPECT_TRUE(fs::exists(dir / "bake" / "bake.json"));

    // The host engine shades with the plain split sum (the method is the engine's to pick).
    const facet::test::Ran render = facet::test::run_command(
        std::string(FACET_RENDER_PATH) + " --no-bake-cache --model " + model + " --env " + env +
        " --camera orbit:0,0,3 --target 0,0,0 --fov 45 --width 320 --height 240 --shading split-sum --out " +
        (dir / "render.png").string());
    ASSERT_EQ(render.status, 0) << render.output;

    int width = 0;
    const auto a = pixels(dir / "host.png", &width), b = pixels(dir / "render.png");
    ASSERT_EQ(width, 320);
    ASSERT_EQ(a.size(), b.size());
    size_t off = 0, max_diff = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const size_t d = size_t(std::abs(int(a[i]) - int(b[i])));
        off += d > 1;
        max_diff = std::max(max_diff, d);
    }
    const double fraction = double(off) / double(a.size());
    std::printf("host_engine vs facet-render: %.4f%% of values differ by more than 1/255 (largest %zu/255)\n",
                100.0 * fraction, max_diff);
    EXPECT_LE(fraction, 0.001);
}
