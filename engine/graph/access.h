#pragma once
// What each declared access means for synchronisation2: pipeline stages, access flags
// and the image layout it needs. Pure functions (no Vulkan calls).
#include <vulkan/vulkan.h>

#include <facet/graph/types.h>

namespace facet {

struct AccessInfo {
    VkPipelineStageFlags2 stages;
    VkAccessFlags2 access;
    VkImageLayout layout;  // for images
    bool writes;
};

// Throws UsageError when the access makes no sense for the pass kind (for example a
// colour attachment in a compute pass) or the resource kind.
AccessInfo access_info(PassKind kind, Access access, bool is_image);

}  // namespace facet
