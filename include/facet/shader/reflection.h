#pragma once
// What a compiled shader expects from the pipeline that runs it, read from its SPIR-V
// (the Binding/DescriptorSet decorations, the storage classes and types of its
// variables, the Offset decorations of its push-constant block, the LocalSize execution
// mode), so that C++ never restates a shader's bindings or workgroup size.
//
// Facet pushes descriptors into set 0 only: a resource in another set, an unsized
// (runtime) array of descriptors or an image whose sampled-ness is unknown is an Error
// naming the shader and the variable.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>

namespace facet {

struct DescriptorBinding {
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    uint32_t count = 1;  // array elements (layout(binding = b) uniform sampler2D maps[4]: 4)
    std::string name;    // the GLSL variable (or block) name, for messages; may be empty
};

struct ShaderReflection {
    VkShaderStageFlags stages = 0;
    std::vector<DescriptorBinding> bindings;  // set 0, ascending binding numbers
    // The push-constant block's size: the end of its last member (Offset + size), rounded
    // up to 4 as a VkPushConstantRange needs. 0: no push constants.
    uint32_t push_constant_bytes = 0;
    // Compute shaders: local_size_x, _y, _z. {0, 0, 0} for other stages.
    std::array<uint32_t, 3> workgroup_size{0, 0, 0};

    // The binding numbered `binding`, or nullptr.
    const DescriptorBinding* find(uint32_t binding) const;
    // Descriptors over all bindings (an array counts each element).
    uint32_t descriptor_count() const;
};

// The interface of one shader stage. `name` is used in messages.
Result<ShaderReflection> reflect_spirv(std::span<const uint32_t> words, std::string_view name);

// The interface of a pipeline made of stages `a` and `b` (vertex and fragment): the union
// of their bindings (a binding both declare must agree in type and count) and the larger
// push-constant block.
Result<ShaderReflection> merge_stages(const ShaderReflection& a, const ShaderReflection& b, std::string_view name);

// "storage image", "combined image sampler", ...
const char* descriptor_type_name(VkDescriptorType type);

}  // namespace facet
