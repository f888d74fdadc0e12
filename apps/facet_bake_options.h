#pragma once
// facet-bake's command line, apart from the program so that it can be tested and
// fuzzed without a GPU.
#include <cstdint>
#include <optional>
#include <string>

#include <facet/ibl/brdf_lut.h>
#include <facet/ibl/irradiance.h>
#include <facet/ibl/specular.h>
#include <facet/io/environment_image.h>

namespace facet {

struct BakeOptions {
    std::string env, out_dir, device, graph_dot;
    std::string shader_cache;  // empty: no on-disk shader cache
    std::string lut_cache;     // the BRDF LUT kept across runs (BakeSettings::lut_cache); empty: none
    uint32_t sky_width = 1024;
    uint32_t max_env_width = kDefaultMaxEnvironmentWidth;  // wider files are downsampled while read
    uint32_t cube_size = 0;  // 0: input height / 2
    float exposure = 1.0f;
    bool validation = false, sanitize = false, force = false;
    bool float32 = false;         // every output RGBA32F (else RGBA16F where the values fit)
    bool extract_lights = false;  // suns and lamps as disk lights (ibl/light_extraction.h)
    double target_error = 0;  // 0: no accuracy budget
    float roughness_min = 0.0f, roughness_max = 1.0f;
    IrradianceSettings irradiance;
    SpecularSettings specular;
    BrdfLutSettings lut;
};

// Nothing when --help or --version was answered; throws std::invalid_argument naming
// the option for bad usage.
std::optional<BakeOptions> parse_bake_options(int argc, char** argv);

}  // namespace facet
