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

// Misuse of an API (a stale graph handle, a pass reading an unwritten resource).
class UsageError : public std::logic_error {
public:
    using std::logic_error::logic_error;
};

const char* vk_result_name(VkResult result);

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
    const T* operator->() const { return &value(); }
    T& operator*() { return value(); }
    const T& operator*() const { return value(); }

private:
    std::variant<T, Error> data_;
};

// For calls that return nothing on success.
struct Ok {};
using Status = Result<Ok>;

}  // namespace facet
