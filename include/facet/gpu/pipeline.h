#pragma once
// Compute and graphics pipelines whose descriptors are pushed (VK_KHR_push_descriptor).
// The layout comes from the shaders' SPIR-V (facet/shader/reflection.h): set 0 holds the
// bindings the shaders declare, with their descriptor types and array sizes, and one
// push-constant range of the shaders' push block covers every stage; a compute
// pipeline knows its workgroup size. C++ never restates them.
//
// Errors: creation returns an Error when the SPIR-V cannot be reflected (naming the
// shader and the variable) or the driver fails. UsageError (thrown) is for programmer
// misuse: empty SPIR-V, descriptors or push constants that do not match what the
// shaders declare, the workgroup size of a graphics pipeline. Thread safety: pipelines
// may be created on several threads at once; binding and pushing record into the
// caller's command buffer.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/shader/reflection.h>

namespace facet {

class Context;

class PipelineLayout {
public:
    PipelineLayout() = default;
    // Set 0 of the reflection's bindings and its push-constant range, visible to its stages.
    static Result<PipelineLayout> create(Context& context, const ShaderReflection& reflection,
                                         const std::string& name);
    ~PipelineLayout();
    PipelineLayout(PipelineLayout&& other) noexcept;
    PipelineLayout& operator=(PipelineLayout&& other) noexcept;

    VkPipelineLayout handle() const { return layout_; }
    VkDescriptorSetLayout set_layout() const { return set_layout_; }
    VkShaderStageFlags stages() const { return stages_; }

private:
    void reset();
    Context* context_ = nullptr;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkShaderStageFlags stages_ = 0;
};

// One descriptor to push: an image view (sampled/storage/combined) or a buffer range.
struct DescriptorWrite {
    static DescriptorWrite storage_image(VkImageView view, VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL);
    static DescriptorWrite sampled_image(VkImageView view, VkSampler sampler,
                                         VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    static DescriptorWrite storage_buffer(VkBuffer buffer, VkDeviceSize offset = 0,
                                          VkDeviceSize range = VK_WHOLE_SIZE);
    static DescriptorWrite uniform_buffer(VkBuffer buffer, VkDeviceSize offset = 0,
                                          VkDeviceSize range = VK_WHOLE_SIZE);

    VkDescriptorType type{};
    VkDescriptorImageInfo image{};
    VkDescriptorBufferInfo buffer{};
};

class Pipeline {
public:
    Pipeline() = default;
    ~Pipeline();
    Pipeline(Pipeline&& other) noexcept;
    Pipeline& operator=(Pipeline&& other) noexcept;

    // A compute pipeline running `spirv` (entry point "main"); bindings, push-constant
    // size and workgroup size are read from it.
    static Result<Pipeline> compute(Context& context, std::span<const uint32_t> spirv, const std::string& name);
    // compute() in two steps, so that the driver's compilation (the slow one) can run on
    // another thread (ProgramCache::Batch): everything but the VkPipeline first (its
    // reflection, layout and shader module), then create_compute() makes the VkPipeline,
    // once. Until then the pipeline cannot be bound (bind() is a UsageError).
    static Result<Pipeline> compute_deferred(Context& context, std::span<const uint32_t> spirv,
                                             const std::string& name);
    Status create_compute();
    bool created() const { return pipeline_ != VK_NULL_HANDLE; }

    struct GraphicsDesc {
        std::span<const uint32_t> vertex_spirv;
        std::span<const uint32_t> fragment_spirv;
        std::vector<VkFormat> color_formats;
        VkFormat depth_format = VK_FORMAT_UNDEFINED;
        VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
        VkCullModeFlags cull = VK_CULL_MODE_NONE;
        VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        // Vertex input (empty: vertices generated in the shader).
        std::vector<VkVertexInputBindingDescription> vertex_bindings;
        std::vector<VkVertexInputAttributeDescription> vertex_attributes;
        bool depth_test = false;
        bool depth_write = false;
        bool alpha_blend = false;
    };
    // Dynamic rendering; viewport and scissor are dynamic state. The layout is the union
    // of the two stages' interfaces (a binding both declare must agree).
    static Result<Pipeline> graphics(Context& context, const GraphicsDesc& desc, const std::string& name);

    VkPipeline handle() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_.handle(); }
    VkPipelineBindPoint bind_point() const { return bind_point_; }
    // What the shaders declare: bindings of set 0, push-constant size, workgroup size.
    const ShaderReflection& reflection() const { return reflection_; }
    // local_size_x, _y, _z of a compute pipeline (UsageError for a graphics pipeline):
    // dispatch group_count(width, workgroup_size()[0]) groups, ...
    std::array<uint32_t, 3> workgroup_size() const;

    void bind(VkCommandBuffer cmd) const;
    // One write per descriptor of set 0, in binding order (an array binding takes one write
    // per element). UsageError when their number or types differ from the shaders'.
    void push_descriptors(VkCommandBuffer cmd, std::span<const DescriptorWrite> writes) const;
    // The whole push-constant block: UsageError unless `bytes` is the size the shaders
    // declare (reflection().push_constant_bytes).
    void push_constants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const;
    template <class T>
    void push_constants(VkCommandBuffer cmd, const T& data) const {
        push_constants(cmd, &data, sizeof(T));
    }

private:
    void reset();
    Context* context_ = nullptr;
    std::string name_;
    ShaderReflection reflection_;
    PipelineLayout layout_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkShaderModule module_ = VK_NULL_HANDLE;  // kept from compute_deferred() to create_compute()
    VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
};

// Workgroup count covering `size` items with groups of `local`.
inline uint32_t group_count(uint32_t size, uint32_t local) { return (size + local - 1) / local; }

}  // namespace facet
