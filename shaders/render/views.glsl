#ifndef FACET_VIEWS_GLSL
#define FACET_VIEWS_GLSL
// What the forward pass writes (engine/render/views.h keeps the same numbers).
#define VIEW_FINAL 0
#define VIEW_NORMAL 1
#define VIEW_POSITION 2
#define VIEW_BASECOLOR 3
#define VIEW_METALLIC 4
#define VIEW_ROUGHNESS 5
#define VIEW_OCCLUSION 6
#define VIEW_EMISSIVE 7
#define VIEW_D 8
#define VIEW_F 9
#define VIEW_G 10
#define VIEW_DIFFUSE 11
#define VIEW_SPECULAR 12
#define VIEW_IRRADIANCE 13
#define VIEW_PREFILTERED 14
#define VIEW_SPECULAR_F0 15
#define VIEW_CLEARCOAT 16
#define VIEW_CLEARCOAT_NORMAL 17
#define VIEW_IRIDESCENCE 18
#define VIEW_ANISOTROPY 19
#define VIEW_SHEEN 20
#define VIEW_TRANSMISSION 21
#endif
