// BakedEnvironment: what a bake owns, save -> load giving back the same texels exactly and
// the metadata load needs, and a missing, truncated or mismatched file being an error that
// names it. Also the rules of ibl/bake_rules.h and the JSON reader load() relies on.
#include <gtest/gtest.h>


#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <sstream>

#include <facet/render/specular_lobes.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/ibl/bake_rules.h>
#include <facet/ibl/baked_environment.h>
#include <facet/ibl/method_domain.h>
#include <facet/ibl/procedural_sky.h>
#include <facet/reference/ibl_reference.h>
#include <facet/shader/program_cache.h>
#include "io/json_reader.h"
#include "support/gpu_test.h"
#include "support/output_files.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

std::vector<std::vector<std::byte>> bytes_of(Context& context, const Image& image) {
    std::vector<std::vector<std::byte>> out;
    for (uint32_t m = 0; m < image.desc().mip_levels; ++m)
        for (uint32_t layer = 0; layer < image.desc().array_layers; ++layer)
            out.push_back(test::must(read_image(context, image, m, layer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)));
    return out;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

EnvironmentSource sun_source(uint32_t w, double sun, double diameter_deg = 6.0) {
    const test::Equirect sky = test::sun_sky(w, w / 2, sun, diameter_deg, 40.0, 20.0);
    EnvironmentSource s;
    s.name = "sun sky";
    s.image.rgba = sky.rgba;
    s.image.width = s.width = s.image.source_width = s.source_width = sky.w;
    s.image.height = s.height = s.image.source_height = s.source_height = sky.h;
    s.content_hash = "sun" + std::to_string(sun);
    return s;
}

BakeSettings small_settings() {
    BakeSettings b;
    b.ibl.irradiance.size = 8;
    b.ibl.specular.sample_count = 64;
    b.ibl.lut.size = 16;
    b.ibl.lut.sample_count = 32;
    return b;
}

class BakedEnvironmentTest : public test::GpuTest {
protected:
    Result<BakedEnvironment> bake(const EnvironmentSource& source, const BakeSettings& settings) {
        ShaderCompiler compiler;
        ProgramCache programs(ctx(), compiler);
        return bake_environment(ctx(), programs, source, settings);
    }
    void expect_same(const BakedEnvironment& a, const BakedEnvironment& b) {
        auto same = [&](const Image* x, const Image* y, const char* what) {
            ASSERT_EQ(x == nullptr, y == nullptr) << what;
            if (!x) return;
            EXPECT_EQ(x->desc(), y->desc()) << what;
            EXPECT_TRUE(bytes_of(ctx(), *x) == bytes_of(ctx(), *y)) << what << ": texels differ";
        };
        same(&a.environment(), &b.environment(), "environment");
        same(&a.cube(), &b.cube(), "cube");
        same(a.specular(), b.specular(), "specular");
        same(a.irradiance(), b.irradiance(), "irradiance");
        same(a.lut(), b.lut(), "lut");
        const BakeMetadata &m = a.metadata(), &n = b.metadata();
        EXPECT_EQ(m.bake_key, n.bake_key);
        EXPECT_EQ(m.content_hash, n.content_hash);
        EXPECT_EQ(m.roughness, n.roughness);
        EXPECT_EQ(m.light_split_level, n.light_split_level);
        EXPECT_EQ(m.settings.specular.levels, n.settings.specular.levels);
        EXPECT_EQ(m.settings.irradiance.method, n.settings.irradiance.method);
        EXPECT_EQ(m.warnings, n.warnings);
        ASSERT_EQ(a.lights().size(), b.lights().size());
        for (size_t i = 0; i < a.lights().size(); ++i) {
            EXPECT_EQ(a.lights()[i].direction, b.lights()[i].direction);
            EXPECT_EQ(a.lights()[i].radiance, b.lights()[i].radiance);
            EXPECT_EQ(a.lights()[i].angular_radius, b.lights()[i].angular_radius);
        }
        for (size_t i = 0; i < a.sh9().size(); i += 4)
            for (size_t c = 0; c < 3 && i / 4 < 9; ++c) EXPECT_EQ(a.sh9()[i + c], b.sh9()[i + c]);
        if (!a.sh9().empty()) EXPECT_EQ(a.sh9()[36], b.sh9()[36]);
    }
};

TEST_F(BakedEnvironmentTest, SaveThenLoadGivesTheSameTexelsWithExtractedLights) {
    BakeSettings settings = small_settings();
    settings.extract_lights = true;
    settings.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    auto baked = bake(sun_source(256, 1e4, 3.0), settings);
    ASSERT_TRUE(baked) << baked.error().message;
    ASSERT_EQ(baked->lights().size(), 1u) << "the sun is extracted";
    const uint32_t levels = baked->metadata().settings.specular.levels;
    EXPECT_EQ(baked->metadata().light_split_level, light_split_level(baked->lights(), levels));
    EXPECT_GT(baked->metadata().light_split_level, 0u);
    EXPECT_EQ(baked->metadata().roughness.size(), levels);
    EXPECT_FALSE(baked->metadata().timings.empty());
    test::TempDir dir("baked_environment_lights");
    ASSERT_TRUE(baked->save(dir.path.string()));
    for (const char* name : baked_environment_files()) EXPECT_TRUE(fs::exists(dir / name)) << name;
    auto loaded = BakedEnvironment::load(ctx(), dir.path.string());
    ASSERT_TRUE(loaded) << loaded.error().message;
    expect_same(*baked, *loaded);
    auto key = saved_bake_key(dir.path.string());
    ASSERT_TRUE(key) << key.error().message;
    EXPECT_EQ(*key, baked->metadata().bake_key);
    EXPECT_FALSE(saved_bake_key((dir / "nowhere").string()));
    // The forward pass's inputs from either.
    RenderGraph graph;
    const IblInputs in = import_baked_environment(graph, *loaded, 0.5f);
    EXPECT_TRUE(in.cube.valid() && in.specular.valid() && in.irradiance.valid() && in.lut.valid());
    EXPECT_EQ(in.specular_levels, levels);
    EXPECT_EQ(in.intensity, 0.5f);
    EXPECT_NE(in.cube_sampler, VkSampler(VK_NULL_HANDLE));
}

// With lights extracted the irradiance is still the whole environment's (the forward pass
// shades only the disks' specular): texel for texel the bake without extraction's. A bake
// saved before that (its bake.json without lights.irradiance) is refused, naming the key.
TEST_F(BakedEnvironmentTest, IrradianceWithExtractedLightsIsTheWholeEnvironments) {
    BakeSettings settings = small_settings();
    settings.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    const EnvironmentSource sun = sun_source(256, 1e4, 3.0);
    auto whole = bake(sun, settings);
    ASSERT_TRUE(whole) << whole.error().message;
    settings.extract_lights = true;
    auto extracted = bake(sun, settings);
    ASSERT_TRUE(extracted) << extracted.error().message;
    ASSERT_EQ(extracted->lights().size(), 1u) << "the sun is extracted";
    ASSERT_TRUE(whole->irradiance() && extracted->irradiance());
    const auto a = bytes_of(ctx(), *whole->irradiance()), b = bytes_of(ctx(), *extracted->irradiance());
    EXPECT_TRUE(a == b) << "the irradiance with the sun extracted differs from the whole environment's";
    // The specular levels from 1 on do differ: they come from the map without the sun.
    EXPECT_FALSE(bytes_of(ctx(), *whole->specular()) == bytes_of(ctx(), *extracted->specular()));

    test::TempDir dir("baked_environment_old_irradiance");
    ASSERT_TRUE(extracted->save(dir.path.string()));
    std::string json = read_text(dir / "bake.json");
    const size_t at = json.find("\"irradiance\": \"the whole environment");
    ASSERT_NE(at, std::string::npos) << json;
    json.replace(at, 1, "\"former_");
    write_text(dir / "bake.json", json);
    auto old = BakedEnvironment::load(ctx(), dir.path.string());
    ASSERT_FALSE(old) << "a bake whose irradiance lacks the lights was loaded";
    EXPECT_NE(old.error().message.find("lights.irradiance"), std::string::npos) << old.error().message;
    EXPECT_NE(old.error().message.find("bake.json"), std::string::npos) << old.error().message;
}

TEST_F(BakedEnvironmentTest, SpecularLevelZeroIsTheEnvironmentCubesLevelZero) {
    // The pass that makes the cube writes specular level 0 (the mirror) too: the same texels.
    BakeSettings settings = small_settings();
    settings.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    auto baked = bake(sun_source(128, 1e4, 3.0), settings);
    ASSERT_TRUE(baked) << baked.error().message;
    ASSERT_NE(baked->specular(), nullptr);
    for (const auto& t : baked->metadata().timings) EXPECT_NE(t.name, "specular level 0 (copy)") << "no copy pass";
    for (uint32_t layer = 0; layer < 6; ++layer) {
        const auto cube = test::must(read_image(ctx(), baked->cube(), 0, layer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
        const auto mirror =
            test::must(read_image(ctx(), *baked->specular(), 0, layer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
        EXPECT_TRUE(cube == mirror) << "face " << layer;
    }
}

TEST_F(BakedEnvironmentTest, SaveThenLoadGivesTheSameTexelsWithSh9InHalfFloat) {
    BakeSettings settings = small_settings();
    settings.ibl.irradiance.method = IrradianceMethod::sh9;
    auto baked = bake(sun_source(64, 50.0), settings);
    ASSERT_TRUE(baked) << baked.error().message;
    ASSERT_EQ(baked->sh9().size(), 40u);
    EXPECT_EQ(baked->specular()->desc().format, VK_FORMAT_R16G16B16A16_SFLOAT);
    test::TempDir dir("baked_environment_sh9");
    ASSERT_TRUE(baked->save(dir.path.string()));
    EXPECT_TRUE(fs::exists(dir / "sh9.json"));
    auto loaded = BakedEnvironment::load(ctx(), dir.path.string());
    ASSERT_TRUE(loaded) << loaded.error().message;
    expect_same(*baked, *loaded);
    // Saving what was loaded gives the same KTX2 files, byte for byte.
    test::TempDir again("baked_environment_sh9_again");
    ASSERT_TRUE(loaded->save(again.path.string()));
    for (const char* name : {"specular.ktx2", "irradiance.ktx2", "brdf_lut.ktx2", "environment.ktx2", "sh9.json"})
        EXPECT_EQ(read_text(dir / name), read_text(again / name)) << name;
}

// The BRDF LUT kept across bakes (BakeSettings::lut_cache): the first bake computes it and
// keeps it, a bake of another environment uploads it instead of computing it, with the
// same texels; a damaged entry is said, removed and the LUT computed again.
TEST_F(BakedEnvironmentTest, LutCacheKeepsTheLutAcrossEnvironments) {
    const fs::path dir = fs::temp_directory_path() / ("facet_lut_cache_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    BakeSettings settings = small_settings();
    settings.lut_cache.directory = dir.string();
    auto bake_with_lines = [&](const EnvironmentSource& source, std::string& lines) {
        ShaderCompiler compiler;
        ProgramCache programs(ctx(), compiler);
        BakeCallbacks cb;
        cb.progress = [&](const std::string& line) { lines += line + "\n"; };
        return bake_environment(ctx(), programs, source, settings, cb);
    };
    auto has_pass = [](const BakedEnvironment& b, const std::string& name) {
        for (const PassTiming& t : b.metadata().timings)
            if (t.name == name) return true;
        return false;
    };
    std::string lines;
    auto first = bake_with_lines(sun_source(64, 50.0), lines);
    ASSERT_TRUE(first) << first.error().message;
    EXPECT_TRUE(has_pass(*first, "brdf lut"));
    EXPECT_FALSE(has_pass(*first, "upload brdf lut (cached)"));
    // Another environment: the LUT comes from the cache, texel for texel the one computed.
    lines.clear();
    auto second = bake_with_lines(sun_source(64, 500.0), lines);
    ASSERT_TRUE(second) << second.error().message;
    EXPECT_TRUE(has_pass(*second, "upload brdf lut (cached)")) << lines;
    EXPECT_FALSE(has_pass(*second, "brdf lut"));
    EXPECT_NE(lines.find("BRDF LUT from the cache"), std::string::npos) << lines;
    ASSERT_TRUE(first->lut() && second->lut());
    EXPECT_TRUE(bytes_of(ctx(), *first->lut()) == bytes_of(ctx(), *second->lut()));
    // Another model or size is another entry.
    settings.ibl.lut.brdf = BrdfModel::thesis;
    auto thesis = bake_with_lines(sun_source(64, 50.0), lines);
    ASSERT_TRUE(thesis) << thesis.error().message;
    EXPECT_TRUE(has_pass(*thesis, "brdf lut"));
    settings.ibl.lut.brdf = BrdfModel::gltf;
    // A damaged entry: said, removed, computed again (the same texels), and kept again.
    size_t damaged = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.path().filename() == "brdf_lut.rgba32f" && e.path().string().find("-gltf-") != std::string::npos) {
            std::fstream f(e.path(), std::ios::in | std::ios::out | std::ios::binary);
            f.seekp(100);
            f.put(char(0x7f));
            ++damaged;
        }
    ASSERT_EQ(damaged, 1u);
    lines.clear();
    auto third = bake_with_lines(sun_source(64, 50.0), lines);
    ASSERT_TRUE(third) << third.error().message;
    EXPECT_NE(lines.find("contents differ from the manifest"), std::string::npos) << lines;
    EXPECT_TRUE(has_pass(*third, "brdf lut"));
    EXPECT_TRUE(bytes_of(ctx(), *first->lut()) == bytes_of(ctx(), *third->lut()));
    lines.clear();
    auto fourth = bake_with_lines(sun_source(64, 50.0), lines);
    ASSERT_TRUE(fourth) << fourth.error().message;
    EXPECT_TRUE(has_pass(*fourth, "upload brdf lut (cached)")) << lines;
    fs::remove_all(dir);
}

TEST_F(BakedEnvironmentTest, MissingTruncatedOrMismatchedFilesAreErrorsNamingThem) {
    auto baked = bake(sun_source(64, 50.0), small_settings());
    ASSERT_TRUE(baked) << baked.error().message;
    test::TempDir dir("baked_environment_damage");
    const std::string saved = (dir / "saved").string();
    ASSERT_TRUE(baked->save(saved));
    auto fresh = [&](const char* name) {
        const fs::path copy = dir / name;
        fs::remove_all(copy);
        fs::copy(saved, copy);
        return copy;
    };
    auto expect_error = [&](const fs::path& d, const std::string& file, const std::string& reason) {
        auto loaded = BakedEnvironment::load(ctx(), d.string());
        ASSERT_FALSE(loaded) << file;
        EXPECT_NE(loaded.error().message.find((d / file).string()), std::string::npos) << loaded.error().message;
        EXPECT_NE(loaded.error().message.find(reason), std::string::npos) << loaded.error().message;
    };
    ASSERT_TRUE(BakedEnvironment::load(ctx(), saved));
    for (const char* file : {"specular.ktx2", "irradiance.ktx2", "brdf_lut.ktx2", "environment.ktx2",
                             "environment.exr", "bake.json"}) {
        const fs::path d = fresh("missing");
        fs::remove(d / file);
        auto loaded = BakedEnvironment::load(ctx(), d.string());
        ASSERT_FALSE(loaded) << file;
        EXPECT_NE(loaded.error().message.find(file), std::string::npos) << loaded.error().message;
    }
    {
        const fs::path d = fresh("truncated");
        fs::resize_file(d / "irradiance.ktx2", fs::file_size(d / "irradiance.ktx2") / 2);
        auto loaded = BakedEnvironment::load(ctx(), d.string());
        ASSERT_FALSE(loaded);
        EXPECT_NE(loaded.error().message.find("irradiance.ktx2"), std::string::npos) << loaded.error().message;
    }
    {
        // bake.json says the specular cube is another size than the file holds.
        const fs::path d = fresh("mismatched");
        std::string json = read_text(d / "bake.json");
        const std::string entry = "\"file\": \"specular.ktx2\",\n    \"size\": 16";
        const size_t at = json.find(entry);
        ASSERT_NE(at, std::string::npos) << json;
        json.replace(at, entry.size(), "\"file\": \"specular.ktx2\",\n    \"size\": 8");
        write_text(d / "bake.json", json);
        expect_error(d, "specular.ktx2", "size 16, but bake.json says 8");
    }
    {
        // Another format than the one recorded.
        const fs::path d = fresh("format");
        std::string json = read_text(d / "bake.json");
        const std::string entry = "\"file\": \"brdf_lut.ktx2\",\n    \"size\": 16,\n    \"mip_levels\": 1,\n    \"format\": \"R16G16B16A16_SFLOAT\"";
        const size_t at = json.find(entry);
        ASSERT_NE(at, std::string::npos) << json;
        json.replace(at, entry.size(), "\"file\": \"brdf_lut.ktx2\",\n    \"size\": 16,\n    \"mip_levels\": 1,\n    \"format\": \"R32G32B32A32_SFLOAT\"");
        write_text(d / "bake.json", json);
        expect_error(d, "brdf_lut.ktx2", "format R16G16B16A16_SFLOAT, but bake.json says R32G32B32A32_SFLOAT");
    }
    {
        const fs::path d = fresh("corrupt");
        write_text(d / "bake.json", read_text(d / "bake.json").substr(0, 200));
        expect_error(d, "bake.json", "JSON line");
    }
    {
        const fs::path d = fresh("sizes");
        std::string json = read_text(d / "bake.json");
        const size_t at = json.find("\"width\": 64");
        ASSERT_NE(at, std::string::npos);
        json.replace(at, 11, "\"width\": 65");
        write_text(d / "bake.json", json);
        expect_error(d, "environment.exr", "bake.json says 65x32");
    }
}

// The lower-level form: the bake's passes in the caller's graph, writing into the
// caller's own images (here a LUT and a specular cube), texel for texel what
// bake_environment keeps in RGBA32F.
TEST_F(BakedEnvironmentTest, PassesWriteIntoTheCallersImages) {
    const EnvironmentSource source = sun_source(64, 50.0);
    BakeSettings settings = small_settings();
    settings.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    auto baked = bake(source, settings);
    ASSERT_TRUE(baked) << baked.error().message;
    const IblSettings resolved = resolved_ibl_settings(settings.ibl, source);

    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ImageDesc lut_desc;
    lut_desc.width = lut_desc.height = resolved.lut.size;
    ImageDesc spec_desc = baked->specular()->desc();
    spec_desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    Image lut = test::must(Image::create(ctx(), lut_desc, usage, "engine's lut"));
    Image specular = test::must(Image::create(ctx(), spec_desc, usage, "engine's specular"));
    const ResourceState readable{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    ShaderCompiler compiler;
    ProgramCache programs(ctx(), compiler);
    IblBake ibl(ctx(), programs);
    RenderGraph graph;
    IblTargets targets;
    targets.lut = graph.import_image("engine lut", {lut.handle(), lut_desc, {}, readable});
    targets.specular = graph.import_image("engine specular", {specular.handle(), spec_desc, {}, readable});
    auto images = ibl.add_passes(graph, source, resolved, {}, targets);
    ASSERT_TRUE(images) << images.error().message;
    CompiledGraph compiled = graph.compile();
    GraphRun run(ctx(), compiled);
    ASSERT_TRUE(run.submit_and_wait());
    EXPECT_TRUE(bytes_of(ctx(), lut) == bytes_of(ctx(), *baked->lut())) << "LUT";
    EXPECT_TRUE(bytes_of(ctx(), specular) == bytes_of(ctx(), *baked->specular())) << "specular";

    // An image of another size is refused, naming it.
    RenderGraph wrong;
    ImageDesc small = lut_desc;
    small.width = small.height = resolved.lut.size / 2;
    IblTargets bad;
    bad.lut = wrong.import_image("engine lut", {lut.handle(), small, {}, readable});
    auto refused = ibl.add_passes(wrong, source, resolved, {}, bad);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("the caller's brdf lut image is 8x8"), std::string::npos)
        << refused.error().message;
}

// environment.exr and .hdr encoded ahead (BakeSettings::encoded_environment, what
// facet-bake does while the device starts) are the bytes save() would have encoded from
// the baked environment; the bake keeps them only when they are of the texels it bakes.
TEST_F(BakedEnvironmentTest, EnvironmentFilesEncodedAheadAreWrittenOnlyForTheirOwnTexels) {
    const EnvironmentSource source = sun_source(64, 50.0);
    auto encoded = encode_environment_files(source);
    ASSERT_TRUE(encoded) << encoded.error().message;
    EXPECT_TRUE(encoded->previews);
    EXPECT_FALSE(encoded->exr.empty());
    EXPECT_FALSE(encoded->hdr.empty());
    auto plain = bake(source, small_settings());
    ASSERT_TRUE(plain) << plain.error().message;
    test::TempDir reference("encoded_ahead_reference");
    ASSERT_TRUE(plain->save(reference.path.string()));
    // The bytes encoded ahead are those save() encodes from the texels read back.
    EXPECT_EQ(read_text(reference / "environment.exr"), std::string(encoded->exr.begin(), encoded->exr.end()));
    EXPECT_EQ(read_text(reference / "environment.hdr"), std::string(encoded->hdr.begin(), encoded->hdr.end()));

    // Marked bytes show which files were written from what was encoded ahead.
    auto marked = [&](const EncodedEnvironmentFiles& from, const std::string& content_hash) {
        auto files = std::make_shared<EncodedEnvironmentFiles>(from);
        files->content_hash = content_hash;
        files->exr.assign(10, uint8_t('E'));
        files->hdr.assign(10, uint8_t('H'));
        return std::shared_ptr<const EncodedEnvironmentFiles>(files);
    };
    auto save_with = [&](std::shared_ptr<const EncodedEnvironmentFiles> files, const char* name,
                         const BakeSaveOptions& options = {}) {
        BakeSettings settings = small_settings();
        settings.encoded_environment = std::move(files);
        auto baked = bake(source, settings);
        EXPECT_TRUE(baked) << baked.error().message;
        auto dir = std::make_unique<test::TempDir>(name);
        if (baked) EXPECT_TRUE(baked->save(dir->path.string(), options));
        return dir;
    };
    {
        auto dir = save_with(marked(*encoded, source.content_hash), "encoded_ahead_used");
        EXPECT_EQ(read_text(*dir / "environment.exr"), std::string(10, 'E'));
        EXPECT_EQ(read_text(*dir / "environment.hdr"), std::string(10, 'H'));
        for (const char* name : {"specular.ktx2", "irradiance.ktx2", "environment.ktx2", "environment.png"})
            EXPECT_EQ(read_text(*dir / name), read_text(reference / name)) << name;
    }
    {
        // Of other texels: ignored, the environment is read back and encoded as before.
        auto dir = save_with(marked(*encoded, "another input"), "encoded_ahead_other");
        EXPECT_EQ(read_text(*dir / "environment.exr"), read_text(reference / "environment.exr"));
        EXPECT_EQ(read_text(*dir / "environment.hdr"), read_text(reference / "environment.hdr"));
    }
    {
        // Encoded with previews, saved without: the EXR is encoded again, no .hdr written.
        auto dir = save_with(marked(*encoded, source.content_hash), "encoded_ahead_no_previews", BakeSaveOptions{false});
        EXPECT_EQ(read_text(*dir / "environment.exr"), read_text(reference / "environment.exr"));
        EXPECT_FALSE(fs::exists(*dir / "environment.hdr"));
    }
    {
        // With extracted lights the bake's environment is the residual: ignored too.
        const EnvironmentSource lit = sun_source(256, 1e4, 3.0);
        auto lit_encoded = encode_environment_files(lit);
        ASSERT_TRUE(lit_encoded) << lit_encoded.error().message;
        BakeSettings settings = small_settings();
        settings.extract_lights = true;
        auto residual = bake(lit, settings);
        ASSERT_TRUE(residual) << residual.error().message;
        ASSERT_EQ(residual->lights().size(), 1u) << "the sun is extracted";
        test::TempDir residual_reference("encoded_ahead_residual_reference");
        ASSERT_TRUE(residual->save(residual_reference.path.string()));
        settings.encoded_environment = marked(*lit_encoded, lit.content_hash);
        auto with = bake(lit, settings);
        ASSERT_TRUE(with) << with.error().message;
        test::TempDir dir("encoded_ahead_residual");
        ASSERT_TRUE(with->save(dir.path.string()));
        EXPECT_EQ(read_text(dir / "environment.exr"), read_text(residual_reference / "environment.exr"));
    }
    EnvironmentSource sky;
    sky.name = "builtin:sky";
    sky.sky = ProceduralSky{};
    auto none = encode_environment_files(sky);
    ASSERT_FALSE(none);
    EXPECT_NE(none.error().message.find("builtin:sky"), std::string::npos) << none.error().message;

    // On a thread of its own, for texels handed over later: the same bytes; none for no
    // texels, a sky's, or a source that never comes.
    {
        std::promise<std::shared_ptr<const EnvironmentSource>> later;
        EncodedEnvironment pending = encode_environment_files_in_background(later.get_future().share());
        ASSERT_TRUE(pending);
        later.set_value(std::make_shared<const EnvironmentSource>(source));
        auto files = pending.get();
        ASSERT_TRUE(files);
        EXPECT_EQ(files->exr, encoded->exr);
        EXPECT_EQ(files->hdr, encoded->hdr);
        EXPECT_EQ(files->content_hash, source.content_hash);
        BakeSettings settings = small_settings();
        settings.encoded_environment = pending;
        auto baked = bake(source, settings);
        ASSERT_TRUE(baked) << baked.error().message;
        test::TempDir dir("encoded_in_background");
        ASSERT_TRUE(baked->save(dir.path.string()));
        EXPECT_EQ(read_text(dir / "environment.exr"), read_text(reference / "environment.exr"));
        EXPECT_EQ(read_text(dir / "environment.hdr"), read_text(reference / "environment.hdr"));
    }
    for (auto given : {std::shared_ptr<const EnvironmentSource>(), std::make_shared<const EnvironmentSource>(sky)}) {
        std::promise<std::shared_ptr<const EnvironmentSource>> later;
        EncodedEnvironment pending = encode_environment_files_in_background(later.get_future().share());
        later.set_value(given);
        EXPECT_FALSE(pending.get());
    }
    {
        EncodedEnvironment pending;
        {
            std::promise<std::shared_ptr<const EnvironmentSource>> never;
            pending = encode_environment_files_in_background(never.get_future().share());
        }
        EXPECT_FALSE(pending.get()) << "a broken promise ends the encoder with nothing";
    }
    EXPECT_FALSE(EncodedEnvironment{});
    EXPECT_FALSE(EncodedEnvironment{}.get());
}

// A procedural sky is rendered into texels for the warnings only where a method's domain
// depends on the content: elsewhere its parameters give the same warnings.
TEST_F(BakedEnvironmentTest, ASkysWarningsNeedItsTexelsOnlyWhereTheyReadThem) {
    ProceduralSky black = ProceduralSky{};
    black.sun_radiance = black.zenith_radiance = black.horizon_radiance = black.ground_radiance = {0.0f, 0.0f, 0.0f};
    EXPECT_TRUE(black.black());
    EXPECT_FALSE(ProceduralSky{}.black());
    EXPECT_FALSE(ProceduralSky::white().black());
    ShaderCompiler compiler;
    ProgramCache programs(ctx(), compiler);
    int lazy = 0;
    for (const auto& [sky, width] : {std::pair{ProceduralSky{}, 128u}, std::pair{ProceduralSky{}, 16u},
                                     std::pair{ProceduralSky::white(), 64u}, std::pair{black, 64u}}) {
        EnvironmentSource source;
        source.name = "sky";
        source.sky = sky;
        source.width = source.source_width = width;
        source.height = source.source_height = width / 2;
        EnvironmentSource rendered = source;
        ASSERT_TRUE(materialize_environment(ctx(), programs, rendered));
        for (IrradianceMethod i : {IrradianceMethod::convolve, IrradianceMethod::riemann, IrradianceMethod::sh9,
                                   IrradianceMethod::blur, IrradianceMethod::lowmip})
            for (SpecularMethod s : {SpecularMethod::automatic, SpecularMethod::importance, SpecularMethod::filtered,
                                     SpecularMethod::convolve, SpecularMethod::mips, SpecularMethod::hybrid}) {
                IblSettings settings;
                settings.irradiance.method = i;
                settings.specular.method = s;
                if (method_warnings_read_content(settings)) continue;
                ++lazy;
                EXPECT_EQ(bake_warnings(source, settings), bake_warnings(rendered, settings)) << width;
            }
    }
    EXPECT_GT(lazy, 0);
    // The 16x8 sky warns about its size without being rendered.
    EnvironmentSource tiny;
    tiny.sky = ProceduralSky{};
    tiny.width = 16;
    tiny.height = 8;
    EXPECT_FALSE(bake_warnings(tiny, IblSettings{}).empty());
}

TEST(BakeRules, WhatASceneNeedsAndTheSplitLevel) {
    IblSettings requested;
    SceneNeeds metals;
    metals.diffuse = false;
    metals.min_roughness = 0.4f;
    const IblSettings s = ibl_settings_for_scene(requested, metals, false);
    EXPECT_FALSE(s.want_irradiance) << "pure metals need no irradiance";
    // The fitted lookups of roughness 0.4 and up read narrower kernels, down to the table's
    // smallest from the 0.4 row on (render/specular_lobes.h); never above the surfaces'.
    EXPECT_EQ(s.specular.min_roughness, lowest_lookup_roughness(0.4f));
    EXPECT_LT(s.specular.min_roughness, 0.4f);
    EXPECT_GT(s.specular.min_roughness, 0.1f);
    EXPECT_LT(lowest_lookup_roughness(0.1f), 0.1f);
    EXPECT_EQ(lowest_lookup_roughness(0.0f), 0.0f);
    EXPECT_TRUE(ibl_settings_for_scene(requested, metals, true).want_irradiance) << "multiscatter reads it";
    EXPECT_TRUE(ibl_settings_for_scene(requested, SceneNeeds{}, false).want_irradiance);
    // Lookup: roughness r reads level r x (levels - 1).
    EXPECT_FLOAT_EQ(specular_lookup_lod(0.5f, 6), 2.5f);
    EXPECT_FLOAT_EQ(specular_lookup_lod(1.0f, 6), 5.0f);
    EXPECT_FLOAT_EQ(specular_lookup_lod(1.0f, 1), 0.0f);
    // Split: with lights, only level 0 (the mirror) keeps them, however wide they are.
    EXPECT_EQ(light_split_level({}, 6), 0u);
    DiskLight sun;
    sun.angular_radius = 0.05f;
    const std::vector<DiskLight> one{sun};
    EXPECT_EQ(light_split_level(one, 6), 1u);
    sun.angular_radius = 2.0f;
    EXPECT_EQ(light_split_level(std::vector<DiskLight>{sun}, 6), 1u);
    // The key: any setting changes it, the same settings repeat it.
    EnvironmentSource env;
    env.content_hash = "abc";
    env.width = 64;
    env.height = 32;
    BakeSettings b;
    const std::string key = bake_key(env, b);
    EXPECT_EQ(key.size(), 16u);
    EXPECT_EQ(key, bake_key(env, b));
    BakeSettings other = b;
    other.extract_lights = true;
    EXPECT_NE(key, bake_key(env, other));
    other = b;
    other.ibl.specular.levels = 5;
    EXPECT_NE(key, bake_key(env, other));
    env.content_hash = "abd";
    EXPECT_NE(key, bake_key(env, b));
}

TEST(JsonReader, ReadsWhatTheWriterWritesAndNamesWhereItFails) {
    auto doc = parse_json(R"({"a": [1, -2.5e3, true, null], "s": "x\"\\\n\u00e9\ud83d\ude00", "o": {"k": {}}})");
    ASSERT_TRUE(doc) << doc.error().message;
    const JsonValue* a = doc->find("a");
    ASSERT_TRUE(a && a->is_array());
    ASSERT_EQ(a->items().size(), 4u);
    EXPECT_EQ(a->items()[1].number(), -2500.0);
    EXPECT_TRUE(a->items()[2].boolean());
    EXPECT_TRUE(a->items()[3].is_null());
    EXPECT_EQ(doc->find("s")->string(), "x\"\\\n\xc3\xa9\xf0\x9f\x98\x80");
    EXPECT_TRUE(doc->find("o")->find("k")->is_object());
    EXPECT_EQ(doc->find("missing"), nullptr);
    for (const char* bad : {"", "{", "{\"a\" 1}", "[1,]", "[1 2]", "\"open", "01x", "{\"a\": 1} x", "nul", "1e999"}) {
        auto r = parse_json(bad);
        EXPECT_FALSE(r) << bad;
        if (!r) EXPECT_NE(r.error().message.find("JSON line 1, column"), std::string::npos) << r.error().message;
    }
    EXPECT_NE(parse_json("{\n\n  \"a\": x}").error().message.find("line 3, column 8"), std::string::npos)
        << parse_json("{\n\n  \"a\": x}").error().message;
    EXPECT_FALSE(parse_json(std::string(100, '[') + std::string(100, ']'))) << "nesting is bounded";
}

}  // namespace
}  // namespace facet
