#version 460
// The reflectance equation: punctual lights with the full BRDF, image-based lighting with
// the split sum, all composed by facet/shading.glsl (what a host's own shaders call too)
// for the BRDF model of the frame; this file reads the material and the frame's data.
// Variants (defines) carry only the features a material uses: HAS_BASE_COLOR_MAP,
// HAS_METALLIC_ROUGHNESS_MAP, HAS_NORMAL_MAP, HAS_OCCLUSION_MAP (and OCCLUSION_IN_METALLIC_ROUGHNESS:
// it is R of the metallic-roughness texture), HAS_EMISSIVE_MAP,
// ALPHA_OPAQUE (alpha written as 1), ALPHA_MASK, ALPHA_BLEND, DOUBLE_SIDED, MIRRORED (the
// instance's world matrix mirrors: its front faces wind clockwise), UNLIT (points, lines and
// KHR_materials_unlit: base colour x vertex colour + emissive, which the loader clears for
// unlit materials), CLEARCOAT (KHR_materials_clearcoat's layer) and its HAS_CLEARCOAT_MAP,
// HAS_CLEARCOAT_ROUGHNESS_MAP, HAS_CLEARCOAT_NORMAL_MAP, HAS_SPECULAR_MAP and HAS_SPECULAR_COLOR_MAP
// (KHR_materials_specular's textures), FACET_IRIDESCENCE (KHR_materials_iridescence's film) and
// its HAS_IRIDESCENCE_MAP, HAS_IRIDESCENCE_THICKNESS_MAP, FACET_ANISOTROPY (KHR_materials_anisotropy)
// and its HAS_ANISOTROPY_MAP, FACET_SHEEN (KHR_materials_sheen) and its HAS_SHEEN_COLOR_MAP,
// HAS_SHEEN_ROUGHNESS_MAP, FACET_TRANSMISSION (KHR_materials_transmission and _volume) and its
// HAS_TRANSMISSION_MAP, HAS_THICKNESS_MAP, <SLOT>_UV (a texture's coordinates: its uv set and
// KHR_texture_transform) and NORMAL_TANGENT_FRAME, USE_IBL, BRDF_THESIS (the thesis' model
// instead of glTF's), MULTISCATTER (energy compensation), DOMINANT_DIRECTION (bent specular
// lookup) and FACET_TWO_LOOKUPS (two fitted lookups instead of three: where every bending
// group a material reaches allows them, FrameSettings::two_lookup_groups), VIEW (what is written: render/views.glsl).
#include "facet/shading.glsl"
#include "render/forward_interface.glsl"
#include "render/views.glsl"

#ifndef VIEW
#define VIEW VIEW_FINAL
#endif
#include "render/disk_constants.glsl"

#ifdef BRDF_THESIS
const uint brdf_model = FACET_BRDF_THESIS;
#else
const uint brdf_model = FACET_BRDF_GLTF;
#endif

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
#if defined(HAS_NORMAL_MAP) || defined(HAS_CLEARCOAT_NORMAL_MAP) || defined(FACET_ANISOTROPY)
layout(location = 3) in vec4 in_tangent;
#endif
layout(location = 4) in vec4 in_color;
layout(location = 5) in vec2 in_uv1;

// Each texture's coordinates, <SLOT>_UV: TEXCOORD_0 unless the material's pipeline says
// otherwise (render/forward_pass.cpp: TEXCOORD_1, and KHR_texture_transform's matrix as a
// constant, (mat3x2(...) * vec3(in_uv1, 1.0))).
#ifndef BASE_COLOR_UV
#define BASE_COLOR_UV in_uv
#endif
#ifndef METALLIC_ROUGHNESS_UV
#define METALLIC_ROUGHNESS_UV in_uv
#endif
#ifndef NORMAL_UV
#define NORMAL_UV in_uv
#endif
#ifndef OCCLUSION_UV
#define OCCLUSION_UV in_uv
#endif
#ifndef EMISSIVE_UV
#define EMISSIVE_UV in_uv
#endif
#ifndef CLEARCOAT_UV
#define CLEARCOAT_UV in_uv
#endif
#ifndef CLEARCOAT_ROUGHNESS_UV
#define CLEARCOAT_ROUGHNESS_UV in_uv
#endif
#ifndef CLEARCOAT_NORMAL_UV
#define CLEARCOAT_NORMAL_UV in_uv
#endif
#ifndef SPECULAR_UV
#define SPECULAR_UV in_uv
#endif
#ifndef SPECULAR_COLOR_UV
#define SPECULAR_COLOR_UV in_uv
#endif
#ifndef IRIDESCENCE_UV
#define IRIDESCENCE_UV in_uv
#endif
#ifndef IRIDESCENCE_THICKNESS_UV
#define IRIDESCENCE_THICKNESS_UV in_uv
#endif
#ifndef ANISOTROPY_UV
#define ANISOTROPY_UV in_uv
#endif
#ifndef SHEEN_COLOR_UV
#define SHEEN_COLOR_UV in_uv
#endif
#ifndef SHEEN_ROUGHNESS_UV
#define SHEEN_ROUGHNESS_UV in_uv
#endif
#ifndef TRANSMISSION_UV
#define TRANSMISSION_UV in_uv
#endif
#ifndef THICKNESS_UV
#define THICKNESS_UV in_uv
#endif

layout(location = 0) out vec4 out_color;

// What the material gives at this fragment; the shading itself is facet/shading.glsl's.
struct Surface {
    FacetSurface shading;
    float alpha;
    vec3 emissive;
    float thickness;  // KHR_materials_volume, in the mesh's units (0: thin-walled)
};

Surface surface_at(MaterialData m) {
    vec4 base = m.base_color * in_color;
#ifdef HAS_BASE_COLOR_MAP
    base *= texture(base_color_map, BASE_COLOR_UV);
#endif
    float metallic = m.factors.x;
    float roughness = m.factors.y;
#ifdef HAS_METALLIC_ROUGHNESS_MAP
    vec4 mr = texture(metallic_roughness_map, METALLIC_ROUGHNESS_UV);
    roughness *= mr.g;
    metallic *= mr.b;
#endif
    float occlusion = m.extra.z;
#if defined(HAS_OCCLUSION_MAP) && defined(OCCLUSION_IN_METALLIC_ROUGHNESS)
    // The occlusion in R of the metallic-roughness texel already read (GpuScene packs the
    // two when they share coordinates and sampler): one fetch fewer.
    occlusion *= 1.0 + m.factors.w * (mr.r - 1.0);
#elif defined(HAS_OCCLUSION_MAP)
    occlusion *= 1.0 + m.factors.w * (texture(occlusion_map, OCCLUSION_UV).r - 1.0);
#endif
    Surface s;
    s.alpha = base.a;
    s.emissive = m.emissive_f0.rgb;
#ifdef HAS_EMISSIVE_MAP
    s.emissive *= texture(emissive_map, EMISSIVE_UV).rgb;
#endif
    vec3 n = normalize(in_normal);
#ifdef DOUBLE_SIDED
#ifdef MIRRORED
    if (gl_FrontFacing) n = -n;
#else
    if (!gl_FrontFacing) n = -n;
#endif
#endif
    vec3 geometric_n = n;
#if defined(HAS_NORMAL_MAP) || defined(HAS_CLEARCOAT_NORMAL_MAP) || defined(FACET_ANISOTROPY)
    // Tangent frame of the glTF specification: bitangent = cross(n, t) * w.
    vec3 t = in_tangent.xyz - n * dot(n, in_tangent.xyz);
    bool has_frame = dot(t, t) > 1e-12;
    t = has_frame ? normalize(t) : vec3(0.0);
    mat3 frame_tbn = mat3(t, cross(n, t) * (in_tangent.w < 0.0 ? -1.0 : 1.0), n);
#endif
#ifdef HAS_NORMAL_MAP
    if (has_frame) {
        vec3 tn = texture(normal_map, NORMAL_UV).xyz * 2.0 - 1.0;
        tn.xy *= m.factors.z;
#ifdef NORMAL_TANGENT_FRAME
        // The map's tangent axes are those of the transformed uvs (NORMAL_TANGENT_FRAME,
        // render/forward_pass.cpp's tangent_frame_literal).
        tn.xy = NORMAL_TANGENT_FRAME * tn.xy;
#endif
        n = normalize(frame_tbn * tn);
    }
#endif
    // KHR_materials_specular: its factors times its textures (A, RGB).
    float specular_factor = m.extra.y;
#ifdef HAS_SPECULAR_MAP
    specular_factor *= texture(specular_factor_map, SPECULAR_UV).a;
#endif
    vec3 specular_color = m.specular_color.rgb;
#ifdef HAS_SPECULAR_COLOR_MAP
    specular_color *= texture(specular_color_map, SPECULAR_COLOR_UV).rgb;
#endif
    s.shading = facet_surface(brdf_model, n, base.rgb, clamp(metallic, 0.0, 1.0), clamp(roughness, 0.0, 1.0), m.emissive_f0.a,
                              specular_factor, occlusion);
    facet_surface_specular_color(s.shading, specular_color);
#ifdef CLEARCOAT
    // The layer: its factors times its textures (R, G), its normal the geometry's unless it
    // has a normal map of its own (the extension: not the surface's normal map).
    float coat = m.clearcoat.x, coat_roughness = m.clearcoat.y;
#ifdef HAS_CLEARCOAT_MAP
    coat *= texture(clearcoat_map, CLEARCOAT_UV).r;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
    coat_roughness *= texture(clearcoat_roughness_map, CLEARCOAT_ROUGHNESS_UV).g;
#endif
    vec3 coat_n = geometric_n;
#ifdef HAS_CLEARCOAT_NORMAL_MAP
    if (has_frame) {
        vec3 tn = texture(clearcoat_normal_map, CLEARCOAT_NORMAL_UV).xyz * 2.0 - 1.0;
        tn.xy *= m.clearcoat.z;
#ifdef CLEARCOAT_NORMAL_TANGENT_FRAME
        tn.xy = CLEARCOAT_NORMAL_TANGENT_FRAME * tn.xy;
#endif
        coat_n = normalize(frame_tbn * tn);
    }
#endif
    facet_surface_clearcoat(s.shading, clamp(coat, 0.0, 1.0), clamp(coat_roughness, 0.0, 1.0), coat_n);
#endif
#ifdef FACET_IRIDESCENCE
    // The film: its factor times R of its texture; its thickness the maximum, or from the
    // minimum to the maximum by G of its thickness texture.
    float film = m.iridescence.x, thickness = m.iridescence.w;
#ifdef HAS_IRIDESCENCE_MAP
    film *= texture(iridescence_map, IRIDESCENCE_UV).r;
#endif
#ifdef HAS_IRIDESCENCE_THICKNESS_MAP
    thickness = mix(m.iridescence.z, m.iridescence.w, texture(iridescence_thickness_map, IRIDESCENCE_THICKNESS_UV).g);
#endif
    facet_surface_iridescence(s.shading, clamp(film, 0.0, 1.0), m.iridescence.y, max(thickness, 0.0));
#endif
#ifdef FACET_ANISOTROPY
    // The stretch: its direction in tangent space (cos, sin) of the rotation, or the map's RG
    // (from [0, 1] to [-1, 1]) turned by it; its strength times the map's B.
    float strength = m.anisotropy.x;
    vec2 direction = vec2(cos(m.anisotropy.y), sin(m.anisotropy.y));
#ifdef HAS_ANISOTROPY_MAP
    vec3 am = texture(anisotropy_map, ANISOTROPY_UV).rgb;
    vec2 d = am.rg * 2.0 - 1.0;
    d = dot(d, d) > 1e-12 ? normalize(d) : vec2(1.0, 0.0);
    direction = mat2(direction.x, direction.y, -direction.y, direction.x) * d;
    strength *= am.b;
#endif
    if (has_frame) facet_surface_anisotropy(s.shading, clamp(strength, 0.0, 1.0), frame_tbn * vec3(direction, 0.0));
#endif
#ifdef FACET_SHEEN
    // The sheen: its colour times RGB of its colour texture, its roughness times A of its own.
    vec3 sheen_color = m.sheen.rgb;
    float sheen_roughness = m.sheen.a;
#ifdef HAS_SHEEN_COLOR_MAP
    sheen_color *= texture(sheen_color_map, SHEEN_COLOR_UV).rgb;
#endif
#ifdef HAS_SHEEN_ROUGHNESS_MAP
    sheen_roughness *= texture(sheen_roughness_map, SHEEN_ROUGHNESS_UV).a;
#endif
    facet_surface_sheen(s.shading, clamp(sheen_color, 0.0, 1.0), clamp(sheen_roughness, 0.0, 1.0));
#endif
    s.thickness = 0.0;
#ifdef FACET_TRANSMISSION
    // The transmission: its factor times R of its texture; the volume's thickness times G of its own.
    float transmission = m.transmission.x;
#ifdef HAS_TRANSMISSION_MAP
    transmission *= texture(transmission_map, TRANSMISSION_UV).r;
#endif
    facet_surface_transmission(s.shading, clamp(transmission, 0.0, 1.0), facet_ior_from_f0(m.emissive_f0.a));
    s.thickness = m.transmission.y;
#ifdef HAS_THICKNESS_MAP
    s.thickness *= texture(thickness_map, THICKNESS_UV).g;
#endif
#endif
    return s;
}

#ifdef FACET_SURFACE_VIEW
// A view of the surface itself (FACET_SURFACE_VIEW: engine/render/views.cpp's view_of_surface
// decides which): what the material gives, no light.
vec4 surface_view(Surface surface) {
    FacetSurface s = surface.shading;
#if VIEW == VIEW_NORMAL
    return vec4(s.n, 1.0);
#elif VIEW == VIEW_POSITION
    return vec4(in_world, 1.0);
#elif VIEW == VIEW_BASECOLOR
    return vec4(s.albedo, surface.alpha);
#elif VIEW == VIEW_METALLIC
#ifdef UNLIT
    return vec4(vec3(s.metallic), 0.0);  // alpha 0 marks an unlit surface (the reference mode copies it)
#else
    return vec4(vec3(s.metallic), 1.0);
#endif
#elif VIEW == VIEW_ROUGHNESS
    return vec4(vec3(s.roughness), 1.0);
#elif VIEW == VIEW_OCCLUSION
    return vec4(vec3(s.occlusion), 1.0);
#elif VIEW == VIEW_EMISSIVE
    return vec4(surface.emissive, 1.0);
#elif VIEW == VIEW_SPECULAR_F0
    return vec4(s.dielectric_f0, s.specular_factor);
#elif VIEW == VIEW_CLEARCOAT
    return vec4(s.clearcoat, s.clearcoat_roughness, 0.0, 1.0);
#elif VIEW == VIEW_CLEARCOAT_NORMAL
    return vec4(s.clearcoat_n, 1.0);
#elif VIEW == VIEW_IRIDESCENCE
    return vec4(s.iridescence, s.iridescence_ior, s.iridescence_thickness, 1.0);
#elif VIEW == VIEW_ANISOTROPY
    return vec4(s.anisotropy_t, s.anisotropy);
#elif VIEW == VIEW_SHEEN
    return vec4(s.sheen_color, s.sheen_roughness);
#elif VIEW == VIEW_TRANSMISSION
    return vec4(s.transmission, s.transmission_roughness, surface.thickness, 1.0);
#else
#error "FACET_SURFACE_VIEW for a view surface_view does not write (engine/render/views.cpp view_of_surface)"
#endif
}
#endif

void main() {
    MaterialData m = material;
#ifdef FLAT_FLOOR
    // The rasterizer's floor (FrameSettings::flat_floor): the base colour factor, nothing read
    // or lit.
    out_color = vec4(m.base_color.rgb, 1.0);
    return;
#endif
    Surface surface = surface_at(m);
    FacetSurface s = surface.shading;
#ifdef ALPHA_MASK
    if (surface.alpha < m.extra.x) discard;
    surface.alpha = 1.0;  // what passes the cutoff is opaque
#endif
#ifdef ALPHA_OPAQUE
    surface.alpha = 1.0;  // glTF: OPAQUE ignores the alpha channel entirely
#endif
#if defined(UNLIT) && VIEW == VIEW_FINAL
    // Points and lines have no surface to light: base colour (vertex colour included) and
    // emission, as other glTF viewers draw them.
    out_color = vec4(s.albedo + surface.emissive, surface.alpha);
    return;
#endif
#ifdef FACET_SURFACE_VIEW
    // Written before any light is looked at: a pipeline of a few thousand words of SPIR-V
    // instead of the lit one's 20000 (lavapipe builds it in ~7 ms instead of ~90).
    out_color = surface_view(surface);
#else
    vec3 v = normalize(frame.camera_position.xyz - in_world);
    vec3 n = s.n;
    float NdotV = clamp(dot(n, v), 0.0, 1.0);

    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
#ifdef USE_IBL
    float lut_roughness = s.roughness;
#ifdef FACET_ANISOTROPY
    // The stretched lobe's albedo: the glTF model's LUT at the roughness that masks v alike.
    if (s.anisotropy > 0.0 && s.brdf == FACET_BRDF_GLTF) lut_roughness = facet_anisotropic_view_roughness(s, v);
#endif
    vec4 lut = facet_brdf_lut(brdf_lut, NdotV, lut_roughness);
    // frame.ibl.y is the highest specular level (roughness 1).
    float specular_levels = frame.ibl.y + 1.0;
#endif
#if defined(MULTISCATTER) && defined(USE_IBL)
    vec3 light_energy = facet_multiscatter_light_energy(s.F0, lut);
#else
    vec3 light_energy = vec3(1.0);
#endif
#ifdef FACET_TRANSMISSION
    // What lies behind: the view ray leaves the surface at `exit`, refracted by the index
    // through a volume's thickness (world units: the instance's mean scale), the point
    // itself where it is thin-walled; its light is attenuated along the way.
    mat4 world = instance.world;
    float path = max(surface.thickness, 0.0) * (length(world[0].xyz) + length(world[1].xyz) + length(world[2].xyz)) / 3.0;
    vec3 refracted = refract(-v, n, 1.0 / facet_ior_from_f0(m.emissive_f0.a));
    vec3 exit = in_world + (path > 0.0 && dot(refracted, refracted) > 0.0 ? normalize(refracted) * path : vec3(0.0));
    vec3 through_direction = normalize(exit - frame.camera_position.xyz);
    vec3 transmittance = facet_volume_transmittance(m.attenuation.rgb, m.transmission.z, path);
    vec3 through = vec3(0.0);  // the transmitted light
#endif
    // The component views show the terms for the first light, or for the mirror
    // direction (h = n) when the scene has no light.
    vec3 view_l = reflect(-v, n);
    bool view_punctual = false;
    for (uint i = 0u; i < frame.counts.x; ++i) {
        vec3 l;
        vec3 incident = facet_punctual_incidence(unpack_punctual_light(lights[i]), in_world, l);
        if (i == 0u) {
            view_l = l;
            view_punctual = true;
        }
        vec3 light_diffuse, light_specular;
        facet_reflect_light(s, v, NdotV, l, incident, true, light_diffuse, light_specular);
#ifdef FACET_TRANSMISSION
        if (dot(n, l) < 0.0) light_diffuse *= transmittance;  // light from behind crosses the volume
#endif
        diffuse += light_diffuse;
        specular += light_energy * light_specular;
    }
    vec3 irradiance = vec3(0.0), prefiltered = vec3(0.0);
#ifdef USE_IBL
#ifdef DOMINANT_DIRECTION
    const bool dominant_direction = true;
#else
    const bool dominant_direction = false;
#endif
    // The lookups of the prefiltered cube, made once: the environment reads them, and the
    // disks' specular counts for the share of them read from levels without the lights.
#if defined(DOMINANT_DIRECTION) && defined(FACET_TWO_LOOKUPS)
    // Two lookups where the material's groups allow them (render/forward_pass.cpp).
    FacetSpecularLookups lookups = facet_two_specular_lookups(s, v, NdotV, specular_levels, specular_lobes);
#else
    FacetSpecularLookups lookups = facet_specular_lookups(s, v, NdotV, specular_levels, specular_lobes, dominant_direction);
#endif
    float disk_specular_weight = facet_disk_specular_weight(lookups, frame.ibl.z);
    // The DISK_LIGHTS disks, constants of the pipeline: their specular (and what passes
    // through a transmitting surface). Their diffuse is the irradiance cube's, baked from the
    // whole environment (ibl/ibl_bake.h, SpecularSplit): the diffuse lobe integrates them
    // exactly there (each disk's closed-form diffuse cost ~1 ms of a 1280x720 frame on lavapipe);
    // what that leaves is the diffuse weight's (1 - F) taken as its mean over the hemisphere
    // instead of at each disk's half vector (the shared environments' worst groups moved by
    // under 0.2 points). A sheen's lobe and an iridescent film's F change too much across
    // the hemisphere for that (the sun sky's groups read 9-37% off): such surfaces shade each
    // disk's diffuse and sheen in closed form, the disks' irradiance taken out of the cube's
    // (FACET_DISK_DIFFUSE).
#if defined(FACET_SHEEN) || defined(FACET_IRIDESCENCE)
#define FACET_DISK_DIFFUSE
#endif
    vec3 disk_specular_sum = vec3(0.0), disk_coat_sum = vec3(0.0);
    vec3 disk_through_sum = vec3(0.0), disk_diffuse_sum = vec3(0.0), disk_irradiance_sum = vec3(0.0);
#ifdef FACET_TRANSMISSION
#define FACET_DISK_THROUGH(disk) disk_through = facet_disk_transmission(s, v, NdotV, disk);
#else
#define FACET_DISK_THROUGH(disk)
#endif
#ifdef CLEARCOAT
#define FACET_DISK_CLEARCOAT(disk)                                                                                 \
    float below;                                                                                                   \
    vec3 coat_specular;                                                                                            \
    facet_disk_clearcoat(s, v, disk, below, coat_specular);                                                        \
    disk_diffuse *= below;                                                                                         \
    disk_specular *= below;                                                                                        \
    disk_through *= below;                                                                                         \
    disk_coat_sum += coat_specular;
#else
#define FACET_DISK_CLEARCOAT(disk)
#endif
#ifdef FACET_SHEEN
    // The sheen's lobe at the cap's centre times its solid angle (facet/sheen.glsl), summed
    // with the diffuse: like it, it is not read from the prefiltered levels.
#define FACET_DISK_SHEEN(disk)                                                                                     \
    vec3 disk_sheen = facet_sheen_light(s, v, NdotV, disk.direction, disk.radiance * disk.solid_angle,            \
                                        disk_diffuse, disk_specular);                                              \
    disk_through *= facet_sheen_scaling(s, NdotV);                                                                 \
    disk_diffuse += disk_sheen;
#else
#define FACET_DISK_SHEEN(disk)
#endif
#ifdef FACET_DISK_DIFFUSE
#define FACET_DISK_DIFFUSE_SUM(disk)                                                                               \
    disk_diffuse_sum += disk_diffuse;                                                                              \
    disk_irradiance_sum += facet_disk_irradiance(s.n, disk) / PI * disk.radiance;
#else
#define FACET_DISK_DIFFUSE_SUM(disk)
#endif
#define FACET_DISK(i)                                                                                              \
    if (i < DISK_LIGHTS) {                                                                                         \
        vec3 disk_diffuse, disk_specular, disk_through = vec3(0.0);                                                \
        FacetDiskLight disk = unpack_disk_light(FACET_DISK_LIGHT_##i);                                             \
        facet_disk_light(s, v, NdotV, disk, ((FACET_DISK_POINTS >> i) & 1) != 0, disk_diffuse, disk_specular);     \
        FACET_DISK_THROUGH(disk)                                                                                   \
        FACET_DISK_SHEEN(disk)                                                                                     \
        FACET_DISK_CLEARCOAT(disk)                                                                                 \
        FACET_DISK_DIFFUSE_SUM(disk)                                                                               \
        disk_specular_sum += disk_specular;                                                                        \
        disk_through_sum += disk_through;                                                                          \
    }
    FACET_DISK(0) FACET_DISK(1) FACET_DISK(2) FACET_DISK(3) FACET_DISK(4) FACET_DISK(5) FACET_DISK(6) FACET_DISK(7)
    FACET_DISK(8) FACET_DISK(9) FACET_DISK(10) FACET_DISK(11) FACET_DISK(12) FACET_DISK(13) FACET_DISK(14) FACET_DISK(15)
#undef FACET_DISK
#undef FACET_DISK_CLEARCOAT
#undef FACET_DISK_SHEEN
#undef FACET_DISK_THROUGH
#undef FACET_DISK_DIFFUSE_SUM
    specular += disk_specular_sum * disk_specular_weight * frame.ibl.x * s.occlusion;
#ifdef CLEARCOAT
    // The layer's own share of the disks: by its roughness's lookup (the levels below
    // frame.ibl.z still hold the lights).
    specular += disk_coat_sum * facet_disk_specular_weight(s.clearcoat_roughness, specular_levels, frame.ibl.z) *
                frame.ibl.x * s.occlusion;
#endif
#ifdef MULTISCATTER
    const bool multiscatter = true;
#else
    const bool multiscatter = false;
#endif
    vec3 cube_irradiance = texture(irradiance_map, s.n).rgb;
#ifdef FACET_DISK_DIFFUSE
    diffuse += disk_diffuse_sum * frame.ibl.x * s.occlusion;
    vec3 env_irradiance = max(cube_irradiance - disk_irradiance_sum, 0.0) * frame.ibl.x;
#else
    vec3 env_irradiance = cube_irradiance * frame.ibl.x;
#endif
    FacetEnvironmentLight env = facet_environment_light(s, v, NdotV, lut, env_irradiance, specular_map, frame.ibl.x,
                                                        multiscatter, lookups);
#ifdef FACET_SHEEN
    vec3 env_sheen = facet_environment_sheen(s, NdotV, env.irradiance, env.diffuse, env.specular);
    env.specular += env_sheen;
#endif
    facet_environment_clearcoat(s, v, lut, brdf_lut, specular_map, specular_levels, frame.ibl.x, env);
#ifdef FACET_TRANSMISSION
    // The environment behind along the exit point's view ray, at the transmitted lobe's
    // roughness, and the disks behind (the levels below frame.ibl.z still hold them).
    float through_lod = facet_specular_lod(s.transmission_roughness, specular_levels);
    vec3 through_albedo = facet_transmission_albedo(s, facet_brdf_lut(brdf_lut, NdotV, s.transmission_roughness));
    through = s.transmission * s.albedo * through_albedo * textureLod(specular_map, through_direction, through_lod).rgb *
                  frame.ibl.x +
              disk_through_sum * facet_disk_specular_weight(s.transmission_roughness, specular_levels, frame.ibl.z) *
                  frame.ibl.x;
#endif
    diffuse += env.diffuse;
    specular += env.specular;
    irradiance = cube_irradiance * frame.ibl.x;  // the disks' included
    prefiltered = env.prefiltered;
#endif

#ifdef FACET_TRANSMISSION
    {
#ifndef USE_IBL
        vec3 F_n, through_albedo;
        facet_fresnel(s, NdotV, F_n, through_albedo);  // no LUT: the weight at n.v
#endif
#if VIEW == VIEW_FINAL
        // The opaque scene behind, where it covers the exit point (the transmission
        // background, mipmapped: a blur as wide as the lobe's, log2(width) x its roughness,
        // the Khronos glTF sample viewer's choice), over the environment.
        vec4 clip = frame.view_projection * vec4(exit, 1.0);
        if (clip.w > 0.0) {
            vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
            float lod = log2(float(textureSize(transmission_background, 0).x)) * s.transmission_roughness;
            vec4 scene = textureLod(transmission_background, uv, lod);
            through = s.transmission * s.albedo * through_albedo * scene.rgb + (1.0 - scene.a) * through;
        }
#endif
        // A sheen and a clear coat over the surface dim it as they dim the base's light.
#ifdef FACET_SHEEN
        through *= facet_sheen_scaling(s, NdotV);
#endif
        through *= (1.0 - facet_clearcoat_fresnel(s, NdotV)) * transmittance;
        diffuse += through;
    }
#endif
#ifdef UNLIT
    // An unlit surface's colour is its base colour: no lobe, no lookup, no BRDF term (the
    // component views show it as diffuse, the others 0).
    diffuse = s.albedo;
    specular = irradiance = prefiltered = vec3(0.0);
#endif
#if VIEW == VIEW_FINAL
    out_color = vec4(diffuse + specular + surface.emissive, surface.alpha);
#elif VIEW == VIEW_DIFFUSE
    out_color = vec4(diffuse, 1.0);
#elif VIEW == VIEW_SPECULAR
    out_color = vec4(specular, 1.0);
#elif VIEW == VIEW_IRRADIANCE
    out_color = vec4(irradiance, 1.0);
#elif VIEW == VIEW_PREFILTERED
    out_color = vec4(prefiltered, 1.0);
#elif defined(UNLIT)
    out_color = vec4(0.0, 0.0, 0.0, 1.0);  // D, F, G: no BRDF
#else
    vec3 h = normalize(v + view_l);
    float NdotL = clamp(dot(n, view_l), 0.0, 1.0);
#if VIEW == VIEW_D
    out_color = vec4(vec3(D_GGX(clamp(dot(n, h), 0.0, 1.0), s.roughness)), 1.0);
#elif VIEW == VIEW_F
    vec3 F, kd;
    facet_fresnel(s, clamp(dot(h, v), 0.0, 1.0), F, kd);
    out_color = vec4(F, 1.0);
#elif VIEW == VIEW_G
    out_color = vec4(vec3(facet_geometry(s, NdotV, NdotL, view_punctual)), 1.0);
#endif
#endif
#endif  // FACET_SURFACE_VIEW
}
