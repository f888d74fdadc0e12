// Structs that C++ fills and GLSL reads: the C++ mirror's sizes and offsets against the
// layout glslang gives the shader's struct (std430 / std140, read from the SPIR-V), so a
// member added, moved or retyped on one side only fails here. No GPU needed.
//
// Reachable here are the mirrors declared in headers. The forward pass's FrameData,
// LightData, DrawConstants and SkyConstants (engine/render/forward_renderer.cpp), the
// reference pass's Params and LightData (engine/render/reference_renderer.cpp) and the
// bake's push-constant blocks (engine/ibl/*.cpp) are defined inside .cpp files; for the
// lights, the GLSL copies are checked against each other instead (one packed layout,
// render/packed_light.glsl).
#include <gtest/gtest.h>

#include <cstddef>

#include <facet/render/gpu_scene.h>
#include <facet/shader/compiler.h>
#include "support/spirv_layout.h"

namespace facet {
namespace {

// std430 arrays of these (render/forward_interface.glsl): vec4 and mat4 members only, so
// the C++ layout is the GLSL one with no padding.
static_assert(sizeof(GpuInstance) == 128);
static_assert(offsetof(GpuInstance, world) == 0 && offsetof(GpuInstance, normal_matrix) == 64);
static_assert(sizeof(GpuMaterial) == 64);
static_assert(offsetof(GpuMaterial, base_color) == 0 && offsetof(GpuMaterial, emissive_f0) == 16 &&
              offsetof(GpuMaterial, factors) == 32 && offsetof(GpuMaterial, extra) == 48);

std::vector<uint32_t> compile(ShaderStage stage, const char* name, std::vector<ShaderDefine> defines = {}) {
    ShaderCompiler compiler;
    auto spirv = compiler.compile(stage, name, defines);
    if (!spirv) {
        ADD_FAILURE() << name << ": " << spirv.error().message;
        return {};
    }
    return spirv->words;
}

struct Member {
    const char* name;
    size_t offset;
};

void expect_layout(const std::vector<uint32_t>& spirv, const char* shader, const char* type, size_t size,
                   std::initializer_list<Member> members) {
    auto layout = test::spirv_struct_layout(spirv, type);
    ASSERT_TRUE(layout) << type << " not found in " << shader;
    EXPECT_EQ(layout->offsets.size(), members.size()) << type << " in " << shader << ": member count";
    for (const Member& m : members) {
        ASSERT_TRUE(layout->offsets.count(m.name)) << type << "." << m.name << " not in " << shader;
        EXPECT_EQ(layout->offsets.at(m.name), m.offset) << type << "." << m.name << " in " << shader;
    }
    ASSERT_TRUE(layout->array_stride) << type << " in " << shader << ": no array of it";
    EXPECT_EQ(*layout->array_stride, size) << type << " in " << shader << ": array stride vs sizeof";
}

TEST(GpuLayout, InstanceDataMatchesGpuInstance) {
    auto spirv = compile(ShaderStage::vertex, "render/forward.vert");
    expect_layout(spirv, "render/forward.vert", "InstanceData", sizeof(GpuInstance),
                  {{"world", offsetof(GpuInstance, world)}, {"normal_matrix", offsetof(GpuInstance, normal_matrix)}});
}

TEST(GpuLayout, MaterialDataMatchesGpuMaterial) {
    auto spirv = compile(ShaderStage::fragment, "render/forward.frag", {{"USE_IBL", "1"}});
    expect_layout(spirv, "render/forward.frag", "MaterialData", sizeof(GpuMaterial),
                  {{"base_color", offsetof(GpuMaterial, base_color)},
                   {"emissive_f0", offsetof(GpuMaterial, emissive_f0)},
                   {"factors", offsetof(GpuMaterial, factors)},
                   {"extra", offsetof(GpuMaterial, extra)}});
}

// The forward pass, the reference pass and the skybox read one packed light layout.
TEST(GpuLayout, EveryShaderReadsTheSamePackedLight) {
    auto forward = compile(ShaderStage::fragment, "render/forward.frag", {{"USE_IBL", "1"}});
    auto reference = compile(ShaderStage::compute, "render/reference.comp");
    auto skybox = compile(ShaderStage::compute, "render/skybox.comp");
    auto a = test::spirv_struct_layout(forward, "Light");
    auto b = test::spirv_struct_layout(reference, "Light");
    auto c = test::spirv_struct_layout(skybox, "Disk");
    ASSERT_TRUE(a && b && c);
    EXPECT_EQ(a->offsets, b->offsets);
    EXPECT_EQ(a->offsets, c->offsets);
    ASSERT_TRUE(a->array_stride && b->array_stride && c->array_stride);
    EXPECT_EQ(*a->array_stride, 64u);
    EXPECT_EQ(*b->array_stride, *a->array_stride);
    EXPECT_EQ(*c->array_stride, *a->array_stride);
    EXPECT_EQ(a->offsets.at("position_range"), 0u);
    EXPECT_EQ(a->offsets.at("direction_type"), 16u);
    EXPECT_EQ(a->offsets.at("color_intensity"), 32u);
    EXPECT_EQ(a->offsets.at("cone"), 48u);
}

// The reader itself: a struct with padding the std430 rules put in.
TEST(GpuLayout, ReaderFindsStd430Padding) {
    const char* source = R"(#version 460
layout(local_size_x = 1) in;
struct Padded { float a; vec3 b; float c; vec2 d; };
layout(std430, binding = 0) buffer B { Padded items[]; };
void main() { items[0].a = 1.0; }
)";
    ShaderCompiler compiler;
    auto spirv = compiler.compile_source(ShaderStage::compute, "padded.comp", source);
    ASSERT_TRUE(spirv) << spirv.error().message;
    auto layout = test::spirv_struct_layout(spirv->words, "Padded");
    ASSERT_TRUE(layout);
    EXPECT_EQ(layout->offsets.at("a"), 0u);
    EXPECT_EQ(layout->offsets.at("b"), 16u);  // vec3 aligns to 16
    EXPECT_EQ(layout->offsets.at("c"), 28u);
    EXPECT_EQ(layout->offsets.at("d"), 32u);
    EXPECT_EQ(layout->array_stride.value_or(0), 48u);
    EXPECT_FALSE(test::spirv_struct_layout(spirv->words, "NoSuchStruct"));
}

}  // namespace
}  // namespace facet
