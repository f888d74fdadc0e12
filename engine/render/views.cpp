#include <facet/render/views.h>

#include <sstream>

namespace facet {
namespace {
constexpr const char* kViewNames[] = {"final", "normal", "position", "basecolor", "metallic",
                                      "roughness", "occlusion", "emissive", "D", "F", "G",
                                      "diffuse", "specular", "irradiance", "prefiltered", "f0",
                                      "clearcoat", "clearcoat_normal", "iridescence", "anisotropy", "sheen",
                                      "transmission"};
constexpr int kViewCount = sizeof(kViewNames) / sizeof(kViewNames[0]);
}  // namespace

const char* view_name(View view) {
    const int i = static_cast<int>(view);
    return i >= 0 && i < kViewCount ? kViewNames[i] : "unknown";
}

std::optional<View> parse_view(const std::string& name) {
    for (int i = 0; i < kViewCount; ++i)
        if (name == kViewNames[i]) return static_cast<View>(i);
    return std::nullopt;
}

bool view_of_surface(View view) {
    switch (view) {
        case View::normal:
        case View::position:
        case View::basecolor:
        case View::metallic:
        case View::roughness:
        case View::occlusion:
        case View::emissive:
        case View::specular_f0:
        case View::clearcoat:
        case View::clearcoat_normal:
        case View::iridescence:
        case View::anisotropy:
        case View::sheen:
        case View::transmission: return true;
        case View::final_color:
        case View::D:
        case View::F:
        case View::G:
        case View::diffuse:
        case View::specular:
        case View::irradiance:
        case View::prefiltered: return false;
    }
    return false;
}

std::string view_names() {
    std::string list;
    for (int i = 1; i < kViewCount; ++i) list += std::string(i > 1 ? "," : "") + kViewNames[i];
    return list;
}

std::optional<std::vector<View>> parse_view_list(const std::string& list, std::string* error) {
    std::vector<View> views;
    std::stringstream in(list);
    std::string item;
    while (std::getline(in, item, ',')) {
        if (item.empty()) continue;
        if (item == "all") {
            for (int i = 1; i < kViewCount; ++i) views.push_back(static_cast<View>(i));
            continue;
        }
        auto view = parse_view(item);
        if (!view || *view == View::final_color) {
            if (error) *error = "unknown view '" + item + "' (one of: all," + view_names() + ")";
            return std::nullopt;
        }
        views.push_back(*view);
    }
    return views;
}

}  // namespace facet
