#pragma once
// The material extensions that change the dielectric lobe's Fresnel, read into Material's
// dielectric_f0 and specular_factor (the shading's, the views' and the truth's inputs):
// - KHR_materials_ior: F0 = ((ior - 1) / (ior + 1))^2, outside ior 1; the schema allows
//   ior >= 1 and ior = 0 (F0 = 1, the specular-glossiness conversion);
// - KHR_materials_specular: dielectric F0 = min(F0(ior) x specularColor, 1) x specular and
//   F90 = specular (the extension's "Implementation"), with specular = specularFactor and
//   specularColorFactor into Material::specular_color; specularTexture and
//   specularColorTexture are not drawn: a warning each.
// Invalid values (ior in (0, 1), a factor out of its range) are errors naming the material.
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include <facet/scene/scene.h>

namespace facet::gltf_detail {

// KHR_texture_transform on a textureInfo: offset, rotation (radians, counter-clockwise) and
// scale into ref.uv_transform (translation x rotation x scale, the extension's matrix), and
// texCoord, when given, into ref.uv_set (0 or 1, else an error).
void read_texture_transform(const tinygltf::ExtensionMap& extensions, const std::string& where, TextureRef& ref);

// KHR_materials_unlit: out.unlit, with what lights the surface (metallic-roughness,
// normal, occlusion and emissive inputs) cleared: only base colour, alpha and vertex
// colour count (the extension's definition).
void read_unlit(const tinygltf::Material& material, Material& out);

// KHR_materials_clearcoat: clearcoatFactor and clearcoatRoughnessFactor into out.clearcoat
// and out.clearcoat_roughness (each in [0, 1], else an error), its three textures (with
// texCoord and KHR_texture_transform, as the core textures) and the normal texture's scale.
void read_clearcoat(const tinygltf::Model& model, const tinygltf::Material& material, const std::string& where,
                    Material& out);

// KHR_materials_iridescence: its factor (in [0, 1]), film ior (at least 1), thickness
// range (0 .. 1e6 nm) and two textures (with texCoord and KHR_texture_transform).
void read_iridescence(const tinygltf::Model& model, const tinygltf::Material& material, const std::string& where,
                      Material& out);

// KHR_materials_anisotropy: its strength (in [0, 1]), rotation (radians) and texture (with
// texCoord and KHR_texture_transform).
void read_anisotropy(const tinygltf::Model& model, const tinygltf::Material& material, const std::string& where,
                     Material& out);

// KHR_materials_sheen: sheenColorFactor (three numbers in [0, 1]) and sheenRoughnessFactor
// (in [0, 1]), else an error; its two textures (colour sRGB RGB, roughness A, with texCoord
// and KHR_texture_transform).
void read_sheen(const tinygltf::Model& model, const tinygltf::Material& material, const std::string& where,
                Material& out);

// KHR_materials_transmission: transmissionFactor (in [0, 1]) and transmissionTexture (R);
// KHR_materials_volume: thicknessFactor (at least 0), thicknessTexture (G), attenuationDistance
// (positive; absent: infinite, no attenuation) and attenuationColor (three numbers in [0, 1]).
// Either one's values out of range are an error; the textures take texCoord and
// KHR_texture_transform.
void read_transmission(const tinygltf::Model& model, const tinygltf::Material& material, const std::string& where,
                       Material& out);

// KHR_materials_ior (the dielectric F0) and KHR_materials_specular: its factors and its two
// textures (with texCoord and KHR_texture_transform, as the core textures).
void read_dielectric_extensions(const tinygltf::Model& model, const tinygltf::Material& material,
                                const std::string& where, Material& out);

}  // namespace facet::gltf_detail
