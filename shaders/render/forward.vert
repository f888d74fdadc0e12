#version 460
// The thesis' vertex stage: object -> world position, normal (and tangent for normal
// maps), uv sets and vertex colour; clip position from the camera's view-projection.
// POINTS: point primitives, one pixel each.
#include "render/forward_interface.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_color;
layout(location = 5) in vec2 in_uv1;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
#if defined(HAS_NORMAL_MAP) || defined(HAS_CLEARCOAT_NORMAL_MAP) || defined(FACET_ANISOTROPY)
layout(location = 3) out vec4 out_tangent;
#endif
layout(location = 4) out vec4 out_color;
layout(location = 5) out vec2 out_uv1;

void main() {
    vec4 world = instance.world * vec4(in_position, 1.0);
    out_world = world.xyz;
    out_normal = mat3(instance.normal_matrix) * in_normal;
    out_uv = in_uv;
    out_uv1 = in_uv1;
    out_color = in_color;
#if defined(HAS_NORMAL_MAP) || defined(HAS_CLEARCOAT_NORMAL_MAP) || defined(FACET_ANISOTROPY)
    // A mirroring world matrix turns cross(n, t) around: the handedness turns with it.
    float mirrored = determinant(mat3(instance.world)) < 0.0 ? -1.0 : 1.0;
    out_tangent = vec4(mat3(instance.world) * in_tangent.xyz, in_tangent.w * mirrored);
#endif
#ifdef POINTS
    gl_PointSize = 1.0;
#endif
    gl_Position = frame.view_projection * world;
}
