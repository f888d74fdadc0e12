#pragma once
// facet-bake's outputs (design.md): reading the baked images back and writing the KTX2
// files, previews and bake.json into one OutputSet, which the caller commits.
#include <cstdint>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/graph/graph_run.h>
#include <facet/ibl/brdf_lut.h>
#include <facet/ibl/irradiance.h>
#include <facet/ibl/specular.h>

namespace facet {

class Context;
class Image;
class OutputSet;

// Every level and layer of an image, as stored (RGBA32F or RGBA8).
struct ImageTexels {
    ImageDesc desc;
    std::vector<std::vector<std::byte>> levels;  // [mip]: layers one after another
};
ImageTexels read_all(Context& context, const Image& image);

struct BakeResults {
    std::vector<PassTiming> timings;
    ImageTexels environment, preview, irradiance, specular, lut;
    std::vector<float> sh9;  // sh9 method: 10 vec4 (L_0..L_8 RGB, then the window h)
};

struct BakeDescription {
    std::string input, content_hash, bake_key, device, version;
    uint64_t sanitized_texels = 0;
    uint32_t source_width = 0, source_height = 0;  // the file's size; the bake's is the environment's
    uint32_t max_env_width = 0;
    IrradianceSettings irradiance;
    SpecularSettings specular;
    BrdfLutSettings lut;
    uint32_t cube_size = 0;
    float exposure = 1;
    double wall_time_ms = 0;
    std::vector<std::string> warnings;  // methods used outside their domain (ibl/method_domain.h)
    // The accuracy budget, when one was given (apps/bake_budget.h).
    struct BudgetEntry {
        std::string stage, method, params;
        double predicted_error = 0, time_ms = 0;
        bool met = false;
    };
    double budget_target = 0;
    float budget_roughness_min = 0, budget_roughness_max = 1;
    std::vector<BudgetEntry> budget;
};

// The files a finished bake leaves in its directory.
const std::vector<const char*>& bake_output_names();

// Writes every output to its temporary in `outputs` (bake.json last: the marker of a
// complete bake); fails (naming the file) on the first that cannot be written, or when
// any baked value is NaN, Inf or negative. A safe point between files (apps/interrupt.h).
Status stage_bake_files(OutputSet& outputs, const std::string& dir, const BakeDescription& d, const BakeResults& r);

}  // namespace facet
