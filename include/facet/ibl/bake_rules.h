#pragma once
// Every rule that couples a bake to the frame that samples it, in one place, so that the
// bake and the forward pass cannot disagree: what a scene needs baked, the specular level
// where extracted lights take over (FrameSettings::environment_light_level must equal
// it), the lookup lod of a roughness, the method-domain warnings and the bake key.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <facet/ibl/bake_settings.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/ibl/light_extraction.h>
#include <facet/scene/scene_needs.h>

namespace facet {

// The bake a scene needs, from what was requested: no irradiance when every surface is a
// pure metal (unless multiscatter compensation, which reads it, is on), and no specular
// level below the one a lookup at the scene's smallest roughness reads.
IblSettings ibl_settings_for_scene(IblSettings requested, const SceneNeeds& needs, bool multiscatter);

// With extracted lights, the first specular level without them: level 0 (the mirror) keeps
// them, so that mirrors show windows and softboxes in their true shapes, which the disks only
// approximate; every rougher level comes from the map without them and the disks take over.
// (Keeping them in the levels whose lobe, alpha = roughness^2, is narrower than the widest
// light's radius, as before: with the fitted lookups (shading.glsl) that made metals of
// roughness 1/6 to 1/3 worse under every shared environment with wide lights, e.g. the worst
// group under empty_warehouse_01 7.4% against 3.7% and under studio_small_03 22% against 9%.)
// 0 without lights. The frame's FrameSettings::environment_light_level must be this value
// for the bake it samples.
uint32_t light_split_level(std::span<const DiskLight> lights, uint32_t specular_levels);

// The level of the prefiltered cube holding a roughness (level m = roughness m / (levels - 1)).
inline float specular_lookup_lod(float roughness_value, uint32_t specular_levels) {
    return roughness_value * float(specular_levels > 1 ? specular_levels - 1 : 0);
}

// One sentence per method used outside its domain (ibl/method_domain.h) for this
// environment. Methods whose domain depends on the content
// (method_warnings_read_content) need `analysed`'s texels: a procedural sky must have been
// rendered into them (materialize_environment), else their list is empty; the rest need
// only a sky's parameters.
std::vector<std::string> bake_warnings(const EnvironmentSource& analysed, const IblSettings& resolved);

// Everything that decides the bake's outputs, hashed (16 hex digits): equal keys mean
// equal bakes (the library version, the input's content hash and size, every setting
// as resolved). For caching bakes and skipping a bake that is up to date.
std::string bake_key(const EnvironmentSource& source, const BakeSettings& resolved);

}  // namespace facet
