#pragma once
// How the programs start Vulkan.
#include <memory>
#include <string>

#include <facet/gpu/context.h>

namespace facet {

// The Vulkan context of a program: the chosen device (empty: FACET_DEVICE, a GPU, else
// lavapipe), validation when asked (else FACET_VALIDATION decides); throws
// std::runtime_error with the reason when Vulkan cannot start.
std::unique_ptr<Context> start_vulkan(const std::string& device, bool validation);

}  // namespace facet
