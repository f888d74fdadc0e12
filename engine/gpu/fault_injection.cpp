#include "gpu/fault_injection.h"

#include <array>
#include <cstdlib>
#include <mutex>

#include <facet/core/log.h>

namespace facet {

namespace {

struct ArmedFault {
    bool armed = false;
    uint32_t skip = 0;
    VkResult result = VK_SUCCESS;
};

std::mutex g_mutex;
std::array<ArmedFault, 3> g_faults;
std::array<uint64_t, 3> g_calls{};

VkResult usual_failure(FaultSite site) {
    switch (site) {
        case FaultSite::memory: return VK_ERROR_OUT_OF_DEVICE_MEMORY;
        case FaultSite::submit: return VK_ERROR_DEVICE_LOST;
        case FaultSite::pipeline: return VK_ERROR_UNKNOWN;
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

Status inject_faults_from_environment() {
    static std::once_flag once;
    Status status = Ok{};
    std::call_once(once, [&] {
        const char* env = std::getenv("FACET_INJECT_FAULT");
        if (!env || !*env) return;
        const std::string spec = env;
        const size_t colon = spec.find(':');
        const std::string name = spec.substr(0, colon);
        FaultSite site;
        if (name == "memory") site = FaultSite::memory;
        else if (name == "submit") site = FaultSite::submit;
        else if (name == "pipeline") site = FaultSite::pipeline;
        else {
            status = Error{"FACET_INJECT_FAULT='" + spec + "': the site must be memory, submit or pipeline"};
            return;
        }
        uint32_t skip = 0;
        if (colon != std::string::npos) {
            const std::string count = spec.substr(colon + 1);
            char* end = nullptr;
            const unsigned long value = std::strtoul(count.c_str(), &end, 10);
            if (count.empty() || *end != '\0' || count[0] == '-' || value > UINT32_MAX) {
                status = Error{"FACET_INJECT_FAULT='" + spec + "': SKIP must be a whole number"};
                return;
            }
            skip = static_cast<uint32_t>(value);
        }
        inject_fault(site, skip);
        log(LogLevel::warning, "FACET_INJECT_FAULT=" + spec + ": a Vulkan call will fail on purpose");
    });
    return status;
}

}  // namespace facet
