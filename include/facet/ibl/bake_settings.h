#pragma once
// What a whole bake is asked for (ibl/baked_environment.h), and the callbacks it reports
// through: progress lines, pass progress, and safe points where the caller may stop it.
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <string>

#include <vulkan/vulkan.h>

#include <facet/cache/directory_cache.h>
#include <facet/core/result.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/ibl/light_extraction.h>

namespace facet {

struct EncodedEnvironmentFiles;  // ibl/baked_environment.h

// environment.exr (and .hdr) encoded by the caller: ready, or still being encoded on a
// thread of its own (encode_environment_files_in_background, ibl/baked_environment.h).
class EncodedEnvironment {
public:
    EncodedEnvironment() = default;
    // Files already encoded (null: none).
    EncodedEnvironment(std::shared_ptr<const EncodedEnvironmentFiles> ready);
    // Files still being encoded; the value is null where the encoder failed.
    explicit EncodedEnvironment(std::shared_future<std::shared_ptr<const EncodedEnvironmentFiles>> pending)
        : pending_(std::move(pending)) {}
    explicit operator bool() const { return pending_.valid(); }
    // The files, once encoded (waits for the encoder); null for none or a failed encoder.
    std::shared_ptr<const EncodedEnvironmentFiles> get() const { return pending_.valid() ? pending_.get() : nullptr; }

private:
    std::shared_future<std::shared_ptr<const EncodedEnvironmentFiles>> pending_;
};

// What BakedEnvironment::save writes.
struct BakeSaveOptions {
    // environment.png, environment.hdr and brdf_lut.png: for people and other tools;
    // load() reads none of them (a cache entry leaves them out).
    bool previews = true;
};

struct BakeSettings {
    // Methods and sizes (cube_size 0: the input's height / 2); resolved against the
    // input by bake_environment (resolved_ibl_settings).
    IblSettings ibl;
    // The format the outputs are stored in: RGBA16F (what glTF viewers read) or RGBA32F.
    // An output whose values exceed RGBA16F's range (65504) is kept in RGBA32F whatever
    // this says, and the bake says so (BakeMetadata::format_notes).
    VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT;
    // Suns and lamps taken out of the map and returned as disk lights (ibl/light_extraction.h);
    // the specular levels below light_split_level() come from the whole environment.
    bool extract_lights = false;
    LightExtractionSettings extraction;
    // The accuracy budget (ibl/bake_budget.h): 0 = none; else the cheapest methods whose
    // measured relative RMS error meets it over the roughness range.
    double target_error = 0;
    float roughness_min = 0.0f, roughness_max = 1.0f;
    float preview_exposure = 1.0f;  // environment.png
    bool preview = true;            // environment.png made at all (not needed to render)
    // The BRDF LUT kept across processes (it depends on the model, its size, its samples
    // and the shaders that make it, not on the environment): an entry "brdf-lut-..." of
    // this DirectoryCache (facet-render's bake cache, facet-bake's --lut-cache). A hit
    // uploads it instead of computing it; a damaged entry is said, removed and made again.
    // Empty directory: none.
    CacheOptions lut_cache{"", 4ull << 30, false};
    // environment.exr (and .hdr) encoded by the caller from the texels it bakes
    // (encode_environment_files or encode_environment_files_in_background in
    // ibl/baked_environment.h), e.g. while the device starts: the BakedEnvironment keeps
    // them, and saving writes these bytes instead of reading the environment back and
    // encoding it (it waits there for files still being encoded). Ignored where they are
    // not of the environment as baked (another input or size, a built-in sky, the residual
    // of extracted lights) or the encoder failed: the environment is then encoded from the
    // texels read back, as without them.
    EncodedEnvironment encoded_environment;
};

// A line of progress (passes, the budget's measurements, ...).
using BakeProgressFn = std::function<void(const std::string& line)>;
// After each pass of the bake's graph: passes done, their total, the pass's name.
using BakePassFn = std::function<void(uint32_t done, uint32_t total, const std::string& pass)>;
// Called at safe points (named: "shaders" before the bake's own shaders, "pass" after
// each pass, "budget" inside the accuracy budget's brute-force sums, "file" between
// output files); returning true stops the work, which frees what it holds and returns
// an Error for which is_cancelled() is true.
using BakeStopFn = std::function<bool(const char* point)>;

struct BakeCallbacks {
    BakeProgressFn progress;
    BakePassFn pass_done;
    BakeStopFn stop;
    // The bake's compiled graph in Graphviz form, before it runs (facet-bake --graph-dot).
    std::function<void(const std::string& dot)> graph_dot;
};

// The message of the Error a stopped bake returns.
inline constexpr const char* kBakeCancelled = "cancelled";
inline bool is_cancelled(const Error& error) { return error.message == kBakeCancelled; }

}  // namespace facet
