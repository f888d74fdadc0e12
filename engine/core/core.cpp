#include <facet/core/hash.h>
#include <facet/core/log.h>
#include <facet/core/result.h>
#include <facet/core/units.h>

#include <sys/mman.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include "core/huge_pages.h"
#include "core/vulkan_error.h"

namespace facet {

namespace {
// What a user can make of the failures that reach them (the VkResult alone says little).
std::string vk_result_meaning(VkResult result) {
    switch (result) {
        case VK_ERROR_OUT_OF_DEVICE_MEMORY: return " (the device is out of memory: try smaller images or sizes)";
        case VK_ERROR_OUT_OF_HOST_MEMORY: return " (the driver is out of host memory)";
        case VK_TIMEOUT:
            return " (the GPU did not finish in time: it hung, or the work needs a longer "
                   "ContextOptions::fence_timeout_ms)";
        case VK_ERROR_DEVICE_LOST:
            return " (the device was lost: a driver crash, reset or timeout; nothing more can run on it)";
        default: return "";
    }
}
}  // namespace

VulkanError::VulkanError(VkResult result, const std::string& what)
    : std::runtime_error(what + ": " + vk_result_name(result) + vk_result_meaning(result)), result_(result) {}

VulkanError::VulkanError(const Error& error) : std::runtime_error(error.message), result_(error.vk_result) {}

const char* vk_result_name(VkResult result) {
    switch (result) {
#define FACET_CASE(x) \
    case x:           \
        return #x;
        FACET_CASE(VK_SUCCESS)
        FACET_CASE(VK_NOT_READY)
        FACET_CASE(VK_TIMEOUT)
        FACET_CASE(VK_INCOMPLETE)
        FACET_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        FACET_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        FACET_CASE(VK_ERROR_INITIALIZATION_FAILED)
        FACET_CASE(VK_ERROR_DEVICE_LOST)
        FACET_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        FACET_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        FACET_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        FACET_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        FACET_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        FACET_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        FACET_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        FACET_CASE(VK_ERROR_FRAGMENTED_POOL)
        FACET_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        FACET_CASE(VK_ERROR_UNKNOWN)
#undef FACET_CASE
        default:
            return "VkResult(unknown)";
    }
}

std::string format_bytes(uint64_t bytes) {
    char text[32];
    if (bytes >= (uint64_t(1) << 30)) std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1u << 30));
    else if (bytes >= (uint64_t(1) << 20)) std::snprintf(text, sizeof text, "%.0f MiB", double(bytes) / double(1u << 20));
    else std::snprintf(text, sizeof text, "%.0f KiB", double(bytes) / 1024.0);
    return text;
}

void vk_check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw VulkanError(result, what);
}

namespace {
std::mutex g_log_mutex;
LogSink g_log_sink;
std::atomic<LogLevel> g_log_level{LogLevel::info};
}  // namespace

void set_log_level(LogLevel minimum) { g_log_level.store(minimum); }
LogLevel log_level() { return g_log_level.load(); }

void set_log_sink(LogSink sink) {
    std::lock_guard lock(g_log_mutex);
    g_log_sink = std::move(sink);
}

void log(LogLevel level, std::string_view message) {
    std::lock_guard lock(g_log_mutex);
    if (g_log_sink) {
        g_log_sink(level, message);
        return;
    }
    if (level < g_log_level.load()) return;
    static const char* names[] = {"debug", "info", "warning", "error"};
    std::fprintf(stderr, "facet %s: %.*s\n", names[static_cast<int>(level)],
                 static_cast<int>(message.size()), message.data());
}

Hash64& Hash64::add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        state ^= bytes[i];
        state *= 0x100000001b3ull;
    }
    return *this;
}

Hash64& Hash64::add_bulk(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    // Each lane: xor in a word, multiply by an odd constant, xor-shift (both bijective, so
    // a changed word changes its lane's state for good).
    std::uint64_t lanes[4] = {state, state ^ 0x9e3779b97f4a7c15ull, state ^ 0xbf58476d1ce4e5b9ull,
                              state ^ 0x94d049bb133111ebull};
    std::size_t i = 0;
    for (; i + 32 <= size; i += 32)
        for (int l = 0; l < 4; ++l) {
            std::uint64_t word;
            std::memcpy(&word, bytes + i + 8 * l, 8);
            std::uint64_t x = (lanes[l] ^ word) * 0xbf58476d1ce4e5b9ull;
            lanes[l] = x ^ (x >> 31);
        }
    add(lanes, sizeof lanes);
    add(bytes + i, size - i);
    const std::uint64_t length = size;
    return add(&length, sizeof length);
}

std::string Hash64::hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(state));
    return text;
}

void advise_huge_pages(void* data, std::size_t size) {
    constexpr uintptr_t huge = uintptr_t(2) << 20;
    if (!data || size < huge) return;
    const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + huge - 1) & ~(huge - 1);
    const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + size) & ~(huge - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

}  // namespace facet
