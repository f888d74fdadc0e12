#pragma once
// Numbers written into shader source as constants of a pipeline (the forward pass's disks,
// texture transforms): every float to round-trip (%.9g), always a float literal.
#include <cstdio>
#include <string>

namespace facet {

inline std::string glsl_float_literal(double v) {
    char number[32];
    std::snprintf(number, sizeof number, "%.9g", v);
    std::string n = number;
    if (n.find_first_of(".eEn") == std::string::npos) n += ".0";  // 1 -> 1.0
    return n;
}

}  // namespace facet
