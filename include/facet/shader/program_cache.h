#pragma once
// Compute and graphics pipelines built from shaders/ on first use and kept for the context's life,
// keyed by shader name + defines (a pass asks for its program each time it is added).
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
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

    // While a Batch lives, the driver compiles the compute pipelines asked for on worker
    // threads, one per core, instead of one after another inside compute(): compute()
    // returns once the shader is SPIR-V and the pipeline's layout and reflection (bindings,
    // workgroup size) are made. finish() waits for every one and returns the first error
    // (the failed pipelines leave the cache: their pointers dangle). No pipeline of the batch may be bound before
    // finish() (Pipeline::bind throws). Graphics pipelines are made as before. One batch
    // at a time; reload() waits for the batch. The destructor finishes it if need be.
    // facet-bake's 14 pipelines so (lavapipe, two cores): its whole process 0.48 s against 0.53.
    class Batch {
    public:
        explicit Batch(ProgramCache& cache);
        ~Batch();
        Batch(const Batch&) = delete;
        Batch& operator=(const Batch&) = delete;
        Status finish();

    private:
        friend class ProgramCache;
        void add(const std::string& key, Pipeline* pipeline);
        void work();

        ProgramCache& cache_;
        std::mutex mutex_;
        std::condition_variable wake_;
        std::deque<std::pair<std::string, Pipeline*>> queue_;
        std::vector<std::pair<std::string, Error>> failed_;
        std::vector<std::thread> workers_;
        bool closing_ = false;
        bool finished_ = false;
    };

private:
    struct Entry {
        std::unique_ptr<Pipeline> pipeline;
        std::function<Result<Pipeline>()> build;
    };
    // The pipeline of `key`, made by `build` (kept for reload()) the first time, or by
    // `first` when given (a batch's deferred pipeline, queued for its workers).
    Result<const Pipeline*> get(const std::string& key, std::function<Result<Pipeline>()> build,
                                const std::function<Result<Pipeline>()>& first = {});

    Context& context_;
    ShaderCompiler& compiler_;
    std::map<std::string, Entry> pipelines_;
    Batch* batch_ = nullptr;
};

}  // namespace facet
