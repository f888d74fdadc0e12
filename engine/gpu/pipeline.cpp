#include <facet/gpu/pipeline.h>

#include <utility>
#include <vector>

#include <facet/core/result.h>
#include <facet/gpu/context.h>
#include "gpu/fault_injection.h"

namespace facet {

namespace {

struct ShaderModule {
    VkDevice device = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    ShaderModule() = default;
    ShaderModule(const ShaderModule&) = delete;
    ShaderModule& operator=(const ShaderModule&) = delete;
    ~ShaderModule() {
        if (module) vkDestroyShaderModule(device, module, nullptr);
    }
};

Status create_module(Context& context, std::span<const uint32_t> spirv, const std::string& name, ShaderModule& out) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    out.device = context.device();
    // A failed vkCreate* leaves its output undefined: the owners see VK_NULL_HANDLE.
    if (VkResult r = vkCreateShaderModule(out.device, &info, nullptr, &out.module); r != VK_SUCCESS) {
        out.module = VK_NULL_HANDLE;
        return Error{name + ": vkCreateShaderModule failed (" + vk_result_name(r) + ")", r};
    }
    context.set_name(out.module, VK_OBJECT_TYPE_SHADER_MODULE, name);
    return Ok{};
}

void require_spirv(std::span<const uint32_t> spirv, const std::string& name) {
    if (spirv.empty()) throw UsageError("pipeline '" + name + "': empty SPIR-V");
}

}  // namespace

// ---- PipelineLayout ----

Result<PipelineLayout> PipelineLayout::create(Context& context, const ShaderReflection& reflection,
                                              const std::string& name) {
    PipelineLayout l;
    l.context_ = &context;
    l.stages_ = reflection.stages;
    std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
    for (const DescriptorBinding& b : reflection.bindings)
        layout_bindings.push_back({b.binding, b.type, b.count, reflection.stages, nullptr});
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    set_info.bindingCount = static_cast<uint32_t>(layout_bindings.size());
    set_info.pBindings = layout_bindings.data();
    if (VkResult r = vkCreateDescriptorSetLayout(context.device(), &set_info, nullptr, &l.set_layout_);
        r != VK_SUCCESS) {
        l.set_layout_ = VK_NULL_HANDLE;
        return Error{name + ": vkCreateDescriptorSetLayout failed (" + vk_result_name(r) + ")", r};
    }
    context.set_name(l.set_layout_, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, name);

    VkPushConstantRange push{reflection.stages, 0, reflection.push_constant_bytes};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = 1;
    info.pSetLayouts = &l.set_layout_;
    info.pushConstantRangeCount = reflection.push_constant_bytes ? 1 : 0;
    info.pPushConstantRanges = &push;
    if (VkResult r = vkCreatePipelineLayout(context.device(), &info, nullptr, &l.layout_); r != VK_SUCCESS) {
        l.layout_ = VK_NULL_HANDLE;
        return Error{name + ": vkCreatePipelineLayout failed (" + vk_result_name(r) + ")", r};
    }
    context.set_name(l.layout_, VK_OBJECT_TYPE_PIPELINE_LAYOUT, name);
    return l;
}

PipelineLayout::~PipelineLayout() { reset(); }

PipelineLayout::PipelineLayout(PipelineLayout&& other) noexcept
    : context_(other.context_),
      set_layout_(std::exchange(other.set_layout_, VK_NULL_HANDLE)),
      layout_(std::exchange(other.layout_, VK_NULL_HANDLE)),
      stages_(other.stages_) {}

PipelineLayout& PipelineLayout::operator=(PipelineLayout&& other) noexcept {
    if (this != &other) {
        reset();
        context_ = other.context_;
        set_layout_ = std::exchange(other.set_layout_, VK_NULL_HANDLE);
        layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
        stages_ = other.stages_;
    }
    return *this;
}

void PipelineLayout::reset() {
    if (layout_) vkDestroyPipelineLayout(context_->device(), layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(context_->device(), set_layout_, nullptr);
    layout_ = VK_NULL_HANDLE;
    set_layout_ = VK_NULL_HANDLE;
}

// ---- DescriptorWrite ----

DescriptorWrite DescriptorWrite::storage_image(VkImageView view, VkImageLayout layout) {
    DescriptorWrite w;
    w.type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w.image = {VK_NULL_HANDLE, view, layout};
    return w;
}

DescriptorWrite DescriptorWrite::sampled_image(VkImageView view, VkSampler sampler, VkImageLayout layout) {
    DescriptorWrite w;
    w.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.image = {sampler, view, layout};
    return w;
}

DescriptorWrite DescriptorWrite::storage_buffer(VkBuffer buffer, VkDeviceSize offset, VkDeviceSize range) {
    DescriptorWrite w;
    w.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.buffer = {buffer, offset, range};
    return w;
}

DescriptorWrite DescriptorWrite::uniform_buffer(VkBuffer buffer, VkDeviceSize offset, VkDeviceSize range) {
    DescriptorWrite w;
    w.type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    w.buffer = {buffer, offset, range};
    return w;
}

// ---- Pipeline ----

Pipeline::~Pipeline() { reset(); }

Pipeline::Pipeline(Pipeline&& other) noexcept
    : context_(other.context_),
      name_(std::move(other.name_)),
      reflection_(std::move(other.reflection_)),
      layout_(std::move(other.layout_)),
      pipeline_(std::exchange(other.pipeline_, VK_NULL_HANDLE)),
      module_(std::exchange(other.module_, VK_NULL_HANDLE)),
      bind_point_(other.bind_point_) {}

Pipeline& Pipeline::operator=(Pipeline&& other) noexcept {
    if (this != &other) {
        reset();
        context_ = other.context_;
        name_ = std::move(other.name_);
        reflection_ = std::move(other.reflection_);
        layout_ = std::move(other.layout_);
        pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
        module_ = std::exchange(other.module_, VK_NULL_HANDLE);
        bind_point_ = other.bind_point_;
    }
    return *this;
}

void Pipeline::reset() {
    if (pipeline_) vkDestroyPipeline(context_->device(), pipeline_, nullptr);
    if (module_) vkDestroyShaderModule(context_->device(), module_, nullptr);
    pipeline_ = VK_NULL_HANDLE;
    module_ = VK_NULL_HANDLE;
}

Result<Pipeline> Pipeline::compute(Context& context, std::span<const uint32_t> spirv, const std::string& name) {
    auto p = compute_deferred(context, spirv, name);
    if (!p) return p.error();
    if (Status s = p->create_compute(); !s) return s.error();
    return p;
}

Result<Pipeline> Pipeline::compute_deferred(Context& context, std::span<const uint32_t> spirv, const std::string& name) {
    require_spirv(spirv, name);
    auto reflection = reflect_spirv(spirv, name);
    if (!reflection) return reflection.error();
    if (reflection->stages != VK_SHADER_STAGE_COMPUTE_BIT)
        return Error{name + ": not a compute shader, cannot make a compute pipeline of it"};
    Pipeline p;
    p.context_ = &context;
    p.name_ = name;
    p.bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
    p.reflection_ = std::move(reflection).value();
    auto layout = PipelineLayout::create(context, p.reflection_, name);
    if (!layout) return layout.error();
    p.layout_ = std::move(layout).value();
    ShaderModule module;
    if (Status s = create_module(context, spirv, name, module); !s) return s.error();
    p.module_ = std::exchange(module.module, VK_NULL_HANDLE);
    return p;
}

Status Pipeline::create_compute() {
    if (bind_point_ != VK_PIPELINE_BIND_POINT_COMPUTE || !module_ || pipeline_)
        throw UsageError("pipeline '" + name_ + "': create_compute() is for a pipeline made by compute_deferred(), once");
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module_;
    info.stage.pName = "main";
    info.layout = layout_.handle();
    // Dispatches may start at a workgroup other than 0 (vkCmdDispatchBase: a cube's faces
    // in passes of their own, ibl/specular.cpp).
    info.flags = VK_PIPELINE_CREATE_DISPATCH_BASE_BIT;
    VkResult r = take_injected_fault(FaultSite::pipeline);
    if (r == VK_SUCCESS) r = vkCreateComputePipelines(context_->device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_);
    vkDestroyShaderModule(context_->device(), module_, nullptr);
    module_ = VK_NULL_HANDLE;
    if (r != VK_SUCCESS) {
        pipeline_ = VK_NULL_HANDLE;
        return Error{name_ + ": vkCreateComputePipelines failed (" + vk_result_name(r) + ")", r};
    }
    context_->set_name(pipeline_, VK_OBJECT_TYPE_PIPELINE, name_);
    return Ok{};
}

Result<Pipeline> Pipeline::graphics(Context& context, const GraphicsDesc& desc, const std::string& name) {
    require_spirv(desc.vertex_spirv, name + " vertex");
    require_spirv(desc.fragment_spirv, name + " fragment");
    auto vertex_interface = reflect_spirv(desc.vertex_spirv, name + " vertex");
    if (!vertex_interface) return vertex_interface.error();
    auto fragment_interface = reflect_spirv(desc.fragment_spirv, name + " fragment");
    if (!fragment_interface) return fragment_interface.error();
    if (vertex_interface->stages != VK_SHADER_STAGE_VERTEX_BIT ||
        fragment_interface->stages != VK_SHADER_STAGE_FRAGMENT_BIT)
        return Error{name + ": a graphics pipeline needs a vertex and a fragment shader"};
    auto reflection = merge_stages(*vertex_interface, *fragment_interface, name);
    if (!reflection) return reflection.error();
    Pipeline p;
    p.context_ = &context;
    p.name_ = name;
    p.bind_point_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
    p.reflection_ = std::move(reflection).value();
    auto layout = PipelineLayout::create(context, p.reflection_, name);
    if (!layout) return layout.error();
    p.layout_ = std::move(layout).value();
    ShaderModule vertex, fragment;
    if (Status s = create_module(context, desc.vertex_spirv, name + " vertex", vertex); !s) return s.error();
    if (Status s = create_module(context, desc.fragment_spirv, name + " fragment", fragment); !s) return s.error();
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vertex.module;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fragment.module;
    stages[1].pName = "main";

    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertex_input.vertexBindingDescriptionCount = static_cast<uint32_t>(desc.vertex_bindings.size());
    vertex_input.pVertexBindingDescriptions = desc.vertex_bindings.data();
    vertex_input.vertexAttributeDescriptionCount = static_cast<uint32_t>(desc.vertex_attributes.size());
    vertex_input.pVertexAttributeDescriptions = desc.vertex_attributes.data();
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = desc.topology;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = desc.cull;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = desc.samples;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = desc.depth_test;
    depth.depthWriteEnable = desc.depth_write;
    depth.depthCompareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reversed Z
    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.color_formats.size());
    for (auto& b : blends) {
        b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                           VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
        if (desc.alpha_blend) {
            b.blendEnable = VK_TRUE;
            b.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
            b.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            b.colorBlendOp = VK_BLEND_OP_ADD;
            b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            b.alphaBlendOp = VK_BLEND_OP_ADD;
        }
    }
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = static_cast<uint32_t>(blends.size());
    blend.pAttachments = blends.data();
    const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<uint32_t>(desc.color_formats.size());
    rendering.pColorAttachmentFormats = desc.color_formats.data();
    rendering.depthAttachmentFormat = desc.depth_format;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = p.layout_.handle();
    VkResult r = take_injected_fault(FaultSite::pipeline);
    if (r == VK_SUCCESS) r = vkCreateGraphicsPipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline_);
    if (r != VK_SUCCESS) {
        p.pipeline_ = VK_NULL_HANDLE;
        return Error{name + ": vkCreateGraphicsPipelines failed (" + vk_result_name(r) + ")", r};
    }
    context.set_name(p.pipeline_, VK_OBJECT_TYPE_PIPELINE, name);
    return p;
}

void Pipeline::bind(VkCommandBuffer cmd) const {
    if (!pipeline_) throw UsageError("pipeline '" + name_ + "': bound before it was created");
    vkCmdBindPipeline(cmd, bind_point_, pipeline_);
}

std::array<uint32_t, 3> Pipeline::workgroup_size() const {
    if (bind_point_ != VK_PIPELINE_BIND_POINT_COMPUTE || !context_)
        throw UsageError("pipeline '" + name_ + "': only a compute pipeline has a workgroup size");
    return reflection_.workgroup_size;
}

void Pipeline::push_descriptors(VkCommandBuffer cmd, std::span<const DescriptorWrite> writes) const {
    if (writes.size() != reflection_.descriptor_count())
        throw UsageError("pipeline '" + name_ + "': " + std::to_string(writes.size()) + " descriptors pushed, " +
                         "the shaders declare " + std::to_string(reflection_.descriptor_count()));
    std::vector<VkWriteDescriptorSet> sets(writes.size());
    size_t i = 0;
    for (const DescriptorBinding& binding : reflection_.bindings)
        for (uint32_t element = 0; element < binding.count; ++element, ++i) {
            const DescriptorWrite& write = writes[i];
            if (write.type != binding.type)
                throw UsageError("pipeline '" + name_ + "': binding " + std::to_string(binding.binding) + " ('" +
                                 binding.name + "') is a " + descriptor_type_name(binding.type) + ", pushed a " +
                                 descriptor_type_name(write.type));
            VkWriteDescriptorSet& w = sets[i];
            w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstBinding = binding.binding;
            w.dstArrayElement = element;
            w.descriptorCount = 1;
            w.descriptorType = write.type;
            const bool is_buffer = write.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER ||
                                   write.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            if (is_buffer)
                w.pBufferInfo = &write.buffer;
            else
                w.pImageInfo = &write.image;
        }
    context_->cmd_push_descriptor_set(cmd, bind_point_, layout_.handle(), 0,
                                      static_cast<uint32_t>(sets.size()), sets.data());
}

void Pipeline::push_constants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const {
    if (bytes != reflection_.push_constant_bytes)
        throw UsageError("pipeline '" + name_ + "': " + std::to_string(bytes) + " bytes of push constants pushed, " +
                         "the shaders' push-constant block is " + std::to_string(reflection_.push_constant_bytes));
    vkCmdPushConstants(cmd, layout_.handle(), layout_.stages(), 0, bytes, data);
}

}  // namespace facet
