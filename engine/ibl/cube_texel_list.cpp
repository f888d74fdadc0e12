#include "ibl/cube_texel_list.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <facet/core/shared_constants.h>
#include <facet/gpu/context.h>
#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>

namespace facet {

void dispatch_cube(PassContext& pc, const Pipeline& pipeline, uint32_t n) {
    const auto local = pipeline.workgroup_size();
    vkCmdDispatch(pc.cmd(), group_count(n, local[0]), group_count(n, local[1]), group_count(6, local[2]));
}

void dispatch_cube_faces(PassContext& pc, const Pipeline& pipeline, uint32_t n, uint32_t first, uint32_t count,
                         uint32_t texels_per_invocation_x) {
    const auto local = pipeline.workgroup_size();
    if (local[2] != 1) throw UsageError("dispatch_cube_faces: the shader's local size in z must be 1");
    const uint32_t columns = (n + texels_per_invocation_x - 1) / texels_per_invocation_x;
    // Rows of fewer groups than a workgroup is wide are taken row after row by each
    // workgroup's invocations (shaders/ibl/cube_faces_dispatch.glsl): no idle lanes.
    if (columns >= local[0])
        vkCmdDispatchBase(pc.cmd(), 0, 0, first, group_count(columns, local[0]), group_count(n, local[1]), count);
    else
        vkCmdDispatchBase(pc.cmd(), 0, 0, first, group_count(columns * n, local[0] * local[1]), 1, count);
}

uint32_t texels_per_invocation(const Context& context) {
    return context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 8u : 1u;
}

uint32_t list_lanes(const Context& context) {
    if (context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) return 1;
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceSubgroupSizeControlProperties size_control{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_PROPERTIES};
    subgroup.pNext = &size_control;
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(context.physical_device(), &properties);
    const uint32_t size = subgroup.subgroupSize;
    // A varying size could leave a subgroup partly filled, and a broadcast from an absent
    // lane undefined: only a device with one size (lavapipe: its vector width in floats).
    const bool one_size = size_control.minSubgroupSize == size && size_control.maxSubgroupSize == size;
    const bool usable = (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                        (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT) && one_size && size > 1 &&
                        64 % size == 0;
    return usable ? size : 1u;
}

std::vector<ShaderDefine> list_shader_defines(const Context& context, const char* texels_define) {
    return {{texels_define, std::to_string(texels_per_invocation(context))},
            {"FACET_LIST_LANES", std::to_string(list_lanes(context))}};
}

Result<CubeTexelList> add_cube_texel_list_pass(RenderGraph& graph, ProgramCache& programs, ImageHandle environment,
                                               uint32_t level, const std::string& name) {
    auto program = programs.compute("ibl/cube_texels.comp");
    if (!program) return program.error();
    const ImageDesc& env = graph.resource(environment).image_desc;
    const uint32_t face = env.mip_width(level);
    CubeTexelList list;
    list.count = 6 * face * face;
    // Texels are widest at a face's centre: corners at +-1/face from it in the tangent plane.
    const double rho = std::atan(std::sqrt(2.0) / face), child = std::atan(std::sqrt(2.0) / env.width);
    list.max_spread = std::sqrt(2.0) * rho + child;
    auto texels = graph.create_buffer(name, {VkDeviceSize(list.count) * 32});
    graph.add_compute_pass(name, [&](PassBuilder& b) {
        b.read_storage(environment, ImageRange::mip(0));
        list.buffer = b.write(texels);
    }, [p = *program, environment, texels, block = 1u << level, face](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {
            DescriptorWrite::storage_image(pc.view(environment, ImageRange::mip(0), cube_array_view)),
            DescriptorWrite::storage_buffer(pc.buffer(texels))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), block);
        dispatch_cube(pc, *p, face);
    });
    return list;
}

Result<CubeTexelList> add_equirect_texel_list_pass(RenderGraph& graph, ProgramCache& programs, ImageHandle equirect,
                                                   uint32_t target_entries, const std::string& name) {
    auto program = programs.compute("ibl/equirect_texels.comp");
    if (!program) return program.error();
    const ImageDesc& d = graph.resource(equirect).image_desc;
    uint32_t block = 1;
    while (uint64_t(d.width / (block * 2)) * (d.height / (block * 2)) >= target_entries) block *= 2;
    const uint32_t bx = (d.width + block - 1) / block, by = (d.height + block - 1) / block;
    CubeTexelList list;
    list.count = bx * by;
    // Blocks are widest at the equator: block x pi / height by block x 2 pi / width.
    const double texel = 0.5 * std::hypot(pi / d.height, 2 * pi / d.width);
    list.max_spread = std::sqrt(2.0) * std::min(block * texel, pi) + texel;
    auto texels = graph.create_buffer(name, {VkDeviceSize(list.count) * 32});
    graph.add_compute_pass(name, [&](PassBuilder& b) {
        b.read_storage(equirect, ImageRange::mip(0));
        list.buffer = b.write(texels);
    }, [p = *program, equirect, texels, block, bx, by](PassContext& pc) {
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_image(pc.view(equirect, ImageRange::mip(0))),
                                          DescriptorWrite::storage_buffer(pc.buffer(texels))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), block);
        const auto local = p->workgroup_size();
        vkCmdDispatch(pc.cmd(), group_count(bx, local[0]), group_count(by, local[1]), 1);
    });
    return list;
}

}  // namespace facet
