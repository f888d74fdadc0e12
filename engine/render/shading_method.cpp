#include <facet/render/shading_method.h>

namespace facet {
namespace {
constexpr const char* kShadingMethodNames[] = {"auto", "split-sum", "dominant", "lights", "lights+dominant"};
}  // namespace

const char* shading_method_name(ShadingMethod method) { return kShadingMethodNames[static_cast<int>(method)]; }

std::optional<ShadingMethod> parse_shading_method(std::string_view name) {
    for (int i = 0; i < 5; ++i)
        if (name == kShadingMethodNames[i]) return static_cast<ShadingMethod>(i);
    return std::nullopt;
}

const char* shading_method_names() { return "auto, split-sum, dominant, lights, lights+dominant"; }

}  // namespace facet
