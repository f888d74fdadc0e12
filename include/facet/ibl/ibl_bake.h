#pragma once
// The whole image-based-lighting bake as passes of a caller's render graph: the
// environment (a file's texels or a procedural sky), its cube, the irradiance cube, the
// prefiltered specular cube and the BRDF LUT. facet-bake exports them to files;
// facet-render feeds them to the forward pass in the same graph.
#include <memory>
#include <optional>
#include <string>

#include <facet/core/result.h>
#include <facet/graph/render_graph.h>
#include <facet/ibl/brdf_lut.h>
#include <facet/ibl/irradiance.h>
#include <facet/ibl/procedural_sky.h>
#include <facet/ibl/specular.h>
#include <facet/io/environment_image.h>

namespace facet {

class Buffer;
class Context;
class ProgramCache;
class Sampler;

// An environment by name: builtin:sky, builtin:white, or an image file.
struct EnvironmentSource {
    std::string name;
    std::optional<ProceduralSky> sky;
    EnvironmentImage image;  // file texels (empty for a procedural sky)
    // The procedural sky `image` was rendered from (materialize_environment), so that a bake
    // of those texels makes the cube from the sky itself, as a bake of `sky` does; reset
    // where the texels change (lights taken out, downsampled).
    std::optional<ProceduralSky> sky_model;
    std::string content_hash;
    uint32_t width = 0, height = 0;                // what the bake uses
    uint32_t source_width = 0, source_height = 0;  // the file's (larger when downsampled on load)
    uint32_t max_width = 0;  // the width files were limited to when read (EnvironmentLoadOptions)
};

// `builtin_width`: width of a procedural environment (height = width / 2); it may not
// exceed `file_options.max_width`, which files wider than it are downsampled to.
Result<EnvironmentSource> resolve_environment(const std::string& name, uint32_t builtin_width = 1024,
                                              const EnvironmentLoadOptions& file_options = {});
std::string builtin_environment_names();  // "builtin:sky, builtin:white"

// A procedural environment's texels, computed on the GPU and read back, so that CPU
// work (light extraction) can use them; file environments are left as they are.
Status materialize_environment(Context& context, ProgramCache& programs, EnvironmentSource& source);

struct IblSettings {
    uint32_t cube_size = 0;  // 0: input height / 2
    IrradianceSettings irradiance;
    SpecularSettings specular;
    BrdfLutSettings lut;
    // What the consumer needs (a scene of pure metals needs no irradiance).
    bool want_irradiance = true;
    bool want_specular = true;
    bool want_lut = true;
};

// Sizes that follow from the input: the cube's face and the specular levels it allows.
IblSettings resolved_ibl_settings(const IblSettings& settings, const EnvironmentSource& source);

// The bake's images (`settings` as resolved) against the device's dimension and memory
// limits (gpu/device_limits.h), so that a cube face, LUT or environment too large for
// it is refused before anything is created; add_passes checks this too. With
// `whole_copy`, light extraction's second environment and cube count as well.
Status check_ibl_fits(const Context& context, const EnvironmentSource& source, const IblSettings& settings,
                      bool whole_copy = false);

struct IblImages {
    ImageHandle equirect;    // RGBA32F, the input
    ImageHandle cube;        // the environment cube with its mips (the skybox samples it)
    ImageHandle irradiance;  // E/pi cube (invalid when not wanted)
    ImageHandle specular;    // prefiltered cube, roughness level / (levels - 1)
    ImageHandle lut;         // split-sum A, B, E_avg
    BufferHandle sh9;        // sh9 irradiance coefficients, when that method runs
};

// Light extraction bakes the irradiance (the diffuse lobe integrates the lights exactly, so
// the renderers shade only the disks' specular) and the specular levels below `level`
// (lobes narrower than the extracted lights see them as they are) from the whole
// environment, and the rest and the skybox's cube from the map without its lights.
struct SpecularSplit {
    const EnvironmentSource* whole = nullptr;
    uint32_t level = 0;
};

// Images of the caller's, imported into the graph (an engine's own cube, specular cube,
// irradiance cube or LUT), that the passes write instead of images of their own. Each
// must have the description the bake would create (RGBA32F; the environment cube with
// its full mip chain and the specular cube with settings.specular.levels levels, both
// of settings.cube_size; the irradiance cube of settings.irradiance.size; the LUT of
// settings.lut.size square), and usage STORAGE and SAMPLED; add_passes checks the
// description. An invalid handle: the bake creates that image.
struct IblTargets {
    ImageHandle cube, irradiance, specular, lut;
};

// Owns what the passes use beyond the graph's resources (samplers, the staging buffer
// of a file's texels), so it must outlive the graph's run. Its constructor makes nothing on the
// device; add_passes returns what the device can fail at as an Error.
class IblBake {
public:
    IblBake(Context& context, ProgramCache& programs);
    ~IblBake();
    IblBake(const IblBake&) = delete;
    IblBake& operator=(const IblBake&) = delete;

    // `settings` as returned by resolved_ibl_settings().
    Result<IblImages> add_passes(RenderGraph& graph, const EnvironmentSource& source, const IblSettings& settings,
                                 const SpecularSplit& split = {}, const IblTargets& targets = {});

    // Made by the first add_passes (which returns an Error if the device cannot make it).
    const Sampler& cube_sampler() const { return *cube_sampler_; }

    // The BRDF LUT as computed before (RGBA32F, settings.lut.size squared, from a cache):
    // add_passes uploads it instead of computing it. Other sizes are not used.
    void use_lut(std::vector<float> texels) { cached_lut_ = std::move(texels); }

private:
    Context& context_;
    ProgramCache& programs_;
    std::unique_ptr<Sampler> equirect_sampler_, cube_sampler_;
    std::unique_ptr<Buffer> staging_, whole_staging_, lut_staging_;
    std::vector<float> cached_lut_;
};

}  // namespace facet
