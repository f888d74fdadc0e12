#pragma once
// Driver failures on demand, for testing error paths: out-of-memory, device loss, a
// failed pipeline or a GPU that never finishes are rare on a working machine, so the
// message that reaches the caller and the teardown of what was made so far would go
// untested. ContextOptions::inject_fault arms one; the chosen Vulkan call then fails
// exactly as a driver would report it, without being made.
#include <cstdint>

namespace facet {

enum class FaultSite : uint8_t {
    memory,    // any device memory allocation -> VK_ERROR_OUT_OF_DEVICE_MEMORY
    submit,    // vkQueueSubmit2 -> VK_ERROR_DEVICE_LOST
    pipeline,  // vkCreate{Compute,Graphics}Pipelines -> VK_ERROR_UNKNOWN
    hang,      // a submission is skipped, so its fence never signals: the wait times out
               // (ContextOptions::fence_timeout_ms) with VK_TIMEOUT
};
constexpr int fault_site_count = 4;

// The call at `site` after `skip` successful ones fails, once.
struct FaultInjection {
    FaultSite site = FaultSite::memory;
    uint32_t skip = 0;
};

}  // namespace facet
