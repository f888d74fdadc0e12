#ifndef FACET_EXCESS_THRESHOLD_GLSL
#define FACET_EXCESS_THRESHOLD_GLSL
// The hybrid split's threshold T = factor x the environment's mean luminance (the mean of
// the 1 x 1 mip's six faces, read from `top`, which the including shader declares).
// Shared by specular_excess.comp and specular_excess_equirect.comp.
#include "facet/shared_constants.h"

float excess_threshold(float factor) {
    float mean = 0.0;
    for (int f = 0; f < 6; ++f) mean += facet_luminance(imageLoad(top, ivec3(0, 0, f)).rgb);
    mean /= 6.0;
    // A black environment has no excess; nor has one whose mean is not a finite number.
    return mean > 0.0 && !isinf(mean) ? factor * mean : 3.4e38;
}

#endif
