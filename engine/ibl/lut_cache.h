#pragma once
// The BRDF LUT kept across processes (BakeSettings::lut_cache): it depends on the BRDF
// model, its size, its sample count and the shaders that make it, never on the
// environment, so a bake of a new environment need not compute it again.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <facet/cache/directory_cache.h>
#include <facet/core/result.h>
#include <facet/ibl/brdf_lut.h>

namespace facet {

class ProgramCache;

// "brdf-lut-MODEL-SIZE-SAMPLES-HASH", the hash of the two shaders' cache keys (their
// sources with their includes): an edited shader makes another entry.
Result<std::string> brdf_lut_cache_key(ProgramCache& programs, const BrdfLutSettings& settings);

// The entry's texels (RGBA32F, size x size) or nothing. `note` says why an entry that was
// there is not used (its file is damaged or of another size: the entry is removed).
std::vector<float> find_cached_lut(const CacheOptions& options, const std::string& key, uint32_t size,
                                   std::string& note);

// Keeps `texels` (RGBA32F) under `key`; an Error names the folder.
Status store_cached_lut(const CacheOptions& options, const std::string& key, std::span<const std::byte> texels);

}  // namespace facet
