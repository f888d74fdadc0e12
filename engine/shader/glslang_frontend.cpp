#include "shader/glslang_frontend.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/build_info.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/libspirv.h>
#include <spirv-tools/optimizer.hpp>

#include <memory>
#include <mutex>
#include <regex>
#include <sstream>

#include <facet/core/log.h>

namespace facet::glslang_frontend {

namespace {

void initialize_once() {
    static std::once_flag once;
    std::call_once(once, [] { glslang::InitializeProcess(); });
}

EShLanguage to_glslang(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::vertex: return EShLangVertex;
        case ShaderStage::fragment: return EShLangFragment;
        case ShaderStage::compute: return EShLangCompute;
    }
    return EShLangCompute;
}

// Resolves "x.glsl" relative to the including file, then from the shaders/ root.
class LibraryIncluder : public glslang::TShader::Includer {
public:
    explicit LibraryIncluder(const ShaderLibrary& library) : library_(library) {}

    IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
        return result(library_.find_include(header, includer, true));
    }
    IncludeResult* includeSystem(const char* header, const char* includer, size_t) override {
        return result(library_.find_include(header, includer, false));
    }
    void releaseInclude(IncludeResult* result) override {
        if (!result) return;
        delete static_cast<ShaderLibrary::Source*>(result->userData);
        delete result;
    }

private:
    static IncludeResult* result(std::optional<ShaderLibrary::Source> found) {
        if (!found) return nullptr;
        auto* owned = new ShaderLibrary::Source(std::move(*found));
        return new IncludeResult(owned->name, owned->text.data(), owned->text.size(), owned);
    }
    const ShaderLibrary& library_;
};

constexpr const char* include_extension = "#extension GL_GOOGLE_include_directive : require\n";

// A TShader with its inputs: glslang keeps pointers to the string arrays and the
// preamble, so they live beside it.
struct PreparedShader {
    const char* text;
    int length;
    const char* name;
    std::string preamble;
    std::unique_ptr<glslang::TShader> shader;
};

std::unique_ptr<PreparedShader> prepare(const Input& input) {
    initialize_once();
    auto p = std::make_unique<PreparedShader>();
    p->text = input.text.c_str();
    p->length = static_cast<int>(input.text.size());
    p->name = input.name.c_str();
    p->preamble = std::string(include_extension) + input.preamble;
    p->shader = std::make_unique<glslang::TShader>(to_glslang(input.stage));
    glslang::TShader& shader = *p->shader;
    shader.setStringsWithLengthsAndNames(&p->text, &p->length, &p->name, 1);
    shader.setPreamble(p->preamble.c_str());
    shader.setEnvInput(glslang::EShSourceGlsl, to_glslang(input.stage), glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
    return p;
}

EShMessages messages(const Input& input) {
    int m = EShMsgSpvRules | EShMsgVulkanRules;
    if (input.debug_info) m |= EShMsgDebugInfo;
    return static_cast<EShMessages>(m);
}

std::optional<std::string> line_of(const std::string& text, int line) {
    std::istringstream in(text);
    std::string current;
    for (int i = 1; std::getline(in, current); ++i)
        if (i == line) return current;
    return std::nullopt;
}

}  // namespace

std::string format_log(std::string_view log, const ShaderLibrary& library, const std::string& main_name,
                       const std::string& main_text) {
    static const std::regex located(R"(^(ERROR|WARNING): (.+?):(\d+): (.*)$)");
    std::istringstream in{std::string(log)};
    std::string line, out;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_match(line, m, located)) {
            // glslang names the preamble (our #defines) string -1.
            const std::string file = m[2].str() == "0" ? main_name : m[2].str() == "-1" ? "(defines)" : m[2].str();
            const int number = std::stoi(m[3].str());
            const char* kind = m[1].str() == "ERROR" ? "error" : "warning";
            out += file + ":" + std::to_string(number) + ": " + kind + ": " + m[4].str() + "\n";
            auto text = file == main_name ? std::optional<std::string>(main_text) : library.load(file);
            if (text)
                if (auto source = line_of(*text, number)) out += "    " + *source + "\n";
        } else if (line.find("compilation errors") != std::string::npos || line.empty()) {
            continue;  // glslang's summary line adds nothing to the located messages
        } else {
            out += line + "\n";
        }
    }
    return out;
}

const std::string& toolchain_tag() {
    static const std::string tag = "glslang " + std::to_string(GLSLANG_VERSION_MAJOR) + "." +
                                   std::to_string(GLSLANG_VERSION_MINOR) + "." +
                                   std::to_string(GLSLANG_VERSION_PATCH) + GLSLANG_VERSION_FLAVOR +
                                   ", Vulkan 1.3, SPIR-V 1.5, SPIRV-Tools performance passes keeping the interface (" +
                                   spvSoftwareVersionString() + ")";
    return tag;
}

Result<std::vector<uint32_t>> compile(const ShaderLibrary& library, const Input& input) {
    auto prepared = prepare(input);
    glslang::TShader* shader = prepared->shader.get();
    LibraryIncluder includer(library);
    if (!shader->parse(GetDefaultResources(), 460, false, messages(input), includer))
        return Error{format_log(shader->getInfoLog(), library, input.name, input.text)};
    glslang::TProgram program;
    program.addShader(shader);
    if (!program.link(messages(input)))
        return Error{input.name + ": link error: " + program.getInfoLog()};
    if (std::string warnings = format_log(shader->getInfoLog(), library, input.name, input.text);
        !warnings.empty())
        log(LogLevel::warning, warnings);

    glslang::SpvOptions options;
    options.generateDebugInfo = input.debug_info;
    options.disableOptimizer = true;
    spv::SpvBuildLogger logger;
    std::vector<uint32_t> words;
    glslang::GlslangToSpv(*program.getIntermediate(to_glslang(input.stage)), words, &logger, &options);
    if (std::string messages = logger.getAllMessages(); !messages.empty())
        log(LogLevel::debug, input.name + ": " + messages);
    if (words.empty()) return Error{input.name + ": SPIR-V generation produced no code"};
    if (!input.debug_info) {
        // glslang writes every branch its preprocessor left in, constant conditions and all:
        // the lit forward shader is 20000 words, 2900 once SPIRV-Tools' performance passes
        // have taken out what no input can reach. Drivers then build pipelines from a fraction
        // of the code (lavapipe inlines and optimises all of it first, ~90 ms for the lit
        // forward pipeline). Every binding and specialization constant stays, so that a
        // variant's interface is the source's whatever its defines leave unused.
        spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_3);
        std::string problems;
        optimizer.SetMessageConsumer([&problems](spv_message_level_t level, const char*, const spv_position_t&,
                                                 const char* message) {
            if (level <= SPV_MSG_ERROR) problems += std::string(message) + "\n";
        });
        // SPIRV-Tools' performance recipe (2023.1), with dead-code elimination told to keep the
        // entry point's interface: an input no code reads stays declared, so that stages still
        // match their neighbours' locations and the vertex bindings (the validation layer warns
        // of every unconsumed attribute or output otherwise).
        using namespace spvtools;
        const bool keep_interface = true;
        optimizer.RegisterPass(CreateWrapOpKillPass())
            .RegisterPass(CreateDeadBranchElimPass())
            .RegisterPass(CreateMergeReturnPass())
            .RegisterPass(CreateInlineExhaustivePass())
            .RegisterPass(CreateEliminateDeadFunctionsPass())
            .RegisterPass(CreateAggressiveDCEPass(keep_interface))
            .RegisterPass(CreatePrivateToLocalPass())
            .RegisterPass(CreateLocalSingleBlockLoadStoreElimPass())
            .RegisterPass(CreateLocalSingleStoreElimPass())
            .RegisterPass(CreateAggressiveDCEPass(keep_interface))
            .RegisterPass(CreateScalarReplacementPass())
            .RegisterPass(CreateLocalAccessChainConvertPass())
            .RegisterPass(CreateLocalSingleBlockLoadStoreElimPass())
            .RegisterPass(CreateLocalSingleStoreElimPass())
            .RegisterPass(CreateAggressiveDCEPass(keep_interface))
            .RegisterPass(CreateLocalMultiStoreElimPass())
            .RegisterPass(CreateAggressiveDCEPass(keep_interface))
            .RegisterPass(CreateCCPPass())
            .RegisterPass(CreateAggressiveDCEPass(keep_interface))
            .RegisterPass(CreateLoopUnrollPass(true))
            .RegisterPass(CreateDeadBranchElimPass())
            .RegisterPass(CreateRedundancyEliminationPass())
            .RegisterPass(CreateCombineAccessChainsPass())
            .RegisterPass(CreateSimplificationPass())
            .RegisterPass(CreateScalarReplacementPass())
            .RegisterPass(CreateLocalAccessChainConvertPass())
            .RegisterPass(CreateLocalSingleBlockLoadStoreElimPass())
            .RegisterPass(CreateLocalSingleStoreElimPass())
            .RegisterPass(CreateAggressiveDCEPass(keep_interface))
            .RegisterPass(CreateSSARewritePass())
            .RegisterPass(CreateAggressiveDCEPass(keep_interface))
            .RegisterPass(CreateVectorDCEPass())
            .RegisterPass(CreateDeadInsertElimPass())
            .RegisterPass(CreateDeadBranchElimPass())
            .RegisterPass(CreateSimplificationPass())
            .RegisterPass(CreateIfConversionPass())
            .RegisterPass(CreateCopyPropagateArraysPass())
            .RegisterPass(CreateReduceLoadSizePass())
            .RegisterPass(CreateAggressiveDCEPass(keep_interface))
            .RegisterPass(CreateBlockMergePass())
            .RegisterPass(CreateRedundancyEliminationPass())
            .RegisterPass(CreateDeadBranchElimPass())
            .RegisterPass(CreateBlockMergePass())
            .RegisterPass(CreateSimplificationPass());
        spvtools::OptimizerOptions opt_options;
        opt_options.set_preserve_bindings(true);
        opt_options.set_preserve_spec_constants(true);
        std::vector<uint32_t> optimized;
        if (!optimizer.Run(words.data(), words.size(), &optimized, opt_options) || optimized.empty())
            return Error{input.name + ": SPIR-V optimizer failed: " + problems};
        words = std::move(optimized);
    }
    return words;
}

}  // namespace facet::glslang_frontend
