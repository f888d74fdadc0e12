#include "start_vulkan.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <facet/core/log.h>

namespace facet {

namespace {

// FACET_INJECT_FAULT=SITE[:SKIP]; the error quotes the variable and its value.
Result<FaultInjection> parse_fault(const std::string& spec) {
    const size_t colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    FaultInjection fault;
    if (name == "memory") fault.site = FaultSite::memory;
    else if (name == "submit") fault.site = FaultSite::submit;
    else if (name == "pipeline") fault.site = FaultSite::pipeline;
    else if (name == "hang") fault.site = FaultSite::hang;
    else return Error{"FACET_INJECT_FAULT='" + spec + "': the site must be memory, submit, pipeline or hang"};
    if (colon != std::string::npos) {
        const std::string count = spec.substr(colon + 1);
        char* end = nullptr;
        const unsigned long value = std::strtoul(count.c_str(), &end, 10);
        if (count.empty() || *end != '\0' || count[0] == '-' || value > UINT32_MAX)
            return Error{"FACET_INJECT_FAULT='" + spec + "': SKIP must be a whole number"};
        fault.skip = static_cast<uint32_t>(value);
    }
    return fault;
}

}  // namespace

Result<ContextOptions> context_options_from_environment() {
    ContextOptions options;
    if (const char* log = std::getenv("FACET_LOG"); log && std::strcmp(log, "debug") == 0)
        set_log_level(LogLevel::debug);
    if (const char* validation = std::getenv("FACET_VALIDATION"))
        options.validation = std::strcmp(validation, "0") != 0;
    if (const char* device = std::getenv("FACET_DEVICE")) options.device = device;
    if (const char* fault = std::getenv("FACET_INJECT_FAULT"); fault && *fault) {
        auto parsed = parse_fault(fault);
        if (!parsed) return parsed.error();
        options.inject_fault = parsed.value();
    }
    return options;
}

ContextOptions program_context_options(const std::string& device, bool validation) {
    auto options = context_options_from_environment();
    if (!options) throw std::runtime_error(options.error().message);
    if (!device.empty()) options->device = device;
    if (validation) options->validation = true;
    return options.value();
}

std::unique_ptr<Context> start_vulkan(const std::string& device, bool validation) {
    auto created = Context::create(program_context_options(device, validation));
    if (!created) throw std::runtime_error("cannot start Vulkan: " + created.error().message);
    return std::move(created).value();
}

Result<std::unique_ptr<Context>> create_program_context() {
    auto options = context_options_from_environment();
    if (!options) return options.error();
    return Context::create(options.value());
}

}  // namespace facet
