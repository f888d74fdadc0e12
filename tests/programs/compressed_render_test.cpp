// facet-render on compressed glTF files (EXT_meshopt_compression, KHR_draco_mesh_compression)
// written by the test: the frame matches the same mesh uncompressed (exactly for meshopt,
// which is lossless; within Draco's quantisation otherwise), a used-but-unknown extension
// is a warning on stderr and in NAME.json, and a corrupt stream is one error, no files.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "support/compressed_gltf.h"
#include "support/process.h"

namespace {

namespace fs = std::filesystem;
using facet::test::Ran;

struct TempDir {
    fs::path path = fs::temp_directory_path() / ("facet_compressed_render_" + std::to_string(::getpid()) + "_" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

// Lit by one light from the front, no environment: quick on lavapipe.
Ran render(const std::string& model, const std::string& out) {
    return facet::test::run_command(std::string(FACET_RENDER_PATH) + " --model " + model + " --out " + out +
                                    " --env none --no-skybox --light 'directional dir=-0.3,-0.4,-1 intensity=3'"
                                    " --width 96 --height 72");
}

std::vector<float> read_pixels(const std::string& path) {
    std::vector<float> values;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return values;
    const OIIO::ImageSpec& spec = in->spec();
    values.resize(size_t(spec.width) * spec.height * spec.nchannels);
    in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, values.data());
    return values;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

struct Frames {
    std::vector<float> plain, compressed;
};

Frames render_both(const TempDir& dir, const std::string& compressed_name) {
    Frames f;
    const Ran plain = render(dir / "plain.gltf", dir / "plain.exr");
    EXPECT_EQ(plain.status, 0) << plain.output;
    const Ran compressed = render(dir / compressed_name, dir / "compressed.exr");
    EXPECT_EQ(compressed.status, 0) << compressed.output;
    EXPECT_EQ(compressed.output.find("Validation"), std::string::npos) << compressed.output;
    f.plain = read_pixels(dir / "plain.exr");
    f.compressed = read_pixels(dir / "compressed.exr");
    EXPECT_EQ(f.plain.size(), size_t(96 * 72 * 4));
    EXPECT_EQ(f.plain.size(), f.compressed.size());
    // The mesh fills most of the frame: a blank image cannot pass.
    size_t covered = 0;
    for (size_t i = 3; i < f.plain.size(); i += 4) covered += f.plain[i] > 0.5f;
    EXPECT_GT(covered, f.plain.size() / 4 / 4) << "the plain mesh covers too little of the frame";
    return f;
}

TEST(CompressedRender, MeshoptFrameIsThePlainFrame) {
    TempDir dir;
    const facet::test::TestGeometry g = facet::test::wavy_grid(30, 20);
    facet::test::write_plain_gltf(dir / "plain.gltf", g);
    facet::test::write_meshopt_gltf(dir / "meshopt.glb", g);
    const Frames f = render_both(dir, "meshopt.glb");
    // Lossless decoding, the same vertices: the same pixels up to float rounding. The
    // codec starts triangles at another corner, which changes the order in which the
    // rasteriser sums each attribute's barycentric terms, so not bit for bit.
    double worst = 0;
    for (size_t i = 0; i < f.plain.size() && i < f.compressed.size(); ++i)
        worst = std::max(worst, std::abs(double(f.plain[i]) - f.compressed[i]) / std::max(1e-3, double(std::abs(f.plain[i]))));
    std::printf("worst relative difference %.3g\n", worst);
    EXPECT_LT(worst, 1e-4);
}

TEST(CompressedRender, DracoFrameIsThePlainFrameWithinQuantisation) {
    TempDir dir;
    const facet::test::TestGeometry g = facet::test::wavy_grid(30, 20);
    facet::test::write_plain_gltf(dir / "plain.gltf", g);
    facet::test::write_draco_gltf(dir / "draco.gltf", g);
    const Frames f = render_both(dir, "draco.gltf");
    // 14-bit positions and 10-bit normals: the shading moves by about 1e-3 of its value
    // and only edge pixels change coverage. Bound the mean difference at 1% of the mean.
    double difference = 0, total = 0;
    for (size_t i = 0; i < f.plain.size() && i < f.compressed.size(); ++i) {
        if (i % 4 == 3) continue;
        difference += std::abs(double(f.plain[i]) - f.compressed[i]);
        total += std::abs(double(f.plain[i]));
    }
    ASSERT_GT(total, 0.0);
    EXPECT_LT(difference / total, 0.01);
}

TEST(CompressedRender, UnknownUsedExtensionIsAWarningInTheLogAndJson) {
    TempDir dir;
    facet::test::write_meshopt_gltf(dir / "mesh.gltf", facet::test::wavy_grid(4, 4));
    std::string json = read_text(dir / "mesh.gltf");
    const std::string used = "\"extensionsUsed\": [\"EXT_meshopt_compression\"";
    ASSERT_NE(json.find(used), std::string::npos);
    json.replace(json.find(used), used.size(), used + ", \"KHR_made_up_glass\"");
    facet::test::write_bytes(dir / "mesh.gltf", json.data(), json.size());
    const Ran r = render(dir / "mesh.gltf", dir / "out.png");
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string warning = "extension KHR_made_up_glass is used by the file but not implemented: ignored";
    EXPECT_NE(r.output.find("facet-render: warning: " + warning), std::string::npos) << r.output;
    const std::string out_json = read_text(dir / "out.json");
    const size_t list = out_json.find("\"warnings\": [");
    ASSERT_NE(list, std::string::npos) << out_json;
    EXPECT_EQ(out_json.find("\"" + warning + "\"", list), out_json.find("\"" + warning + "\"")) << out_json;
    EXPECT_NE(out_json.find("\"" + warning + "\""), std::string::npos) << out_json;
}

TEST(CompressedRender, CorruptDracoStreamIsOneErrorAndNoFiles) {
    TempDir dir;
    facet::test::write_draco_gltf(dir / "mesh.gltf", facet::test::wavy_grid(4, 4));
    std::string bin = read_text(dir / "mesh.bin");
    bin.replace(0, 5, "NOPE!");
    facet::test::write_bytes(dir / "mesh.bin", bin.data(), bin.size());
    const Ran r = render(dir / "mesh.gltf", dir / "out.png");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find(dir / "mesh.gltf" + ": mesh 0 primitive 0 (KHR_draco_mesh_compression): the compressed "
                                                "stream does not decode"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    EXPECT_FALSE(fs::exists(dir / "out.json"));
}

}  // namespace
