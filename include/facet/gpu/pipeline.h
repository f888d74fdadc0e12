#pragma once
// Compute and graphics pipelines whose descriptors are pushed (VK_KHR_push_descriptor):
// set 0 holds bindings 0..n-1 of the given types; one push-constant range for all stages.
//
// Errors: creation throws VulkanError when the driver fails and UsageError for
// programmer misuse (empty SPIR-V). Thread safety: pipelines may be created on several
// threads at once; binding and pushing record into the caller's command buffer.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace facet {

class Context;

class PipelineLayout {
public:
    PipelineLayout() = default;
    PipelineLayout(Context& context, std::span<const VkDescriptorType> bindings,
                   VkShaderStageFlags stages, uint32_t push_constant_bytes,
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

    static Pipeline compute(Context& context, std::span<const uint32_t> spirv,
                            std::span<const VkDescriptorType> bindings,
                            uint32_t push_constant_bytes, const std::string& name);

    struct GraphicsDesc {
        std::span<const uint32_t> vertex_spirv;
        std::span<const uint32_t> fragment_spirv;
        std::vector<VkDescriptorType> bindings;
        uint32_t push_constant_bytes = 0;
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
    // Dynamic rendering; viewport and scissor are dynamic state.
    static Pipeline graphics(Context& context, const GraphicsDesc& desc, const std::string& name);

    VkPipeline handle() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_.handle(); }
    VkPipelineBindPoint bind_point() const { return bind_point_; }

    void bind(VkCommandBuffer cmd) const;
    // Pushes descriptors for bindings 0..writes.size()-1 of set 0.
    void push_descriptors(VkCommandBuffer cmd, std::span<const DescriptorWrite> writes) const;
    void push_constants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const;
    template <class T>
    void push_constants(VkCommandBuffer cmd, const T& data) const {
        push_constants(cmd, &data, sizeof(T));
    }

private:
    void reset();
    Context* context_ = nullptr;
    PipelineLayout layout_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
};

// Workgroup count covering `size` items with groups of `local`.
inline uint32_t group_count(uint32_t size, uint32_t local) { return (size + local - 1) / local; }

}  // namespace facet
