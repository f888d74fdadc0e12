// Structs that C++ fills and GLSL reads: the C++ mirror's sizes and offsets against the
// layout glslang gives the shader's struct (std430 / std140, read from the SPIR-V), so a
// member added, moved or retyped on one side only fails here. No GPU needed.
//
// Checked here are the mirrors declared in headers: the scene's instances and materials
// (facet/render/gpu_scene.h), the light every renderer uploads (engine/render/
// light_data.h, read by the forward pass, the reference pass and the skybox) and the
// forward pass's frame, draw and sky constants (engine/render/forward_data.h). The
// reference pass's Params and the bake's push-constant blocks are still defined inside
// their .cpp files.
#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <utility>

#include <facet/render/gpu_scene.h>
#include <facet/shader/compiler.h>
#include "render/forward_data.h"
#include "render/light_data.h"
#include "support/spirv_layout.h"

namespace facet {
namespace {

// std430 arrays of these (render/forward_interface.glsl): vec4 and mat4 members only, so
// the C++ layout is the GLSL one with no padding.
static_assert(sizeof(GpuInstance) == 128);
static_assert(offsetof(GpuInstance, world) == 0 && offsetof(GpuInstance, normal_matrix) == 64);
static_assert(sizeof(GpuMaterial) == 176);
static_assert(offsetof(GpuMaterial, base_color) == 0 && offsetof(GpuMaterial, emissive_f0) == 16 &&
              offsetof(GpuMaterial, factors) == 32 && offsetof(GpuMaterial, extra) == 48 &&
              offsetof(GpuMaterial, clearcoat) == 64 && offsetof(GpuMaterial, specular_color) == 80 &&
              offsetof(GpuMaterial, iridescence) == 96 && offsetof(GpuMaterial, anisotropy) == 112 &&
              offsetof(GpuMaterial, sheen) == 128 &&
              offsetof(GpuMaterial, transmission) == 144 && offsetof(GpuMaterial, attenuation) == 160);

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

// `type` in `spirv` has exactly `members` at their C++ offsets; for an array element
// (array_size set) the array stride is the C++ size.
void expect_members(const std::vector<uint32_t>& spirv, const char* shader, const char* type,
                    std::initializer_list<Member> members, std::optional<size_t> array_size) {
    auto layout = test::spirv_struct_layout(spirv, type);
    ASSERT_TRUE(layout) << type << " not found in " << shader;
    EXPECT_EQ(layout->offsets.size(), members.size()) << type << " in " << shader << ": member count";
    for (const Member& m : members) {
        ASSERT_TRUE(layout->offsets.count(m.name)) << type << "." << m.name << " not in " << shader;
        EXPECT_EQ(layout->offsets.at(m.name), m.offset) << type << "." << m.name << " in " << shader;
    }
    if (!array_size) return;
    ASSERT_TRUE(layout->array_stride) << type << " in " << shader << ": no array of it";
    EXPECT_EQ(*layout->array_stride, *array_size) << type << " in " << shader << ": array stride vs sizeof";
}

void expect_layout(const std::vector<uint32_t>& spirv, const char* shader, const char* type, size_t size,
                   std::initializer_list<Member> members) {
    expect_members(spirv, shader, type, members, size);
}

TEST(GpuLayout, InstanceDataMatchesGpuInstance) {
    auto spirv = compile(ShaderStage::vertex, "render/forward.vert");
    // One element per draw (a uniform block, no array): the members at their offsets, the
    // last one ending where the C++ struct does.
    expect_members(spirv, "render/forward.vert", "InstanceData",
                   {{"world", offsetof(GpuInstance, world)}, {"normal_matrix", offsetof(GpuInstance, normal_matrix)}},
                   std::nullopt);
    static_assert(offsetof(GpuInstance, normal_matrix) + sizeof(glm::mat4) == sizeof(GpuInstance));
}

TEST(GpuLayout, MaterialDataMatchesGpuMaterial) {
    auto spirv = compile(ShaderStage::fragment, "render/forward.frag", {{"USE_IBL", "1"}});
    expect_members(spirv, "render/forward.frag", "MaterialData",
                  {{"base_color", offsetof(GpuMaterial, base_color)},
                   {"emissive_f0", offsetof(GpuMaterial, emissive_f0)},
                   {"factors", offsetof(GpuMaterial, factors)},
                   {"extra", offsetof(GpuMaterial, extra)},
                   {"clearcoat", offsetof(GpuMaterial, clearcoat)},
                   {"specular_color", offsetof(GpuMaterial, specular_color)},
                   {"iridescence", offsetof(GpuMaterial, iridescence)},
                   {"anisotropy", offsetof(GpuMaterial, anisotropy)},
                   {"sheen", offsetof(GpuMaterial, sheen)},
                   {"transmission", offsetof(GpuMaterial, transmission)},
                   {"attenuation", offsetof(GpuMaterial, attenuation)}},
                   std::nullopt);
    static_assert(offsetof(GpuMaterial, attenuation) + sizeof(glm::vec4) == sizeof(GpuMaterial));
}

// The forward pass and the reference pass read one packed light (render/packed_light.glsl)
// from their buffers, and it is the layout LightData fills (the skybox's disks are
// constants of its pipeline, render/disk_constants.glsl).
TEST(GpuLayout, EveryShaderReadsLightData) {
    const std::pair<ShaderStage, const char*> shaders[] = {{ShaderStage::fragment, "render/forward.frag"},
                                                           {ShaderStage::compute, "render/reference.comp"}};
    for (const auto& [stage, name] : shaders) {
        auto spirv = compile(stage, name, {{"USE_IBL", "1"}});
        expect_layout(spirv, name, "PackedLight", sizeof(LightData),
                      {{"position_range", offsetof(LightData, position_range)},
                       {"direction_type", offsetof(LightData, direction_type)},
                       {"color_intensity", offsetof(LightData, color_intensity)},
                       {"cone", offsetof(LightData, cone)}});
    }
}

TEST(GpuLayout, ForwardConstantsMatchTheShaders) {
    using namespace forward;
    auto frag = compile(ShaderStage::fragment, "render/forward.frag", {{"USE_IBL", "1"}});
    expect_members(frag, "render/forward.frag", "Frame",
                   {{"view_projection", offsetof(FrameData, view_projection)},
                    {"camera_position", offsetof(FrameData, camera_position)},
                    {"ibl", offsetof(FrameData, ibl)},
                    {"counts", offsetof(FrameData, counts)}},
                   std::nullopt);
    auto sky = compile(ShaderStage::compute, "render/skybox.comp");
    expect_members(sky, "render/skybox.comp", "Sky",
                   {{"inverse_view_projection", offsetof(SkyConstants, inverse_view_projection)},
                    {"lod", offsetof(SkyConstants, lod)},
                    {"intensity", offsetof(SkyConstants, intensity)}},
                   std::nullopt);
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
