#pragma once
// Fallible calls return Result<T>: a value, or an Error carrying the VkResult (if any)
// and a human reason (vk-bootstrap style). Every public function reports what the
// device, the user's data or files can cause that way; no exception crosses the public
// API except UsageError, which marks programmer misuse (said in each header).
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

#include <vulkan/vulkan.h>

namespace facet {

struct Error {
    std::string message;
    VkResult vk_result = VK_SUCCESS;
};

// Internal to the engine: thrown for Vulkan failures deep inside its own calls and
// caught at every public entry point, which returns it as an Error{message, vk_result}.
// No public function lets it escape. (It stays declared here until every engine file
// includes its private home, engine/core/guarded.h.)
class VulkanError : public std::runtime_error {
public:
    VulkanError(VkResult result, const std::string& what);
    // Carries an Error on unchanged (its message already names the failure).
    explicit VulkanError(const Error& error);
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

// Misuse of an API (a stale graph handle, a pass reading an unwritten resource).
class UsageError : public std::logic_error {
public:
    using std::logic_error::logic_error;
};

const char* vk_result_name(VkResult result);

// Internal, as VulkanError: throws VulkanError naming `what` unless result is VK_SUCCESS.
void vk_check(VkResult result, const char* what);

template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : data_(std::move(value)) {}
    Result(Error error) : data_(std::move(error)) {}

    bool ok() const { return data_.index() == 0; }
    explicit operator bool() const { return ok(); }
    T& value() & { return std::get<0>(data_); }
    T&& value() && { return std::get<0>(std::move(data_)); }
    const T& value() const& { return std::get<0>(data_); }
    const Error& error() const { return std::get<1>(data_); }
    T* operator->() { return &value(); }
    T& operator*() { return value(); }

private:
    std::variant<T, Error> data_;
};

// For calls that return nothing on success.
struct Ok {};
using Status = Result<Ok>;

}  // namespace facet
