#version 460
// The environment seen directly (the thesis' skybox): its cube sampled by direction.
layout(binding = 0) uniform samplerCube environment;

layout(push_constant) uniform Sky {
    mat4 inverse_view_projection;
    float lod;
    float intensity;
} sky;

layout(location = 0) in vec4 in_far;
layout(location = 0) out vec4 out_color;

void main() {
    out_color = vec4(textureLod(environment, normalize(in_far.xyz / in_far.w), sky.lod).rgb * sky.intensity, 1.0);
}
