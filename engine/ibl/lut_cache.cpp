#include "ibl/lut_cache.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include <facet/core/hash.h>
#include <facet/shader/program_cache.h>

namespace facet {
namespace {

constexpr const char* kFile = "brdf_lut.rgba32f";

}  // namespace

Result<std::string> brdf_lut_cache_key(ProgramCache& programs, const BrdfLutSettings& settings) {
    Hash64 hash;
    for (const char* shader : {"ibl/brdf_lut.comp", "ibl/brdf_lut_energy.comp"}) {
        auto spirv = programs.compiler().compile(ShaderStage::compute, shader);
        if (!spirv) return spirv.error();
        hash.add(&spirv->key, sizeof spirv->key);
    }
    return "brdf-lut-" + std::string(brdf_model_name(settings.brdf)) + "-" + std::to_string(settings.size) + "-" +
           std::to_string(settings.sample_count) + "-" + hash.hex();
}

std::vector<float> find_cached_lut(const CacheOptions& options, const std::string& key, uint32_t size,
                                   std::string& note) {
    note.clear();
    DirectoryCache cache(options);
    auto entry = cache.find(key);
    if (!entry) {
        note = entry.error().message;
        return {};
    }
    if (!entry->damage.empty()) note = entry->path + ": " + entry->damage + " (removed)";
    if (entry->path.empty()) return {};
    const std::string path = entry->path + "/" + kFile;
    std::ifstream in(path, std::ios::binary);
    std::vector<char> raw((std::istreambuf_iterator<char>(in)), {});
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(raw.data()), raw.size());
    Status checked = check_cache_file(*entry, kFile, bytes);
    if (checked && bytes.size() != size_t(size) * size * 4 * sizeof(float))
        checked = Error{std::string(kFile) + ": " + std::to_string(bytes.size()) + " bytes, not a " +
                        std::to_string(size) + "-square RGBA32F LUT"};
    if (!checked) {
        note = path + ": " + checked.error().message + " (removed; the LUT is computed again)";
        entry->hold.reset();
        if (Status removed = cache.remove(key); !removed) note += "; " + removed.error().message;
        return {};
    }
    std::vector<float> texels(bytes.size() / sizeof(float));
    std::memcpy(texels.data(), bytes.data(), bytes.size());
    return texels;
}

Status store_cached_lut(const CacheOptions& options, const std::string& key, std::span<const std::byte> texels) {
    DirectoryCache cache(options);
    auto entry = cache.get_or_fill(key, [&](const std::string& staging) -> Status {
        const std::string path = staging + "/" + kFile;
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(texels.data()), std::streamsize(texels.size()));
        out.close();
        if (!out) return Error{path + ": cannot be written"};
        return Ok{};
    });
    if (!entry) return entry.error();
    return Ok{};
}

}  // namespace facet
