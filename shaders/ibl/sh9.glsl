#ifndef FACET_SH9_GLSL
#define FACET_SH9_GLSL
// Real spherical harmonics up to band 2 (9 functions) and the clamped-cosine kernel's
// band factors (Ramamoorthi and Hanrahan 2001, "An Efficient Representation for
// Irradiance Environment Maps": A0 = pi, A1 = 2 pi / 3, A2 = pi / 4).
#include "facet/shared_constants.h"

const float SH9_BAND_FACTOR[3] = float[](facet_pi, 2.0 * facet_pi / 3.0, facet_pi / 4.0);

void sh9_basis(vec3 d, out float y[9]) {
    y[0] = 0.282094792;
    y[1] = 0.488602512 * d.y;
    y[2] = 0.488602512 * d.z;
    y[3] = 0.488602512 * d.x;
    y[4] = 1.092548431 * d.x * d.y;
    y[5] = 1.092548431 * d.y * d.z;
    y[6] = 0.315391565 * (3.0 * d.z * d.z - 1.0);
    y[7] = 1.092548431 * d.x * d.z;
    y[8] = 0.546274215 * (d.x * d.x - d.y * d.y);
}

int sh9_band(int i) { return i == 0 ? 0 : (i < 4 ? 1 : 2); }

// Hanning-type window of band l, (1 + cos(pi l / (2 h))) / 2 (Sloan 2008, "Stupid
// Spherical Harmonics Tricks"); h = 0: no window.
float sh9_window(int l, float h) {
    return h > 0.0 ? 0.5 * (1.0 + cos(facet_pi * float(l) / (2.0 * h))) : 1.0;
}

#endif
