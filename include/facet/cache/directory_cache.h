#pragma once
// A cache of directories on disk, keyed by a string (a bake key): each entry is a folder
// of files written by the caller, made whole before anyone can see it and checked before
// every use. Built for the bake cache of facet-render and facet-viewer
// ($XDG_CACHE_HOME/facet/bakes, docs/design.md, "The library boundary"), usable for any
// derived data that is expensive to make and cheap to verify.
//
// - Atomic entries: the caller fills a private staging folder; a manifest (every file's
//   name, size and FNV-1a hash) is written last and the folder renamed into place, so an
//   entry either exists whole or not at all.
// - Checked before use: a missing file, a size or a hash that differs from the manifest
//   makes the entry damaged; it is reported (CacheEntry::damage), removed and built again,
//   never used. With CacheOptions::check_contents off, the cache checks presence and
//   sizes only and the reader checks each file's hash as it reads it (check_cache_file),
//   so that a hit reads every file once; a reader that finds a difference remove()s the
//   entry and asks again.
// - Concurrency: a per-key lock file (flock) serialises fillers, so two processes asking
//   for the same missing entry at once build it once and both get the same valid files;
//   different keys proceed in parallel. Advisory locks: every user of a cache folder must
//   go through this class.
// - Size bound: after a fill, least-recently-used entries (by the manifest's modification
//   time, refreshed on every hit) are removed until the total fits `max_bytes`; an entry
//   locked by any process (being filled, or held by a CacheEntry) is skipped.
// The library reads no environment: the programs choose the folder
// (default_cache_directory() takes XDG_CACHE_HOME and HOME as arguments).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <facet/core/result.h>

namespace facet {

struct CacheOptions {
    std::string directory;                        // created when missing
    std::uint64_t max_bytes = 4ull << 30;         // bound on the entries' total size
    // Hash every file on each use (true), or leave the contents to the reader (false:
    // check_cache_file on what it reads; the cache checks each file's presence and size).
    bool check_contents = true;
};

// A file of an entry as its manifest records it.
struct CacheFile {
    std::string name;  // relative to the entry's folder, '/'-separated
    std::uint64_t size_bytes = 0;
    std::string hash;  // 64-bit FNV-1a of the contents, 16 hex digits (core/hash.h)
};

struct CacheEntry {
    std::string path;      // the entry's folder: read its files, don't modify them
    bool built = false;    // this call filled it (a miss, or a damaged entry rebuilt)
    std::string damage;    // non-empty when a damaged entry was found and rebuilt: why
    // A shared lock on the entry while this object (or a copy) lives: no process evicts
    // or rebuilds it meanwhile. Drop it when the files have been read.
    std::shared_ptr<const void> hold;
    std::vector<CacheFile> files;  // the manifest (for the reader's own checks)
};

// Whether `bytes`, read from `entry`'s file `name`, are what its manifest records: an
// Error "NAME: contents differ from the manifest (...)" or "NAME: not in the manifest".
Status check_cache_file(const CacheEntry& entry, const std::string& name, std::span<const std::byte> bytes);

// `xdg_cache_home` and `home` as read by the program (empty when unset):
// XDG_CACHE_HOME/facet, else HOME/.cache/facet; an error when both are empty.
Result<std::string> default_cache_directory(const std::string& xdg_cache_home, const std::string& home);

class DirectoryCache {
public:
    explicit DirectoryCache(CacheOptions options);

    // Writes the entry's files into `staging_dir` (an empty folder); a failure leaves no entry.
    using Fill = std::function<Status(const std::string& staging_dir)>;

    // The entry for `key` (letters, digits, '-', '_' and '.'), checked; built with `fill`
    // when missing or damaged. Filesystem failures and fill's own error come back as errors
    // naming the folder.
    Result<CacheEntry> get_or_fill(const std::string& key, const Fill& fill);

    // The entry when it exists and is whole (refreshing its use time), else an empty path.
    // A damaged entry is removed and reported in `damage`.
    Result<CacheEntry> find(const std::string& key);

    // Removes the entry (a reader found it damaged), waiting for other processes' holds;
    // this process must have dropped its own (CacheEntry::hold). No entry: nothing to do.
    Status remove(const std::string& key);

    // Removes least-recently-used entries until the total fits max_bytes (never `keep`).
    Status evict(const std::string& keep = {});

    // Total size in bytes of the whole entries.
    std::uint64_t size_bytes() const;

    const CacheOptions& options() const { return options_; }

    static constexpr const char* manifest_name = "cache-manifest.txt";

private:
    CacheOptions options_;
};

}  // namespace facet
