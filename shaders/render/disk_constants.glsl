#ifndef FACET_DISK_CONSTANTS_GLSL
#define FACET_DISK_CONSTANTS_GLSL
// The disks extracted from the environment as constants of the pipeline: DISK_LIGHTS and
// FACET_DISK_LIGHT_0 .. 15, each a PackedLight constructor of constants
// (render/light_data.h, packed_light_literal; engine/render/forward_data.h,
// disk_light_defines), for the forward pass and the skybox: lavapipe loads a buffer read at a
// pixel's lanes one lane at a time, which cost 0.02x the frame per disk before any shading,
// where constants cost nothing and fold into the disk's arithmetic.
#include "render/packed_light.glsl"

#ifndef DISK_LIGHTS
#define DISK_LIGHTS 0
#endif
#ifndef FACET_DISK_LIGHT_0
#define FACET_DISK_LIGHT_0 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_1
#define FACET_DISK_LIGHT_1 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_2
#define FACET_DISK_LIGHT_2 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_3
#define FACET_DISK_LIGHT_3 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_4
#define FACET_DISK_LIGHT_4 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_5
#define FACET_DISK_LIGHT_5 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_6
#define FACET_DISK_LIGHT_6 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_7
#define FACET_DISK_LIGHT_7 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_8
#define FACET_DISK_LIGHT_8 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_9
#define FACET_DISK_LIGHT_9 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_10
#define FACET_DISK_LIGHT_10 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_11
#define FACET_DISK_LIGHT_11 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_12
#define FACET_DISK_LIGHT_12 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_13
#define FACET_DISK_LIGHT_13 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_14
#define FACET_DISK_LIGHT_14 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif
#ifndef FACET_DISK_LIGHT_15
#define FACET_DISK_LIGHT_15 PackedLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))
#endif

// FACET_DISK_POINTS: bit i set where disk i is shaded as a point (facet_disk_point_lobe: the
// material's lobe is much wider than the cap, render/lobe_disks.h).
#ifndef FACET_DISK_POINTS
#define FACET_DISK_POINTS 0
#endif

#endif
