#version 460
// Test kernel: evaluates the shared BRDF terms for inputs from a buffer, so the tests can
// check them against an independent CPU reference.
#include "facet/brdf.glsl"

layout(local_size_x = 64) in;

struct BrdfInput {
    float NdotV, NdotL, NdotH, VdotH;
    float roughness, f0, pad0, pad1;
};
struct BrdfOutput {
    float D, F, F_rough, G_direct;
    float G_ibl, V_correlated, k_direct_value, k_ibl_value;
};

layout(std430, binding = 0) readonly buffer Inputs { BrdfInput inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { BrdfOutput outputs[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= inputs.length()) return;
    BrdfInput x = inputs[i];
    BrdfOutput o;
    o.D = D_GGX(x.NdotH, x.roughness);
    o.F = F_Schlick(x.VdotH, vec3(x.f0)).x;
    o.F_rough = F_SchlickRoughness(x.NdotV, vec3(x.f0), x.roughness).x;
    o.G_direct = G_Smith(x.NdotV, x.NdotL, k_direct(x.roughness));
    o.G_ibl = G_Smith(x.NdotV, x.NdotL, k_ibl(x.roughness));
    o.V_correlated = V_SmithGGXCorrelated(x.NdotV, x.NdotL, x.roughness * x.roughness);
    o.k_direct_value = k_direct(x.roughness);
    o.k_ibl_value = k_ibl(x.roughness);
    outputs[i] = o;
}
