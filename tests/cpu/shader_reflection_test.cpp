// The interface read from compiled SPIR-V (facet/shader/reflection.h): descriptor types,
// array sizes, push-constant size and workgroup size of real shaders from shaders/ and of
// small sources written for one case each. The expected values are read off the GLSL by
// hand (std430 push blocks: scalars 4 bytes, vec4 16, mat4 64). No GPU needed.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include <facet/shader/compiler.h>
#include <facet/shader/reflection.h>

namespace facet {
namespace {

struct Expected {
    uint32_t binding;
    VkDescriptorType type;
    uint32_t count = 1;
};

void expect_bindings(const ShaderReflection& r, std::initializer_list<Expected> expected, const char* what) {
    ASSERT_EQ(r.bindings.size(), expected.size()) << what;
    size_t i = 0;
    for (const Expected& e : expected) {
        const DescriptorBinding& b = r.bindings[i++];
        EXPECT_EQ(b.binding, e.binding) << what;
        EXPECT_EQ(b.type, e.type) << what << " binding " << e.binding << " ('" << b.name << "') is a "
                                  << descriptor_type_name(b.type);
        EXPECT_EQ(b.count, e.count) << what << " binding " << e.binding;
    }
}

ShaderReflection reflect(ShaderStage stage, const char* name, std::vector<ShaderDefine> defines = {}) {
    ShaderCompiler compiler;
    auto spirv = compiler.compile(stage, name, defines);
    EXPECT_TRUE(spirv) << spirv.error().message;
    return spirv ? spirv->reflection : ShaderReflection{};
}

Result<ShaderReflection> reflect_source(ShaderStage stage, const char* source) {
    ShaderCompiler compiler;
    auto spirv = compiler.compile_source(stage, "case.glsl", source);
    if (!spirv) return spirv.error();
    return spirv->reflection;
}

using Workgroup = std::array<uint32_t, 3>;

// A sampled cube, a storage image and a push block of four scalars.
TEST(ShaderReflection, SpecularImportanceSamplesACubeAndWritesAnImage) {
    const ShaderReflection r = reflect(ShaderStage::compute, "ibl/specular_importance.comp");
    EXPECT_EQ(r.stages, VkShaderStageFlags(VK_SHADER_STAGE_COMPUTE_BIT));
    expect_bindings(r, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                    "specular_importance");
    EXPECT_EQ(r.push_constant_bytes, 16u);  // uint, float, uint, float
    EXPECT_EQ(r.workgroup_size, (Workgroup{8, 8, 1}));
    EXPECT_EQ(r.descriptor_count(), 2u);
}

TEST(ShaderReflection, ShProjectionReadsAndWritesBuffersIn64Wide1DGroups) {
    const ShaderReflection r = reflect(ShaderStage::compute, "ibl/sh9_project.comp");
    expect_bindings(r, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}, {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}}, "sh9_project");
    EXPECT_EQ(r.push_constant_bytes, 4u);
    EXPECT_EQ(r.workgroup_size, (Workgroup{64, 1, 1}));
}

TEST(ShaderReflection, ShaderWithoutPushConstantsHasNone) {
    const ShaderReflection r = reflect(ShaderStage::compute, "ibl/cube_downsample.comp");
    expect_bindings(r, {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                    "cube_downsample");
    EXPECT_EQ(r.push_constant_bytes, 0u);
}

// mat4 (stride 16, 4 columns) + float + float: 72 bytes, no trailing padding.
TEST(ShaderReflection, SkyboxPushBlockWithAMatrix) {
    for (auto defines : {std::vector<ShaderDefine>{}, std::vector<ShaderDefine>{{"FRAME_RGBA16F", "1"}}}) {
        const ShaderReflection r = reflect(ShaderStage::compute, "render/skybox.comp", defines);
        expect_bindings(r,
                        {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},  // the disks are constants of the pipeline
                        "skybox");
        EXPECT_EQ(r.push_constant_bytes, 72u);
        EXPECT_EQ(r.workgroup_size, (Workgroup{8, 8, 1}));
    }
}

// The forward pass: the two stages' interfaces merged into one layout.
TEST(ShaderReflection, ForwardVertexAndFragmentMergeIntoOneLayout) {
    const std::vector<ShaderDefine> defines = {{"USE_IBL", "1"}, {"HAS_NORMAL_MAP", "1"}, {"VIEW", "0"}};
    const ShaderReflection vs = reflect(ShaderStage::vertex, "render/forward.vert", defines);
    const ShaderReflection fs = reflect(ShaderStage::fragment, "render/forward.frag", defines);
    EXPECT_EQ(vs.stages, VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT));
    EXPECT_EQ(fs.stages, VkShaderStageFlags(VK_SHADER_STAGE_FRAGMENT_BIT));
    EXPECT_EQ(vs.workgroup_size, (Workgroup{0, 0, 0}));
    auto merged = merge_stages(vs, fs, "forward");
    ASSERT_TRUE(merged) << merged.error().message;
    EXPECT_EQ(merged->stages, VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));
    expect_bindings(*merged,
                    {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                     {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                     {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},   // the draw's instance
                     {3, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},   // and material
                     {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {11, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},   // the fitted lookups' table
                     {13, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},   // the clear coat's three textures
                     {14, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {15, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {16, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},   // KHR_materials_specular's two
                     {17, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {18, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},   // KHR_materials_iridescence's two
                     {19, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {20, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},    // KHR_materials_anisotropy's
                     {21, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},    // KHR_materials_sheen's two
                     {22, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                     {23, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},    // KHR_materials_transmission's
                     {24, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},    // KHR_materials_volume's
                     {25, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}},   // the transmission background
                    "forward");
    EXPECT_EQ(merged->push_constant_bytes, 0u);  // the draw's data is bound, not pushed
}

TEST(ShaderReflection, EveryKindOfDescriptorAndArrays) {
    auto r = reflect_source(ShaderStage::compute, R"(#version 460
layout(local_size_x = 4, local_size_y = 2, local_size_z = 3) in;
layout(binding = 0) uniform sampler2D maps[4];
layout(binding = 1) uniform texture2D plain_texture;
layout(binding = 2) uniform sampler plain_sampler;
layout(binding = 3) uniform samplerBuffer texels;
layout(binding = 4, r32f) uniform imageBuffer storage_texels;
layout(binding = 5, std140) uniform Constants { vec4 value; } constants;
layout(binding = 6, std430) buffer Data { float data[]; };
layout(binding = 8, rgba8) uniform writeonly image2D targets[6];
void main() {
    vec4 v = texture(maps[1], vec2(0.5)) + texture(sampler2D(plain_texture, plain_sampler), vec2(0.5)) +
             texelFetch(texels, 0) + imageLoad(storage_texels, 0) + constants.value;
    data[0] = v.x;
    imageStore(targets[5], ivec2(0), v);
}
)");
    ASSERT_TRUE(r) << r.error().message;
    expect_bindings(*r,
                    {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4},
                     {1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE},
                     {2, VK_DESCRIPTOR_TYPE_SAMPLER},
                     {3, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                     {4, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER},
                     {5, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                     {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                     {8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 6}},
                    "every kind");
    EXPECT_EQ(r->descriptor_count(), 4u + 6u + 6u);
    EXPECT_EQ(r->workgroup_size, (Workgroup{4, 2, 3}));
    EXPECT_EQ(r->bindings[0].name, "maps");
}

// Arrays (ArrayStride), nested structs and a row-major matrix in a push block.
TEST(ShaderReflection, PushBlockSizeFollowsTheOffsets) {
    auto r = reflect_source(ShaderStage::compute, R"(#version 460
layout(local_size_x = 1) in;
struct Pair { vec2 a; float b; };
layout(push_constant, std430) uniform Params {
    float weights[3];              // 0..12, stride 4
    Pair pair;                     // 16..28 (aligned to 8)
    layout(row_major) mat2x3 m;    // at 32: 3 rows of stride 8 (vec2) = 24 -> 56
    uint last;                     // 56..60
} params;
layout(std430, binding = 0) buffer Out { float o[]; };
void main() { o[0] = params.weights[2] + params.pair.b + params.m[1][2] + float(params.last); }
)");
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(r->push_constant_bytes, 60u);
}

// local_size_x_id: glslang emits gl_WorkGroupSize as a specialisation constant, whose
// default is what a pipeline built without specialisation runs with.
TEST(ShaderReflection, WorkgroupSizeFromSpecialisationConstants) {
    auto r = reflect_source(ShaderStage::compute, R"(#version 460
layout(local_size_x = 32, local_size_y = 3) in;
layout(local_size_x_id = 7) in;
layout(std430, binding = 0) buffer Out { uint o[]; };
void main() { o[gl_GlobalInvocationID.x] = gl_WorkGroupSize.x; }
)");
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(r->workgroup_size, (Workgroup{32, 3, 1}));
}

// The constant decorated BuiltIn WorkgroupSize wins over the LocalSize execution mode
// (SPIR-V specification, BuiltIn WorkgroupSize): the specialisation constant's default
// is changed to 48 in the module, LocalSize still says 32.
TEST(ShaderReflection, WorkgroupSizeBuiltInOverridesLocalSize) {
    ShaderCompiler compiler;
    auto spirv = compiler.compile_source(ShaderStage::compute, "spec.comp", R"(#version 460
layout(local_size_x = 32, local_size_y = 3) in;
layout(local_size_x_id = 7) in;
layout(std430, binding = 0) buffer Out { uint o[]; };
void main() { o[gl_GlobalInvocationID.x] = gl_WorkGroupSize.x; }
)");
    ASSERT_TRUE(spirv) << spirv.error().message;
    std::vector<uint32_t> words = spirv->words;
    constexpr uint32_t op_spec_constant = 50;
    int patched = 0;
    for (size_t at = 5; at < words.size(); at += words[at] >> 16)
        if ((words[at] & 0xffffu) == op_spec_constant && words[at + 3] == 32) {
            words[at + 3] = 48;
            ++patched;
        }
    ASSERT_GT(patched, 0) << "no specialisation constant of 32 in the module";
    auto r = reflect_spirv(words, "spec.comp (patched)");
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(r->workgroup_size, (Workgroup{48, 3, 1}));
}

TEST(ShaderReflection, ResourcesOutsideSetZeroAreAnError) {
    auto r = reflect_source(ShaderStage::compute, R"(#version 460
layout(local_size_x = 1) in;
layout(set = 1, binding = 0, std430) buffer Out { float o[]; };
void main() { o[0] = 1.0; }
)");
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("case.glsl"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("set 1"), std::string::npos) << r.error().message;
}

TEST(ShaderReflection, UnsizedDescriptorArraysAreAnError) {
    auto r = reflect_source(ShaderStage::compute, R"(#version 460
#extension GL_EXT_nonuniform_qualifier : require
layout(local_size_x = 1) in;
layout(binding = 0) uniform sampler2D maps[];
layout(std430, binding = 1) buffer Out { vec4 o[]; };
void main() { o[0] = texture(maps[nonuniformEXT(0)], vec2(0.5)); }
)");
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("'maps'"), std::string::npos) << r.error().message;
}

TEST(ShaderReflection, StagesDisagreeingOnABindingAreAnError) {
    auto vs = reflect_source(ShaderStage::vertex, R"(#version 460
layout(binding = 0, std140) uniform Frame { mat4 view_projection; } frame;
void main() { gl_Position = frame.view_projection * vec4(0.0, 0.0, 0.0, 1.0); }
)");
    auto fs = reflect_source(ShaderStage::fragment, R"(#version 460
layout(binding = 0) uniform sampler2D image;
layout(location = 0) out vec4 color;
void main() { color = texture(image, vec2(0.5)); }
)");
    ASSERT_TRUE(vs && fs);
    auto merged = merge_stages(*vs, *fs, "pair");
    ASSERT_FALSE(merged);
    EXPECT_NE(merged.error().message.find("binding 0"), std::string::npos) << merged.error().message;
    EXPECT_NE(merged.error().message.find("uniform buffer"), std::string::npos) << merged.error().message;
    EXPECT_NE(merged.error().message.find("combined image sampler"), std::string::npos) << merged.error().message;
}

TEST(ShaderReflection, MalformedModulesAreAnErrorNotACrash) {
    EXPECT_FALSE(reflect_spirv({}, "empty"));
    const std::vector<uint32_t> not_spirv = {1, 2, 3, 4, 5, 6};
    EXPECT_FALSE(reflect_spirv(not_spirv, "not spirv"));
    ShaderCompiler compiler;
    auto spirv = compiler.compile(ShaderStage::compute, "ibl/specular_importance.comp");
    ASSERT_TRUE(spirv) << spirv.error().message;
    // Every truncation: the last instruction is cut short (or the entry point is gone).
    for (size_t size = 5; size < spirv->words.size(); size += 7) {
        std::span<const uint32_t> cut(spirv->words.data(), size);
        auto r = reflect_spirv(cut, "cut");
        if (r) EXPECT_LE(r->bindings.size(), 2u);
    }
    // An instruction whose word count runs past the end.
    std::vector<uint32_t> overlong = spirv->words;
    overlong[5] = (0xffffu << 16) | (overlong[5] & 0xffffu);
    auto r = reflect_spirv(overlong, "overlong");
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("truncated"), std::string::npos) << r.error().message;
}

// SPIR-V served from the disk cache carries the same interface as a fresh compile.
TEST(ShaderReflection, DiskCacheHitsCarryTheInterface) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("facet_reflection_test_" + std::to_string(::getpid()));
    ShaderCompilerOptions options;
    options.disk_cache_dir = dir.string();
    options.share_in_process = false;  // the second compiler must read the disk
    ShaderReflection fresh, cached;
    {
        ShaderCompiler compiler(options);
        auto spirv = compiler.compile(ShaderStage::compute, "render/tonemap.comp");
        ASSERT_TRUE(spirv) << spirv.error().message;
        EXPECT_EQ(compiler.stats().compiles, 1u);
        fresh = spirv->reflection;
    }
    {
        ShaderCompiler compiler(options);
        auto spirv = compiler.compile(ShaderStage::compute, "render/tonemap.comp");
        ASSERT_TRUE(spirv) << spirv.error().message;
        EXPECT_EQ(compiler.stats().disk_hits, 1u);
        cached = spirv->reflection;
    }
    std::filesystem::remove_all(dir);
    expect_bindings(cached, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                    "tonemap (cached)");
    EXPECT_EQ(cached.push_constant_bytes, 12u);  // float, uint, float
    EXPECT_EQ(cached.workgroup_size, fresh.workgroup_size);
    EXPECT_EQ(cached.workgroup_size, (Workgroup{8, 8, 1}));
}

}  // namespace
}  // namespace facet
