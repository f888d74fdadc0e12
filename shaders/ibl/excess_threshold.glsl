#ifndef FACET_EXCESS_THRESHOLD_GLSL
#define FACET_EXCESS_THRESHOLD_GLSL
// The hybrid split's threshold T = factor x the environment's mean luminance (the mean of
// the 1 x 1 mip's six faces, read from `top`, which the including shader declares). Read
// once per workgroup: six storage-image reads per texel were three quarters of the
// split's time on lavapipe. It has a barrier: every invocation calls it, before any return.
#include "facet/shared_constants.h"

shared float excess_face_luminance[6];

float excess_threshold(float factor) {
    if (gl_LocalInvocationIndex < 6u)
        excess_face_luminance[gl_LocalInvocationIndex] =
            facet_luminance(imageLoad(top, ivec3(0, 0, int(gl_LocalInvocationIndex))).rgb);
    barrier();
    float mean = 0.0;
    for (int f = 0; f < 6; ++f) mean += excess_face_luminance[f];
    mean /= 6.0;
    // A black environment has no excess; nor has one whose mean is not a finite number.
    return mean > 0.0 && !isinf(mean) ? factor * mean : 3.4e38;
}

#endif
