#version 460
// A host engine's own material shader: its own bindings (set 2), shading with Facet's
// baked data through the installed "facet/shading.glsl" alone.
#extension GL_GOOGLE_include_directive : require
#include "facet/shading.glsl"
layout(set = 2, binding = 7) uniform samplerCube my_irradiance;
layout(set = 2, binding = 8) uniform samplerCube my_specular;
layout(set = 2, binding = 9) uniform sampler2D my_lut;
layout(set = 2, binding = 10) uniform sampler2D my_specular_lobes;  // facet/render/specular_lobes.h
layout(location = 0) in vec3 n_in;
layout(location = 1) in vec3 v_in;
layout(location = 0) out vec4 color;
void main() {
    FacetSurface s = facet_surface(FACET_BRDF_GLTF, normalize(n_in), vec3(0.8), 0.0, 0.5, 0.04, 1.0, 1.0);
    vec3 v = normalize(v_in);
    float NdotV = clamp(dot(s.n, v), 0.0, 1.0);
    vec4 lut = facet_brdf_lut(my_lut, NdotV, s.roughness);
    FacetEnvironmentLight env = facet_environment_light(s, v, NdotV, lut, my_irradiance, my_specular, 8.0, 1.0, false,
                                                        my_specular_lobes, true);
    FacetPunctualLight sun;
    sun.type = FACET_LIGHT_DIRECTIONAL;
    sun.direction = vec3(0.0, -1.0, 0.0);
    sun.intensity = vec3(3.0);
    vec3 l, d, sp;
    vec3 incident = facet_punctual_incidence(sun, vec3(0.0), l);
    facet_reflect_light(s, v, NdotV, l, incident, true, d, sp);
    color = vec4(env.diffuse + env.specular + d + sp, 1.0);
}
