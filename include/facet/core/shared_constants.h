#ifndef FACET_CORE_SHARED_CONSTANTS_H
#define FACET_CORE_SHARED_CONSTANTS_H
// Constants that the C++ code and the shaders both use, written once. This file is valid
// C++ and valid GLSL: C++ sees `inline constexpr double facet::pi`, GLSL sees
// `const float facet_pi` (a prefix, since GLSL has no namespaces and a host's shaders
// include this too). The shaders reach it as "facet/shared_constants.h": the build embeds
// it under that name and installs a copy beside the shading include
// (share/facet/shaders/facet/). tests/shared_constants_test.cpp checks both sides agree.

#ifdef __cplusplus
namespace facet {
#define FACET_SHARED_CONSTANT(name, value) inline constexpr double name = value;
#else
#define FACET_SHARED_CONSTANT(name, value) const float facet_##name = value;
#endif

FACET_SHARED_CONSTANT(pi, 3.14159265358979323846)

// Relative luminance of linear Rec. 709 (sRGB) primaries, Y = 0.2126 R + 0.7152 G +
// 0.0722 B (ITU-R BT.709-6, item 3.3): what every luminance-weighted choice uses
// (importance sampling, light extraction, noise estimates).
FACET_SHARED_CONSTANT(luminance_r, 0.2126)
FACET_SHARED_CONSTANT(luminance_g, 0.7152)
FACET_SHARED_CONSTANT(luminance_b, 0.0722)

#undef FACET_SHARED_CONSTANT

#ifdef __cplusplus
constexpr double luminance(double r, double g, double b) {
    return luminance_r * r + luminance_g * g + luminance_b * b;
}
}  // namespace facet
#else
float facet_luminance(vec3 rgb) {
    return dot(rgb, vec3(facet_luminance_r, facet_luminance_g, facet_luminance_b));
}
#endif

#endif
