#pragma once
// Compute and graphics pipelines built from shaders/ on first use and kept for the context's life,
// keyed by shader name + defines (a pass asks for its program each time it is added).
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>
#include <facet/gpu/pipeline.h>
#include <facet/shader/compiler.h>

namespace facet {

class Context;

class ProgramCache {
public:
    ProgramCache(Context& context, ShaderCompiler& compiler) : context_(context), compiler_(compiler) {}

    // A compute pipeline for `shader` (path under shaders/); its bindings, push-constant
    // size and workgroup size come from the compiled shader (Pipeline::reflection()).
    // The error carries the compiler's file:line message.
    Result<const Pipeline*> compute(const std::string& shader, std::span<const ShaderDefine> defines = {});

    // A graphics pipeline from a vertex and a fragment shader compiled with the same
    // defines; `desc` gives the fixed-function state (its SPIR-V fields are filled here),
    // the shaders their bindings and push constants.
    Result<const Pipeline*> graphics(const std::string& vertex_shader, const std::string& fragment_shader,
                                     Pipeline::GraphicsDesc desc, std::span<const ShaderDefine> defines = {});

    // Shader hot reload: every pipeline built so far is built again from the current
    // sources. All or nothing: on a compile error (file:line) every pipeline stays as it
    // was. On success each is replaced in place, so the pointers handed out stay valid;
    // call it between frames, with no recorded work pending. Returns the pipelines rebuilt.
    Result<size_t> reload();

    Context& context() { return context_; }
    ShaderCompiler& compiler() { return compiler_; }

private:
    struct Entry {
        std::unique_ptr<Pipeline> pipeline;
        std::function<Result<Pipeline>()> build;
    };
    Result<const Pipeline*> get(const std::string& key, std::function<Result<Pipeline>()> build);

    Context& context_;
    ShaderCompiler& compiler_;
    std::map<std::string, Entry> pipelines_;
};

}  // namespace facet
