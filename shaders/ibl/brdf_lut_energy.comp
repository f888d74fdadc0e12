#version 460
// Third LUT channel: the average directional albedo of the single-scattering lobe for
// F0 = 1, E_avg(r) = 2 * integral_0^1 E(mu) mu dmu with E = A + B (Kulla and Conty 2017),
// by the midpoint rule over the LUT's own row. Used for multiscatter energy compensation.
layout(local_size_x = 64) in;
layout(binding = 0, rgba32f) uniform image2D lut;

void main() {
    ivec2 size = imageSize(lut);
    int row = int(gl_GlobalInvocationID.x);
    if (row >= size.y) return;
    float sum = 0.0;
    for (int x = 0; x < size.x; ++x) {
        vec4 t = imageLoad(lut, ivec2(x, row));
        float mu = (float(x) + 0.5) / float(size.x);
        sum += (t.r + t.g) * mu;
    }
    float e_avg = 2.0 * sum / float(size.x);
    for (int x = 0; x < size.x; ++x) {
        vec4 t = imageLoad(lut, ivec2(x, row));
        imageStore(lut, ivec2(x, row), vec4(t.rg, e_avg, t.a));
    }
}
