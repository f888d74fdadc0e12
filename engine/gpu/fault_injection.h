#pragma once
// The engine's side of fault injection (facet/gpu/faults.h): the sites call
// take_injected_fault() just before the real Vulkan call. ContextOptions::inject_fault
// arms a fault when a context is created or adopted; tests may arm one directly with
// inject_fault(). The armed faults and the call counts are process-wide (shared by every
// context) and thread-safe.
#include <cstdint>

#include <vulkan/vulkan.h>

#include <facet/gpu/faults.h>

namespace facet {

// The call at `site` after `skip` successful ones fails once with `result`
// (VK_SUCCESS: the site's usual failure, facet/gpu/faults.h). Replaces any fault armed
// at that site.
void inject_fault(FaultSite site, uint32_t skip = 0, VkResult result = VK_SUCCESS);
void clear_injected_faults();

// Called by the engine just before the real call at `site`: the VkResult to fail with,
// or VK_SUCCESS to go ahead.
VkResult take_injected_fault(FaultSite site);

// How many times the engine reached `site` in this process (to aim a fault at the
// n-th call in tests).
uint64_t fault_site_calls(FaultSite site);

}  // namespace facet
