#pragma once
// Fallible calls return Result<T>: a value, or an Error carrying the VkResult (if any)
// and a human reason (vk-bootstrap style). Programmer errors throw facet::UsageError.
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

// Thrown for Vulkan failures deep inside calls that have no Result (out of memory,
// device lost), so that they reach the caller instead of aborting.
class VulkanError : public std::runtime_error {
public:
    VulkanError(VkResult result, const std::string& what);
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

// Throws VulkanError naming `what` unless result is VK_SUCCESS.
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
