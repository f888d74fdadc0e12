#include "gpu/fault_injection.h"

#include <array>
#include <mutex>

namespace facet {

namespace {

struct ArmedFault {
    bool armed = false;
    uint32_t skip = 0;
    VkResult result = VK_SUCCESS;
};

std::mutex g_mutex;
std::array<ArmedFault, fault_site_count> g_faults;
std::array<uint64_t, fault_site_count> g_calls{};

VkResult usual_failure(FaultSite site) {
    switch (site) {
        case FaultSite::memory: return VK_ERROR_OUT_OF_DEVICE_MEMORY;
        case FaultSite::submit: return VK_ERROR_DEVICE_LOST;
        case FaultSite::pipeline: return VK_ERROR_UNKNOWN;
        case FaultSite::hang: return VK_TIMEOUT;
    }
    return VK_ERROR_UNKNOWN;
}

}  // namespace

void inject_fault(FaultSite site, uint32_t skip, VkResult result) {
    std::lock_guard lock(g_mutex);
    g_faults[static_cast<size_t>(site)] = {true, skip, result == VK_SUCCESS ? usual_failure(site) : result};
}

void clear_injected_faults() {
    std::lock_guard lock(g_mutex);
    g_faults = {};
}

VkResult take_injected_fault(FaultSite site) {
    std::lock_guard lock(g_mutex);
    ++g_calls[static_cast<size_t>(site)];
    ArmedFault& f = g_faults[static_cast<size_t>(site)];
    if (!f.armed) return VK_SUCCESS;
    if (f.skip > 0) {
        --f.skip;
        return VK_SUCCESS;
    }
    f.armed = false;
    return f.result;
}

uint64_t fault_site_calls(FaultSite site) {
    std::lock_guard lock(g_mutex);
    return g_calls[static_cast<size_t>(site)];
}

}  // namespace facet
