#pragma once
// The boundary between the engine's internal exceptions and the public API: engine code
// deep in a call may throw VulkanError (vk_check) or run out of host memory; every
// public entry point runs its body through guarded(), so the caller gets an
// Error{message, vk_result} instead. UsageError (programmer misuse) passes through.
#include <new>
#include <type_traits>
#include <utility>

#include <facet/core/result.h>
#include "core/vulkan_error.h"

namespace facet {

// Inside the engine: a Result's value, or its Error thrown on as VulkanError for the
// nearest guarded() to return.
template <class T>
T or_throw(Result<T> result) {
    if (!result.ok()) throw VulkanError(result.error());
    return std::move(result).value();
}

// Runs `body` (returning Result<T> or Status; a void body gives Status) and returns what
// it returns, or the internal exception it threw as an Error.
template <class F>
auto guarded(F&& body) {
    using R = std::invoke_result_t<F&>;
    using Out = std::conditional_t<std::is_void_v<R>, Status, R>;
    try {
        if constexpr (std::is_void_v<R>) {
            body();
            return Out(Ok{});
        } else {
            return Out(body());
        }
    } catch (const VulkanError& e) {
        return Out(Error{e.what(), e.result()});
    } catch (const std::bad_alloc&) {
        return Out(Error{"out of host memory", VK_ERROR_OUT_OF_HOST_MEMORY});
    }
}

}  // namespace facet
