#pragma once
// Driver failures on demand. Out-of-memory, device loss and failed pipeline creation are
// rare on a working machine, so their error paths (the message that reaches the caller,
// the teardown of everything created so far) would go untested; these hooks make the
// chosen Vulkan call fail exactly as a driver would report it, without calling it.
//
// Programs read FACET_INJECT_FAULT=SITE[:SKIP] when their first Context is created:
// SITE is memory, submit or pipeline; the call after SKIP successful ones fails
// (default 0). Library callers use inject_fault() directly. Process-wide, thread-safe.
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>

namespace facet {

enum class FaultSite : uint8_t {
    memory,    // any device memory allocation -> VK_ERROR_OUT_OF_DEVICE_MEMORY
    submit,    // vkQueueSubmit2 -> VK_ERROR_DEVICE_LOST
    pipeline,  // vkCreate{Compute,Graphics}Pipelines -> VK_ERROR_UNKNOWN
};

// The call at `site` after `skip` successful ones fails once with `result`
// (VK_SUCCESS: the site's usual failure above). Replaces any fault armed at that site.
void inject_fault(FaultSite site, uint32_t skip = 0, VkResult result = VK_SUCCESS);
void clear_injected_faults();

// Called by the engine just before the real call at `site`: the VkResult to fail with,
// or VK_SUCCESS to go ahead.
VkResult take_injected_fault(FaultSite site);

// How many times the engine reached `site` in this process (to aim a fault at the
// n-th call in tests).
uint64_t fault_site_calls(FaultSite site);

// Arms the fault described by FACET_INJECT_FAULT (once per process); a malformed value
// is an error naming the variable.
Status inject_faults_from_environment();

}  // namespace facet
