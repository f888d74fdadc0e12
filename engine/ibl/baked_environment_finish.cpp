#include "ibl/baked_environment_finish.h"

#include <cstring>

#include <facet/gpu/context.h>
#include <facet/gpu/pipeline.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>
#include "core/guarded.h"
#include "ibl/baked_outputs.h"

namespace facet {

ImageHandle add_clear_levels_pass(RenderGraph& graph, ImageHandle image, uint32_t level_count) {
    ImageHandle cleared = image;
    const ImageRange levels{0, level_count, 0, all_remaining};
    graph.add_transfer_pass("clear unused levels", [&](PassBuilder& b) { cleared = b.copy_to(image, levels); },
                            [image, level_count](PassContext& pc) {
                                const VkClearColorValue zero{};
                                const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, level_count, 0,
                                                                    VK_REMAINING_ARRAY_LAYERS};
                                vkCmdClearColorImage(pc.cmd(), pc.image(image), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                                     &zero, 1, &range);
                            });
    return cleared;
}

namespace {

// Whether compute shaders have subgroup arithmetic (lavapipe has; Vulkan does not require it).
bool subgroup_arithmetic_in_compute(const Context& context) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
    vkGetPhysicalDeviceProperties2(context.physical_device(), &properties);
    const VkSubgroupFeatureFlags needed = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
    return (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
           (subgroup.supportedOperations & needed) == needed;
}

}  // namespace

Result<BufferHandle> add_output_range_passes(RenderGraph& graph, ProgramCache& programs,
                                             std::vector<CheckedOutput>& outputs) {
    // Reduced per subgroup where the device can (no shared memory, no barriers: a third of
    // the pass's time on lavapipe), per workgroup otherwise.
    std::vector<ShaderDefine> defines;
    if (subgroup_arithmetic_in_compute(programs.context())) defines.push_back({"FACET_SUBGROUP_REDUCE", "1"});
    auto range = programs.compute("ibl/output_range.comp", defines);
    if (!range) return range.error();
    BufferHandle ranges = graph.create_buffer("output ranges", {VkDeviceSize(outputs.size() * 2 * sizeof(uint32_t))});
    graph.add_transfer_pass("output ranges clear", [&](PassBuilder& b) { ranges = b.write(ranges, Access::transfer_dst); },
                            [ranges](PassContext& pc) { vkCmdFillBuffer(pc.cmd(), pc.buffer(ranges), 0, VK_WHOLE_SIZE, 0); });
    for (uint32_t slot = 0; slot < outputs.size(); ++slot) {
        CheckedOutput& out = outputs[slot];
        const ImageDesc desc = graph.resource(out.image).image_desc;
        const std::string name = "output range (" + graph.resource(out.image).name + ")";
        const ImageRange levels{out.first_level, all_remaining, 0, all_remaining};
        graph.add_compute_pass(name, [&](PassBuilder& b) {
            out.image = b.read_storage(out.image, levels);
            ranges = b.write(ranges, Access::storage_read_write);
        }, [p = *range, image = out.image, ranges, desc, first = out.first_level, slot](PassContext& pc) {
            p->bind(pc.cmd());
            p->push_constants(pc.cmd(), slot);
            for (uint32_t m = first; m < desc.mip_levels; ++m) {
                const DescriptorWrite writes[] = {
                    DescriptorWrite::storage_image(pc.view(image, ImageRange::mip(m), VK_IMAGE_VIEW_TYPE_2D_ARRAY)),
                    DescriptorWrite::storage_buffer(pc.buffer(ranges))};
                p->push_descriptors(pc.cmd(), writes);
                const auto local = p->workgroup_size();
                // Each invocation reads 8 rows (shaders/ibl/output_range.comp).
                vkCmdDispatch(pc.cmd(), group_count(desc.mip_width(m), local[0]),
                              group_count(desc.mip_height(m), local[1] * 8), desc.array_layers);
            }
        });
    }
    return ranges;
}

std::vector<OutputRange> read_output_ranges(Context& context, const Buffer& ranges, size_t count) {
    const std::vector<std::byte> bytes = or_throw(read_buffer(context, ranges));
    std::vector<OutputRange> out(count);
    for (size_t i = 0; i < count && (2 * i + 2) * sizeof(uint32_t) <= bytes.size(); ++i) {
        uint32_t peak_bits, bad;
        std::memcpy(&peak_bits, bytes.data() + 2 * i * sizeof(uint32_t), sizeof peak_bits);
        std::memcpy(&bad, bytes.data() + (2 * i + 1) * sizeof(uint32_t), sizeof bad);
        std::memcpy(&out[i].peak, &peak_bits, sizeof peak_bits);
        out[i].bad = bad;
    }
    return out;
}

Result<const Pipeline*> half_conversion_program(ProgramCache& programs) {
    return programs.compute("ibl/to_half.comp");
}

std::vector<Image> convert_to_half(ProgramCache& programs, std::span<Image* const> rgba32f, VkImageLayout layout,
                                   std::span<const std::string> names) {
    Context& context = programs.context();
    const Pipeline* convert = or_throw(half_conversion_program(programs));
    std::vector<Image> halves;
    // The views are made before recording (the images keep them).
    std::vector<std::vector<std::pair<VkImageView, VkImageView>>> views(rgba32f.size());
    for (size_t i = 0; i < rgba32f.size(); ++i) {
        ImageDesc desc = rgba32f[i]->desc();
        desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        halves.push_back(or_throw(Image::create(context, desc,
                                                VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                                names[i])));
        for (uint32_t m = 0; m < desc.mip_levels; ++m) {
            const VkImageSubresourceRange level{VK_IMAGE_ASPECT_COLOR_BIT, m, 1, 0, desc.array_layers};
            views[i].emplace_back(or_throw(rgba32f[i]->view(level, VK_IMAGE_VIEW_TYPE_2D_ARRAY)),
                                  or_throw(halves[i].view(level, VK_IMAGE_VIEW_TYPE_2D_ARRAY)));
        }
    }
    or_throw(context.submit_and_wait([&](VkCommandBuffer cmd) {
        // The graph's run has completed (its fence was waited on); its writes were made
        // available by the final barriers, so the reads here wait on those.
        for (size_t i = 0; i < rgba32f.size(); ++i) {
            const VkImageSubresourceRange all = whole_range(rgba32f[i]->desc());
            image_barrier(cmd, rgba32f[i]->handle(), all, layout, VK_IMAGE_LAYOUT_GENERAL,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
            image_barrier(cmd, halves[i].handle(), all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                          VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        }
        convert->bind(cmd);
        const auto local = convert->workgroup_size();
        for (size_t i = 0; i < rgba32f.size(); ++i) {
            const ImageDesc& desc = rgba32f[i]->desc();
            for (uint32_t m = 0; m < desc.mip_levels; ++m) {
                const DescriptorWrite writes[] = {DescriptorWrite::storage_image(views[i][m].first),
                                                  DescriptorWrite::storage_image(views[i][m].second)};
                convert->push_descriptors(cmd, writes);
                vkCmdDispatch(cmd, group_count(desc.mip_width(m), local[0]), group_count(desc.mip_height(m), local[1]),
                              desc.array_layers);
            }
        }
        for (size_t i = 0; i < rgba32f.size(); ++i) {
            const VkImageSubresourceRange all = whole_range(rgba32f[i]->desc());
            image_barrier(cmd, rgba32f[i]->handle(), all, VK_IMAGE_LAYOUT_GENERAL, layout,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
            image_barrier(cmd, halves[i].handle(), all, VK_IMAGE_LAYOUT_GENERAL, kBakedLayout,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        }
    }, "converting the baked outputs to RGBA16F"));
    return halves;
}

}  // namespace facet
