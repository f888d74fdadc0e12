#include "graph/access.h"

#include <string>

#include <facet/core/result.h>

namespace facet {

const char* access_name(Access access) {
    switch (access) {
        case Access::sampled: return "sampled";
        case Access::storage_read: return "storage read";
        case Access::storage_write: return "storage write";
        case Access::storage_read_write: return "storage read-write";
        case Access::color_attachment: return "colour attachment";
        case Access::depth_attachment: return "depth attachment";
        case Access::depth_read: return "depth read";
        case Access::transfer_src: return "transfer source";
        case Access::transfer_dst: return "transfer destination";
        case Access::uniform_read: return "uniform read";
        case Access::vertex_read: return "vertex read";
        case Access::index_read: return "index read";
    }
    return "?";
}

bool is_write(Access access) {
    switch (access) {
        case Access::storage_write:
        case Access::storage_read_write:
        case Access::color_attachment:
        case Access::depth_attachment:
        case Access::transfer_dst:
            return true;
        default:
            return false;
    }
}

AccessInfo access_info(PassKind kind, Access access, bool is_image) {
    const VkPipelineStageFlags2 shader_stages =
        kind == PassKind::compute ? VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT
                                  : VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    auto needs = [&](bool ok, const char* what) {
        if (!ok) throw UsageError(std::string(access_name(access)) + " access " + what);
    };
    const bool shader_pass = kind != PassKind::transfer;
    switch (access) {
        case Access::sampled:
            needs(is_image && shader_pass, "needs an image in a compute or graphics pass");
            return {shader_stages, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false};
        case Access::storage_read:
            needs(shader_pass, "needs a compute or graphics pass");
            return {shader_stages, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, false};
        case Access::storage_write:
            needs(shader_pass, "needs a compute or graphics pass");
            return {shader_stages, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL, true};
        case Access::storage_read_write:
            needs(shader_pass, "needs a compute or graphics pass");
            return {shader_stages, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_IMAGE_LAYOUT_GENERAL, true};
        case Access::color_attachment:
            needs(is_image && kind == PassKind::graphics, "needs an image in a graphics pass");
            return {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true};
        case Access::depth_attachment:
            needs(is_image && kind == PassKind::graphics, "needs an image in a graphics pass");
            return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, true};
        case Access::depth_read:
            needs(is_image && kind == PassKind::graphics, "needs an image in a graphics pass");
            return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, false};
        case Access::transfer_src:
            return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false};
        case Access::transfer_dst:
            return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true};
        case Access::uniform_read:
            needs(!is_image && shader_pass, "needs a buffer in a compute or graphics pass");
            return {shader_stages, VK_ACCESS_2_UNIFORM_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false};
        case Access::vertex_read:
            needs(!is_image && kind == PassKind::graphics, "needs a buffer in a graphics pass");
            return {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT,
                    VK_IMAGE_LAYOUT_UNDEFINED, false};
        case Access::index_read:
            needs(!is_image && kind == PassKind::graphics, "needs a buffer in a graphics pass");
            return {VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false};
    }
    throw UsageError("unknown access");
}

}  // namespace facet
