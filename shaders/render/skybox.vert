#version 460
// A full-screen triangle; each pixel's world direction from the inverse of the
// camera's rotation-and-projection.
layout(push_constant) uniform Sky {
    mat4 inverse_view_projection;  // of the view without translation
    float lod;
    float intensity;
} sky;

// Homogeneous, undivided: it is linear in screen position, so interpolation is exact.
layout(location = 0) out vec4 out_far;

void main() {
    vec2 ndc = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2)) * 2.0 - 1.0;
    // Reversed Z: depth 0 is infinitely far.
    gl_Position = vec4(ndc, 0.0, 1.0);
    out_far = sky.inverse_view_projection * vec4(ndc, 1e-6, 1.0);
}
