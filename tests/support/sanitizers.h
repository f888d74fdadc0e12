#pragma once
// Memory figures under AddressSanitizer: its shadow memory, red zones and quarantine of
// freed blocks (256 MiB by default) raise every peak by a few hundred MiB, so absolute
// peak-memory bounds get this much slack there; differences between two runs and
// everything else are checked as in a normal build.
namespace facet::test {

constexpr bool under_address_sanitizer() {
#if defined(__SANITIZE_ADDRESS__)
    return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    return true;
#else
    return false;
#endif
#else
    return false;
#endif
}

constexpr double sanitizer_rss_slack_mib() { return under_address_sanitizer() ? 384.0 : 0.0; }

}  // namespace facet::test
