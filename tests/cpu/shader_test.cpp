// Run-time GLSL compilation: includes, defines, error messages, caches. No GPU needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include <facet/core/hash.h>
#include <facet/shader/compiler.h>

namespace facet {
namespace {

namespace fs = std::filesystem;

constexpr const char* fill_source = R"(#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2D out_image;
void main() {
#ifdef SCALE
    imageStore(out_image, ivec2(gl_GlobalInvocationID.xy), vec4(SCALE));
#else
    imageStore(out_image, ivec2(gl_GlobalInvocationID.xy), vec4(1.0));
#endif
}
)";

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("facet_shader_test_" + std::to_string(::getpid()) + "_" +
                                            std::to_string(counter()++));
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    static int& counter() {
        static int c = 0;
        return c;
    }
    void write(const std::string& name, const std::string& text) const {
        fs::create_directories((path / name).parent_path());
        std::ofstream(path / name) << text;
    }
};

TEST(ShaderCompiler, CompilesComputeSourceToSpirv) {
    ShaderCompiler compiler;
    auto spirv = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source);
    ASSERT_TRUE(spirv) << spirv.error().message;
    ASSERT_GT(spirv->words.size(), 5u);
    EXPECT_EQ(spirv->words[0], 0x07230203u);   // SPIR-V magic
    // SPIR-V 1.5: 1.6 would bring LocalSizeId, which needs maintenance4 on the device.
    EXPECT_EQ(spirv->words[1], 0x00010500u);
}

TEST(ShaderCompiler, CompilesEveryEmbeddedEntryShader) {
    ShaderCompiler compiler;
    for (const char* name : {"ibl/procedural_sky.comp", "render/tonemap_preview.comp", "test/brdf_eval.comp"}) {
        auto spirv = compiler.compile(ShaderStage::compute, name);
        EXPECT_TRUE(spirv) << name << ": " << (spirv ? "" : spirv.error().message);
    }
}

// Variants chosen by the device that lavapipe, where the tests run, never takes: they
// must at least compile (a GPU's one texel per invocation of the convolutions; the output
// ranges' reduction in shared memory for a device without subgroup arithmetic).
TEST(ShaderCompiler, CompilesTheVariantsLavapipeDoesNotRun) {
    ShaderCompiler compiler;
    const std::pair<const char*, const char*> per_invocation[] = {
        {"ibl/specular_hybrid.comp", "FACET_HYBRID_TEXELS"},
        {"ibl/specular_convolve.comp", "FACET_CONVOLVE_TEXELS"},
        {"ibl/irradiance_convolve.comp", "FACET_IRRADIANCE_TEXELS"}};
    for (auto [shader, define] : per_invocation)
        for (const char* texels : {"1", "8"}) {
            const ShaderDefine d{define, texels};
            auto spirv = compiler.compile(ShaderStage::compute, shader, std::span(&d, 1));
            EXPECT_TRUE(spirv) << shader << ", " << texels << " texels: " << (spirv ? "" : spirv.error().message);
        }
    auto workgroup = compiler.compile(ShaderStage::compute, "ibl/output_range.comp");
    ASSERT_TRUE(workgroup) << workgroup.error().message;
    const ShaderDefine subgroup{"FACET_SUBGROUP_REDUCE", "1"};
    auto reduced = compiler.compile(ShaderStage::compute, "ibl/output_range.comp", std::span(&subgroup, 1));
    ASSERT_TRUE(reduced) << reduced.error().message;
    EXPECT_NE(workgroup->words, reduced->words);
}

// The shading include a host's shaders call and the constants header it reads (embedded
// from include/facet/core, byte for byte) are in the library under facet/.
TEST(ShaderCompiler, EmbedsTheShadingIncludeAndTheSharedConstants) {
    ShaderLibrary library;
    auto shading = library.load("facet/shading.glsl");
    ASSERT_TRUE(shading);
    EXPECT_NE(shading->find("facet_environment_light"), std::string::npos);
    auto constants = library.load("facet/shared_constants.h");
    ASSERT_TRUE(constants);
    std::ifstream in(std::string(FACET_SOURCE_DIR) + "/include/facet/core/shared_constants.h", std::ios::binary);
    const std::string on_disk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(*constants, on_disk);
}

TEST(ShaderCompiler, DefinesChangeTheOutputAndTheKey) {
    ShaderCompiler compiler;
    auto plain = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source);
    ShaderDefine scale{"SCALE", "2.5"};
    auto scaled = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source, std::span(&scale, 1));
    ASSERT_TRUE(plain && scaled);
    EXPECT_NE(plain->key, scaled->key);
    EXPECT_NE(plain->words, scaled->words);
}

// The interface variables (Input and Output storage) an OpEntryPoint lists, and the module's
// size: read from the words (opcode in the low half-word, word count in the high).
struct SpirvShape {
    size_t inputs = 0, outputs = 0;
};
SpirvShape shape_of(const std::vector<uint32_t>& words) {
    SpirvShape s;
    for (size_t i = 5; i < words.size();) {
        const uint32_t count = words[i] >> 16, opcode = words[i] & 0xffff;
        if (count == 0) break;
        if (opcode == 59 /* OpVariable */ && count >= 4) {
            if (words[i + 3] == 1 /* Input */) ++s.inputs;
            if (words[i + 3] == 3 /* Output */) ++s.outputs;
        }
        i += count;
    }
    return s;
}

// What the defines leave unreachable goes (SPIRV-Tools' performance passes: the lit forward
// shader is several times smaller), but every binding and every input and output stays, so
// that a variant's interface is its source's: the forward pass pushes all 26 descriptors to
// every material's pipeline, and the stages' locations must still meet (the validation
// layer warns of any attribute or output left unconsumed). debug_info keeps glslang's code.
TEST(ShaderCompiler, OptimisesWhatTheDefinesLeaveButKeepsTheInterface) {
    ShaderCompiler optimised;
    ShaderCompilerOptions debug_options;
    debug_options.debug_info = true;
    ShaderCompiler debug(debug_options);
    const std::vector<ShaderDefine> lit = {{"USE_IBL", "1"}, {"ALPHA_OPAQUE", "1"}};
    for (ShaderStage stage : {ShaderStage::vertex, ShaderStage::fragment}) {
        const char* name = stage == ShaderStage::vertex ? "render/forward.vert" : "render/forward.frag";
        auto small = optimised.compile(stage, name, lit);
        auto full = debug.compile(stage, name, lit);
        ASSERT_TRUE(small && full) << name;
        if (stage == ShaderStage::fragment)
            EXPECT_LT(small->words.size() * 4, full->words.size()) << name << ": the unreachable code is gone";
        ASSERT_EQ(small->reflection.bindings.size(), full->reflection.bindings.size()) << name;
        for (size_t b = 0; b < small->reflection.bindings.size(); ++b) {
            EXPECT_EQ(small->reflection.bindings[b].binding, full->reflection.bindings[b].binding) << name;
            EXPECT_EQ(small->reflection.bindings[b].type, full->reflection.bindings[b].type) << name;
        }
        EXPECT_EQ(small->reflection.push_constant_bytes, full->reflection.push_constant_bytes) << name;
        const SpirvShape a = shape_of(small->words), b = shape_of(full->words);
        EXPECT_EQ(a.inputs, b.inputs) << name;
        EXPECT_EQ(a.outputs, b.outputs) << name;
        EXPECT_GT(a.inputs, 0u) << name;
    }
}

TEST(ShaderCompiler, ErrorInMainFileNamesFileLineAndSource) {
    ShaderCompiler compiler;
    const std::string source = "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {\n    float x = ;\n}\n";
    auto spirv = compiler.compile_source(ShaderStage::compute, "broken.comp", source);
    ASSERT_FALSE(spirv);
    const std::string& message = spirv.error().message;
    EXPECT_NE(message.find("broken.comp:4: error:"), std::string::npos) << message;
    EXPECT_NE(message.find("    float x = ;"), std::string::npos) << message;
}

TEST(ShaderCompiler, ErrorInIncludedFileNamesThatFile) {
    TempDir dir;
    dir.write("lib/helpers.glsl", "float helper() {\n    return 1.0\n}\n");
    dir.write("main.comp",
              "#version 460\n#include \"lib/helpers.glsl\"\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
    ShaderCompilerOptions options;
    options.source_dir = dir.path.string();
    ShaderCompiler compiler(options);
    auto spirv = compiler.compile(ShaderStage::compute, "main.comp");
    ASSERT_FALSE(spirv);
    const std::string& message = spirv.error().message;
    EXPECT_NE(message.find("lib/helpers.glsl:3: error:"), std::string::npos) << message;
}

TEST(ShaderCompiler, MissingIncludeNamesTheIncludingFileAndLine) {
    ShaderCompiler compiler;
    const std::string source = "#version 460\n\n#include \"no_such_file.glsl\"\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    auto spirv = compiler.compile_source(ShaderStage::compute, "includer.comp", source);
    ASSERT_FALSE(spirv);
    const std::string& message = spirv.error().message;
    EXPECT_NE(message.find("includer.comp:3:"), std::string::npos) << message;
    EXPECT_NE(message.find("no_such_file.glsl"), std::string::npos) << message;
}

TEST(ShaderCompiler, ErrorInADefineSaysSo) {
    ShaderCompiler compiler;
    ShaderDefine bad{"1NOT_A_NAME", "1"};
    auto spirv = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source, std::span(&bad, 1));
    ASSERT_FALSE(spirv);
    EXPECT_NE(spirv.error().message.find("(defines)"), std::string::npos) << spirv.error().message;
}

TEST(ShaderCompiler, UnknownShaderNameIsAnError) {
    ShaderCompiler compiler;
    auto spirv = compiler.compile(ShaderStage::compute, "no/such/shader.comp");
    ASSERT_FALSE(spirv);
    EXPECT_NE(spirv.error().message.find("no/such/shader.comp"), std::string::npos);
}

TEST(ShaderCompiler, MemoryCacheHitsAndEditedIncludeRecompiles) {
    TempDir dir;
    dir.write("value.glsl", "const float VALUE = 1.0;\n");
    const std::string main =
        "#version 460\n#include \"value.glsl\"\nlayout(local_size_x = 1) in;\n"
        "layout(std430, binding = 0) buffer B { float v[]; };\nvoid main() { v[0] = VALUE; }\n";
    ShaderCompilerOptions options;
    options.source_dir = dir.path.string();
    ShaderCompiler compiler(options);
    auto first = compiler.compile_source(ShaderStage::compute, "main.comp", main);
    auto second = compiler.compile_source(ShaderStage::compute, "main.comp", main);
    ASSERT_TRUE(first && second);
    EXPECT_EQ(compiler.stats().compiles, 1u);
    EXPECT_EQ(compiler.stats().memory_hits, 1u);
    EXPECT_EQ(first->words, second->words);

    dir.write("value.glsl", "const float VALUE = 2.0;\n");
    auto edited = compiler.compile_source(ShaderStage::compute, "main.comp", main);
    ASSERT_TRUE(edited);
    EXPECT_NE(edited->key, first->key);
    EXPECT_EQ(compiler.stats().compiles, 2u);
}

// The key follows includes of includes, found as glslang finds them (beside the includer,
// then from the root), and a define: each edit compiles again, the same text does not.
TEST(ShaderCompiler, KeyFollowsNestedIncludesAndDefines) {
    TempDir dir;
    dir.write("lib/outer.glsl", "#include \"inner.glsl\"\n#include <root.glsl>\n");
    dir.write("lib/inner.glsl", "const float INNER = 1.0;\n");
    dir.write("root.glsl", "const float ROOT = 1.0;\n");
    const std::string main =
        "#version 460\n  #  include \"lib/outer.glsl\"\nlayout(local_size_x = 1) in;\n"
        "layout(std430, binding = 0) buffer B { float v[]; };\nvoid main() { v[0] = INNER + ROOT + SCALE; }\n";
    ShaderCompilerOptions options;
    options.source_dir = dir.path.string();
    ShaderCompiler compiler(options);
    const ShaderDefine one{"SCALE", "1.0"}, two{"SCALE", "2.0"};
    auto compile = [&](const ShaderDefine& d) {
        auto spirv = compiler.compile_source(ShaderStage::compute, "main.comp", main, std::span(&d, 1));
        EXPECT_TRUE(spirv) << (spirv ? "" : spirv.error().message);
        return spirv ? spirv->key : 0;
    };
    const uint64_t first = compile(one);
    EXPECT_EQ(compile(one), first);
    EXPECT_EQ(compiler.stats().compiles, 1u);
    dir.write("lib/inner.glsl", "const float INNER = 2.0;\n");
    const uint64_t inner = compile(one);
    EXPECT_NE(inner, first);
    dir.write("root.glsl", "const float ROOT = 2.0;\n");
    const uint64_t root = compile(one);
    EXPECT_NE(root, inner);
    EXPECT_NE(compile(two), root);
    EXPECT_EQ(compiler.stats().compiles, 4u);
    EXPECT_EQ(compiler.stats().memory_hits, 1u);
}

// A compiler that shares (the default) finds what another compiler of the process compiled,
// after its own caches: a host's render sessions, each with its own compiler and no cache
// directory, compile each shader once. One that does not share compiles it again.
TEST(ShaderCompiler, CompilersOfAProcessShareTheirResults) {
    const std::string source = std::string(fill_source) + "// " + std::to_string(::getpid()) + " shared\n";
    ShaderCompiler first, second;
    auto a = first.compile_source(ShaderStage::compute, "fill.comp", source);
    auto b = second.compile_source(ShaderStage::compute, "fill.comp", source);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(first.stats().compiles, 1u);
    EXPECT_EQ(second.stats().compiles, 0u);
    EXPECT_EQ(second.stats().process_hits, 1u);
    EXPECT_EQ(a->words, b->words);
    EXPECT_EQ(a->key, b->key);
    EXPECT_EQ(b->reflection.bindings.size(), a->reflection.bindings.size());
    ShaderCompilerOptions alone;
    alone.share_in_process = false;
    ShaderCompiler third(alone);
    auto c = third.compile_source(ShaderStage::compute, "fill.comp", source);
    ASSERT_TRUE(c);
    EXPECT_EQ(third.stats().compiles, 1u);
    EXPECT_EQ(third.stats().process_hits, 0u);
    EXPECT_EQ(c->words, a->words);
    // Another define is another entry.
    const ShaderDefine scale{"SCALE", "3.0"};
    auto d = second.compile_source(ShaderStage::compute, "fill.comp", source, std::span(&scale, 1));
    ASSERT_TRUE(d);
    EXPECT_EQ(second.stats().compiles, 1u);
    EXPECT_NE(d->words, a->words);
}

TEST(ShaderCompiler, DiskCacheIsReusedAndDamagedEntriesRecompiled) {
    TempDir cache;
    ShaderCompilerOptions options;
    options.disk_cache_dir = cache.path.string();
    options.share_in_process = false;  // each compiler's own compiles and disk reads are counted
    Spirv original;
    {
        ShaderCompiler compiler(options);
        auto spirv = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source);
        ASSERT_TRUE(spirv);
        original = *spirv;
        EXPECT_EQ(compiler.stats().compiles, 1u);
    }
    {
        ShaderCompiler compiler(options);
        auto spirv = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source);
        ASSERT_TRUE(spirv);
        EXPECT_EQ(compiler.stats().disk_hits, 1u);
        EXPECT_EQ(compiler.stats().compiles, 0u);
        EXPECT_EQ(spirv->words, original.words);
    }
    // Truncate every entry: the next compiler must notice and compile again.
    for (const auto& entry : fs::directory_iterator(cache.path)) fs::resize_file(entry.path(), 20);
    {
        ShaderCompiler compiler(options);
        auto spirv = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source);
        ASSERT_TRUE(spirv);
        EXPECT_EQ(compiler.stats().disk_hits, 0u);
        EXPECT_EQ(compiler.stats().compiles, 1u);
        EXPECT_EQ(spirv->words, original.words);
    }
}

// The on-disk cache stays within its bound: the least recently used entries go (a read
// counts as a use), a killed writer's old leftover goes, other files stay.
TEST(ShaderCompiler, DiskCacheKeepsItsBoundLeastRecentlyUsedFirst) {
    TempDir cache;
    ShaderCompilerOptions options;
    options.disk_cache_dir = cache.path.string();
    options.share_in_process = false;  // each compiler's compiles and disk reads are counted
    auto entry = [&](const Spirv& spirv) {
        Hash64 h;
        h.state = spirv.key;
        return cache.path / (h.hex() + ".spv");
    };
    auto compile = [](ShaderCompiler& compiler, int i) {
        const ShaderDefine scale{"SCALE", std::to_string(i) + ".0"};
        auto spirv = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source, std::span(&scale, 1));
        EXPECT_TRUE(spirv);
        return spirv ? *spirv : Spirv{};
    };
    std::vector<Spirv> made;
    uint64_t largest = 0;
    const auto now = fs::file_time_type::clock::now();
    {
        ShaderCompiler compiler(options);
        for (int i = 0; i < 6; ++i) {
            made.push_back(compile(compiler, i));
            ASSERT_TRUE(fs::exists(entry(made.back())));
            largest = std::max<uint64_t>(largest, fs::file_size(entry(made.back())));
            // Entry i last used 60 - i minutes ago (0 the oldest).
            fs::last_write_time(entry(made.back()), now - std::chrono::minutes(60 - i));
        }
    }
    std::ofstream(cache.path / "notes.txt") << "not an entry";
    const fs::path leftover = cache.path / "0123456789abcdef.spv.partial-1-0";
    std::ofstream(leftover) << "half";
    fs::last_write_time(leftover, now - std::chrono::hours(2));
    const fs::path fresh_leftover = cache.path / "0123456789abcdef.spv.partial-2-0";
    std::ofstream(fresh_leftover) << "being written";
    // A later process reads the oldest: used now.
    options.disk_cache_max_bytes = 4 * largest + largest / 2;
    {
        ShaderCompiler compiler(options);
        compile(compiler, 0);
        EXPECT_EQ(compiler.stats().disk_hits, 1u);
        // A new entry takes the cache over its bound (7 entries): down to 3/4 of it.
        made.push_back(compile(compiler, 6));
        EXPECT_EQ(compiler.stats().compiles, 1u);
    }
    uint64_t total = 0;
    for (const auto& e : fs::directory_iterator(cache.path))
        if (e.path().extension() == ".spv") total += fs::file_size(e.path());
    EXPECT_LE(total, options.disk_cache_max_bytes / 4 * 3);
    EXPECT_TRUE(fs::exists(entry(made[0]))) << "read just now, so kept";
    EXPECT_TRUE(fs::exists(entry(made[6]))) << "written just now, so kept";
    EXPECT_FALSE(fs::exists(entry(made[1]))) << "the least recently used goes first";
    EXPECT_FALSE(fs::exists(entry(made[2])));
    EXPECT_TRUE(fs::exists(entry(made[5]))) << "the most recent of the old ones stays";
    EXPECT_TRUE(fs::exists(cache.path / "notes.txt"));
    EXPECT_FALSE(fs::exists(leftover)) << "a killed writer's leftover, two hours old";
    EXPECT_TRUE(fs::exists(fresh_leftover)) << "another writer's file in progress";
}

// A cache directory that cannot be made (below a file) costs a warning, never a shader.
TEST(ShaderCompiler, UnwritableDiskCacheStillCompiles) {
    TempDir dir;
    std::ofstream(dir.path / "file") << "not a directory";
    ShaderCompilerOptions options;
    options.disk_cache_dir = (dir.path / "file" / "cache").string();
    options.share_in_process = false;  // each compiler's compiles are counted
    for (int run = 0; run < 2; ++run) {
        ShaderCompiler compiler(options);
        auto spirv = compiler.compile_source(ShaderStage::compute, "fill.comp", fill_source);
        ASSERT_TRUE(spirv) << spirv.error().message;
        EXPECT_EQ(compiler.stats().compiles, 1u);
        EXPECT_EQ(compiler.stats().disk_hits, 0u);
    }
}

TEST(ShaderLibraryPaths, NormalizesAndRejectsEscapes) {
    EXPECT_EQ(normalize_shader_path("a/b/../c.glsl"), "a/c.glsl");
    EXPECT_EQ(normalize_shader_path("./brdf.glsl"), "brdf.glsl");
    EXPECT_EQ(normalize_shader_path("../etc/passwd"), "");
}

}  // namespace
}  // namespace facet
