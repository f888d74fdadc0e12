#include "light_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace facet {

namespace {

Result<glm::vec3> parse_vec3(const std::string& text, const std::string& what) {
    glm::vec3 v;
    char extra;
    if (std::sscanf(text.c_str(), "%f,%f,%f%c", &v.x, &v.y, &v.z, &extra) != 3 || !std::isfinite(v.x) ||
        !std::isfinite(v.y) || !std::isfinite(v.z))
        return Error{what + ": expected X,Y,Z, got '" + text + "'"};
    return v;
}

Result<float> parse_float(const std::string& text, const std::string& what) {
    char* end = nullptr;
    const float value = std::strtof(text.c_str(), &end);
    if (text.empty() || *end || !std::isfinite(value)) return Error{what + ": '" + text + "' is not a number"};
    return value;
}

}  // namespace

Result<Light> parse_light(const std::string& text) {
    std::istringstream in(text);
    std::string type, item;
    in >> type;
    Light light;
    if (type == "directional") light.type = LightType::directional;
    else if (type == "point") light.type = LightType::point;
    else if (type == "spot") light.type = LightType::spot;
    else return Error{"--light '" + text + "': the type must be directional, point or spot"};
    light.intensity = light.type == LightType::directional ? 3.0f : 100.0f;
    bool has_position = false, has_direction = false;
    while (in >> item) {
        const auto eq = item.find('=');
        if (eq == std::string::npos) return Error{"--light '" + text + "': expected KEY=VALUE, got '" + item + "'"};
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        const std::string what = "--light " + key;
        if (key == "pos" || key == "dir" || key == "color") {
            auto v = parse_vec3(value, what);
            if (!v) return v.error();
            if (key == "pos") light.position = *v, has_position = true;
            if (key == "dir") light.direction = *v, has_direction = true;
            if (key == "color") light.color = *v;
        } else if (key == "intensity" || key == "range" || key == "inner" || key == "outer") {
            auto f = parse_float(value, what);
            if (!f) return f.error();
            if (*f < 0) return Error{what + ": must not be negative"};
            if (key == "intensity") light.intensity = *f;
            if (key == "range") light.range = *f;
            if (key == "inner") light.inner_cone = glm::radians(*f);
            if (key == "outer") light.outer_cone = glm::radians(*f);
        } else {
            return Error{"--light '" + text + "': unknown key '" + key +
                         "' (pos, dir, color, intensity, range, inner, outer)"};
        }
    }
    // Scaled by its largest component before normalising, so that directions such as
    // 1e30,0,0 or 1e-30,0,0 (whose squared length overflows or underflows) stay unit length.
    const glm::vec3& d = light.direction;
    const float largest = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    if (light.type != LightType::point && (!has_direction || largest == 0.0f))
        return Error{"--light '" + text + "': needs dir=X,Y,Z (non-zero)"};
    if (light.type != LightType::directional && !has_position)
        return Error{"--light '" + text + "': needs pos=X,Y,Z"};
    if (light.type == LightType::spot && !(light.inner_cone < light.outer_cone && light.outer_cone <= glm::radians(90.0f)))
        return Error{"--light '" + text + "': needs 0 <= inner < outer <= 90 degrees"};
    if (light.type != LightType::point) light.direction = glm::normalize(light.direction / largest);
    return light;
}

}  // namespace facet
