#pragma once
// A finished image-based-lighting bake that owns exactly its outputs, as GPU images, and
// the metadata that describe them; every intermediate of the bake (the graph's other
// images, the upload, the samplers of the passes) is freed when bake_environment returns.
// It can be saved as facet-bake's files (design.md) and loaded back without baking.
//
// Every image is left in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, with usage (at least)
// SAMPLED and TRANSFER_SRC, ready to be imported into a frame's graph
// (import_baked_environment). A bake's images are the graph's own outputs, taken out of
// its run; nothing is copied through the host except by save(). The BakedEnvironment
// must outlive every use of its images.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/gpu/resources.h>
#include <facet/graph/graph_run.h>
#include <facet/ibl/bake_budget.h>
#include <facet/ibl/bake_settings.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/ibl/light_extraction.h>
#include <facet/render/forward_renderer.h>

namespace facet {

class Context;
class OutputSet;
class ProgramCache;
class RenderGraph;

struct BakeMetadata {
    std::string input;         // the environment's name (a file or builtin:NAME)
    std::string content_hash;  // of the input's texels
    std::string bake_key;      // bake_rules.h
    std::string device, version;
    uint64_t sanitized_texels = 0;
    uint32_t width = 0, height = 0;                // the environment as baked
    uint32_t source_width = 0, source_height = 0;  // the file's
    uint32_t max_env_width = 0;  // wider files were downsampled to it while read (0: not recorded)
    IblSettings settings;            // as resolved and baked (the budget's methods, if any)
    std::vector<float> roughness;    // of every specular level (level 0 = 0)
    uint32_t first_specular_level = 0;  // levels below it were not needed (zero texels)
    // Storage format of each output (RGBA16F or RGBA32F; the environment is RGBA32F).
    VkFormat cube_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    VkFormat specular_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    VkFormat irradiance_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    VkFormat lut_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    // One sentence per output kept in RGBA32F although RGBA16F was asked for, because
    // its values exceed RGBA16F's largest (65504) and would be stored as infinities.
    std::vector<std::string> format_notes;
    std::vector<std::string> warnings;  // methods used outside their domain (ibl/method_domain.h)
    std::optional<Budget> budget;       // the accuracy budget's choices and predicted errors
    uint32_t light_split_level = 0;     // bake_rules.h; 0 without extracted lights
    double extracted_power_fraction = 0;
    std::vector<std::string> extraction_notes;
    float preview_exposure = 1.0f;
    std::vector<PassTiming> timings;  // GPU time of every pass of the bake
    double wall_time_ms = 0;
    uint32_t passes = 0;
};

// A file environment's environment.exr (and environment.hdr with previews), encoded from
// its texels ahead of the bake that saves them (BakeSettings::encoded_environment): a
// program encodes them on one thread while another starts the device.
struct EncodedEnvironmentFiles {
    std::string content_hash;  // of the texels encoded (EnvironmentSource::content_hash)
    uint32_t width = 0, height = 0;
    bool previews = false;
    std::vector<uint8_t> exr;
    std::vector<uint8_t> hdr;  // empty without previews
};
// Encoded on the calling thread only (it runs beside other work). An Error for a built-in
// environment (its texels are made on the device) and when an encoder fails.
Result<EncodedEnvironmentFiles> encode_environment_files(const EnvironmentSource& source,
                                                         const BakeSaveOptions& options = {});
// The same on a thread of its own, for the texels `source` gives when it has them (null:
// nothing to encode): a program makes the thread first thing and hands it the texels once
// read, while the device starts on another (a thread made while the Vulkan loader opens
// the drivers waits for it: glibc's loader lock, ~40 ms on lavapipe). Saving waits for the
// files if they are not done by then. The value is null where encoding fails or the
// source never comes (a built-in sky included): the save then encodes the texels it reads
// back.
EncodedEnvironment encode_environment_files_in_background(
    std::shared_future<std::shared_ptr<const EnvironmentSource>> source, const BakeSaveOptions& options = {});

class BakedEnvironment {
public:
    BakedEnvironment(BakedEnvironment&&) noexcept;
    BakedEnvironment& operator=(BakedEnvironment&&) noexcept;
    ~BakedEnvironment();

    // Reads the files save() wrote back into GPU images, without baking, checking each
    // against bake.json: a missing, truncated or mismatched file is an Error naming it.
    // `check` (if given) sees every file as read (its name in `dir`, its bytes) before
    // it is used, and its Error stops the load: a cache checks its manifest's hashes
    // there, so that each file is read once.
    using FileCheck = std::function<Status(const std::string& name, std::span<const std::byte> bytes)>;
    static Result<BakedEnvironment> load(Context& context, const std::string& dir, const FileCheck& check = {});

    // Writes facet-bake's files into `dir` (created if needed), all or none (io/output_set.h).
    // The images are read back from the GPU here, but for the environment's float files
    // when they were encoded ahead (BakeSettings::encoded_environment).
    Status save(const std::string& dir, const BakeSaveOptions& options = {}) const;
    // The same files staged into the caller's OutputSet, which the caller commits (a
    // program that blocks signals around the commit); `stop` is asked between files.
    // `notes` (if given) receives what happens to files an earlier bake left there.
    Status stage(OutputSet& outputs, const std::string& dir, const BakeStopFn& stop = {},
                 std::vector<std::string>* notes = nullptr, const BakeSaveOptions& options = {}) const;

    // The environment as baked: equirect RGBA32F (row 0 = +Y), one level.
    const Image& environment() const { return environment_; }
    // The environment cube with its full mip chain (the skybox samples it).
    const Image& cube() const { return cube_; }
    // The prefiltered specular cube, roughness of level m = metadata().roughness[m];
    // nullptr when not baked (IblSettings::want_specular).
    const Image* specular() const { return specular_ ? &specular_ : nullptr; }
    // E/pi cube; nullptr when not baked (a scene of pure metals).
    const Image* irradiance() const { return irradiance_ ? &irradiance_ : nullptr; }
    // Split-sum A, B and E_avg; nullptr when not baked.
    const Image* lut() const { return lut_ ? &lut_ : nullptr; }
    // The sh9 irradiance method's coefficients: 10 vec4 (L_0..L_8 RGB, then the window h
    // in [36]); empty for other methods.
    const std::vector<float>& sh9() const { return sh9_; }
    // Extracted lights (BakeSettings::extract_lights), shaded as disks by the frame.
    const std::vector<DiskLight>& lights() const { return lights_; }
    const BakeMetadata& metadata() const { return metadata_; }
    // Linear, mipmapped, clamped: how the frame samples the cubes.
    const Sampler& cube_sampler() const { return cube_sampler_; }
    // The tone-mapped preview of the environment (RGBA8, environment size); nullptr for a
    // loaded bake or one baked without it (BakeSettings::preview): environment.png is then
    // not written by save().
    const Image* preview() const { return preview_ ? &preview_ : nullptr; }

private:
    friend struct BakedEnvironmentAccess;
    BakedEnvironment() = default;
    Context* context_ = nullptr;  // the images' (save() reads them back through it)
    Image environment_, cube_, specular_, irradiance_, lut_, preview_;
    Sampler cube_sampler_;
    // environment.exr (and .hdr) encoded ahead (BakeSettings::encoded_environment), or
    // none; used where their content hash and size are the environment's.
    EncodedEnvironment encoded_;
    std::vector<float> sh9_;
    std::vector<DiskLight> lights_;
    BakeMetadata metadata_;
};

// Bakes `source` with `settings`: resolves the sizes, runs the accuracy budget if asked,
// extracts lights if asked, runs every pass in one graph, and keeps only the outputs.
// No exception leaves it: a device or input problem is an Error; a stop at a safe point
// (callbacks.stop) is an Error for which is_cancelled() holds.
Result<BakedEnvironment> bake_environment(Context& context, ProgramCache& programs, const EnvironmentSource& source,
                                          const BakeSettings& settings, const BakeCallbacks& callbacks = {});

// The files a saved bake holds (those without which load() fails, and the previews).
const std::vector<const char*>& baked_environment_files();

// The bake key recorded in DIR/bake.json (bake_rules.h bake_key), without loading the
// images: whether a saved bake (a cache entry, facet-bake's output) is of the same input
// and settings. An Error names the file when it is missing or not a bake's description.
Result<std::string> saved_bake_key(const std::string& dir);

// The baked images as imported resources of a frame's graph, for the forward pass
// (render/forward_renderer.h): left as they are found, readable by shaders.
// `intensity` scales the environment's light. The graph must run while `baked` lives.
IblInputs import_baked_environment(RenderGraph& graph, const BakedEnvironment& baked, float intensity = 1.0f);

}  // namespace facet
