#version 460
// Split-sum BRDF LUT (Karis 2013): for NdotV = (x + 0.5) / W and roughness = (y + 0.5) / H,
// R = A and G = B with  integral f_spec cos = F0 * A + B, the integral over the GGX lobe
// estimated with N Hammersley samples of h ~ D(h) (n.h). Visibility of the model: the
// height-correlated Smith term (glTF) or Smith with Schlick-GGX k = r^2 / 2 (the thesis).
// Alpha: W = the cosine-weighted mean of (1 - v.h)^5 over the hemisphere (the diffuse lobe's
// Fresnel weight, independent of roughness), by N cosine-distributed Hammersley directions.
#include "ibl/sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2D lut;

layout(push_constant) uniform Params {
    uint sample_count;
    uint brdf;  // 0: glTF (V_SmithGGXCorrelated); 1: the thesis (G_Smith with k_ibl)
} params;

void main() {
    ivec2 size = imageSize(lut);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, size))) return;
    float NdotV = (float(texel.x) + 0.5) / float(size.x);
    float roughness = (float(texel.y) + 0.5) / float(size.y);
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float alpha = roughness * roughness;
    float k = k_ibl(roughness);

    float A = 0.0, B = 0.0;
    for (uint i = 0u; i < params.sample_count; ++i) {
        // With u the GGX CDF in theta_h, the weight below grows like (1 - u)^(-1/2) towards
        // the horizon, which gives grazing views (n.v -> 0) a heavy-tailed estimator. The
        // substitution u = 1 - s^2 (du = 2 s ds) removes the singularity.
        vec2 xi = hammersley(i, params.sample_count);
        float s = xi.x;
        vec3 H = importance_sample_ggx_tangent(vec2(1.0 - s * s, xi.y), roughness);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = L.z;
        if (NdotL <= 0.0 || VdotH <= 0.0) continue;
        float NdotH = H.z;
        // f cos / pdf with pdf(l) = D (n.h) / (4 v.h): the D and F terms cancel out.
        float G_Vis = params.brdf == 0u
                          ? 4.0 * V_SmithGGXCorrelated(NdotV, NdotL, alpha) * NdotL * VdotH / NdotH
                          : G_Smith(NdotV, NdotL, k) * VdotH / (NdotH * NdotV);
        G_Vis *= 2.0 * s;
        float Fc = pow(1.0 - VdotH, 5.0);
        A += (1.0 - Fc) * G_Vis;
        B += Fc * G_Vis;
    }
    A /= float(params.sample_count);
    B /= float(params.sample_count);
    float W = 0.0;
    for (uint i = 0u; i < params.sample_count; ++i) {
        vec2 xi = hammersley(i, params.sample_count);
        float r = sqrt(xi.x), phi = 2.0 * PI * xi.y;
        vec3 L = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - xi.x)));
        W += pow(clamp(1.0 - dot(V, normalize(V + L)), 0.0, 1.0), 5.0);
    }
    W /= float(params.sample_count);
    imageStore(lut, texel, vec4(A, B, 0.0, W));
}
