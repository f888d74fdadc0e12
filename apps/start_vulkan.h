#pragma once
// How the programs start Vulkan: the library reads no environment variable, so the
// programs map theirs onto its options here, once.
//   FACET_VALIDATION    1: validation + synchronization validation; 0: off; unset: the
//                       library's default (on in a Debug build)
//   FACET_DEVICE        a device by index or name substring (a --device flag wins)
//   FACET_INJECT_FAULT  SITE[:SKIP], SITE one of memory, submit, pipeline, hang: the call
//                       after SKIP good ones fails on purpose (testing error paths)
//   FACET_LOG           debug: log everything (facet/core/log.h)
#include <functional>
#include <memory>
#include <string>

#include <facet/core/result.h>
#include <facet/gpu/context.h>

namespace facet {

// The options the environment asks for (and the log level FACET_LOG asks for, set as a
// side effect). A malformed value is an Error naming the variable.
Result<ContextOptions> context_options_from_environment();

// context_options_from_environment(), the device flag when given (else FACET_DEVICE),
// validation forced on when asked; throws std::runtime_error with the reason when the
// environment is malformed.
ContextOptions program_context_options(const std::string& device = {}, bool validation = false);

// Context::create(program_context_options(device, validation)); throws
// std::runtime_error with the reason when Vulkan cannot start.
std::unique_ptr<Context> start_vulkan(const std::string& device, bool validation);

// The same, as a Result (for the programs that report errors themselves).
Result<std::unique_ptr<Context>> create_program_context();

}  // namespace facet
