#include "start_vulkan.h"

#include <stdexcept>

namespace facet {

std::unique_ptr<Context> start_vulkan(const std::string& device, bool validation) {
    ContextOptions options;
    options.device = device;
    if (validation) options.validation = true;
    auto created = Context::create(options);
    if (!created) throw std::runtime_error("cannot start Vulkan: " + created.error().message);
    return std::move(created).value();
}

}  // namespace facet
