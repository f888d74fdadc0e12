#include <facet/cache/directory_cache.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <facet/core/hash.h>

namespace facet {
namespace fs = std::filesystem;

namespace {

constexpr const char* manifest_header = "facet-cache 1";

std::string errno_text() { return std::strerror(errno); }

// An exclusive flock on DIR/KEY.lock for the lifetime of the object. Lock files are never
// removed: deleting one while another process waits on it would let a third lock a new
// file of the same name, and two fillers would run at once.
class KeyLock {
public:
    static Result<KeyLock> acquire(const fs::path& path, bool wait, bool shared = false) {
        // flock locks belong to open files, so this process's own shared hold would block
        // its exclusive request forever: refuse that instead of hanging.
        if (!shared && held_here(path.string()))
            return Error{path.string() + ": this process still holds the entry (a CacheEntry is alive); release it first"};
        const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0) return Error{path.string() + ": cannot open the lock file: " + errno_text()};
        int rc;
        do {
            rc = ::flock(fd, (shared ? LOCK_SH : LOCK_EX) | (wait ? 0 : LOCK_NB));
        } while (rc != 0 && errno == EINTR);
        if (rc != 0) {
            const std::string why = errno_text();
            ::close(fd);
            return Error{path.string() + ": cannot lock: " + why};
        }
        KeyLock lock(fd, path.string());
        if (shared) lock.count_hold(+1);
        return lock;
    }
    KeyLock(KeyLock&& other) noexcept
        : fd_(std::exchange(other.fd_, -1)), path_(std::move(other.path_)), shared_(std::exchange(other.shared_, false)) {}
    KeyLock& operator=(KeyLock&&) = delete;
    ~KeyLock() {
        if (shared_) count_hold(-1);
        if (fd_ >= 0) ::close(fd_);  // closing releases the flock
    }
    // Exclusive -> shared: readers may join, evicting (exclusive) must wait.
    void share() {
        ::flock(fd_, LOCK_SH);
        count_hold(+1);
    }

private:
    KeyLock(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
    static std::mutex& holds_mutex() {
        static std::mutex m;
        return m;
    }
    static std::map<std::string, int>& holds() {
        static std::map<std::string, int> h;
        return h;
    }
    static bool held_here(const std::string& path) {
        std::lock_guard guard(holds_mutex());
        auto it = holds().find(path);
        return it != holds().end() && it->second > 0;
    }
    void count_hold(int delta) {
        std::lock_guard guard(holds_mutex());
        auto it = holds().emplace(path_, 0).first;
        it->second += delta;
        if (it->second <= 0) holds().erase(it);  // a long-lived viewer opens many entries
        shared_ = delta > 0;
    }
    int fd_ = -1;
    std::string path_;
    bool shared_ = false;
};


struct ManifestFile {
    std::string name;
    std::uint64_t size = 0;
    std::string hash;
};

Result<std::string> hash_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{path.string() + ": cannot read"};
    Hash64 h;
    std::vector<char> buffer(1 << 20);
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        h.add(buffer.data(), static_cast<size_t>(in.gcount()));
    }
    if (in.bad()) return Error{path.string() + ": read error"};
    return h.hex();
}

// Lists the entry's files (recursively, manifest excluded) with size and hash.
Result<std::vector<ManifestFile>> describe(const fs::path& dir) {
    std::vector<ManifestFile> files;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        if (!it->is_regular_file()) continue;
        const std::string name = fs::relative(it->path(), dir).generic_string();
        if (name == DirectoryCache::manifest_name) continue;
        auto hash = hash_file(it->path());
        if (!hash) return hash.error();
        files.push_back({name, static_cast<std::uint64_t>(it->file_size()), hash.value()});
    }
    if (ec) return Error{dir.string() + ": cannot list: " + ec.message()};
    std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    return files;
}

Result<std::vector<ManifestFile>> read_manifest(const fs::path& dir) {
    std::ifstream in(dir / DirectoryCache::manifest_name);
    if (!in) return Error{"no manifest (an unfinished or foreign entry)"};
    std::string line;
    if (!std::getline(in, line) || line != manifest_header) return Error{"the manifest's first line is not '" + std::string(manifest_header) + "'"};
    std::vector<ManifestFile> files;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::istringstream fields(line);
        ManifestFile f;
        if (!(fields >> f.size >> f.hash) || fields.get() != ' ' || !std::getline(fields, f.name) || f.name.empty())
            return Error{"malformed manifest line '" + line + "'"};
        files.push_back(std::move(f));
    }
    return files;
}

// Why the entry cannot be used, or empty when every listed file is there, whole (with
// `contents` off: of the recorded size; the reader checks the hashes).
std::string check_entry(const fs::path& dir, bool contents = true, std::vector<ManifestFile>* listed = nullptr) {
    auto manifest = read_manifest(dir);
    if (!manifest) return manifest.error().message;
    if (listed) *listed = manifest.value();
    for (const ManifestFile& f : manifest.value()) {
        const fs::path path = dir / f.name;
        std::error_code ec;
        const auto size = fs::file_size(path, ec);
        if (ec) return f.name + ": missing";
        if (size != f.size)
            return f.name + ": " + std::to_string(size) + " bytes, the manifest says " + std::to_string(f.size);
        if (!contents) continue;
        auto hash = hash_file(path);
        if (!hash) return hash.error().message;
        if (hash.value() != f.hash) return f.name + ": contents differ from the manifest (hash " + hash.value() + ", expected " + f.hash + ")";
    }
    return {};
}

std::uint64_t manifest_bytes(const fs::path& dir) {
    auto manifest = read_manifest(dir);
    if (!manifest) return 0;
    std::uint64_t total = 0;
    for (const auto& f : manifest.value()) total += f.size;
    return total;
}

bool valid_key(const std::string& key) {
    if (key.empty() || key.size() > 200 || key[0] == '.') return false;
    return std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
    });
}

void touch(const fs::path& path) {
    ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0);  // best effort: only the LRU order depends on it
}

}  // namespace

Result<std::string> default_cache_directory(const std::string& xdg_cache_home, const std::string& home) {
    // The XDG Base Directory Specification: a relative XDG_CACHE_HOME is invalid, ignore it.
    if (!xdg_cache_home.empty() && xdg_cache_home[0] == '/') return (fs::path(xdg_cache_home) / "facet").string();
    if (!home.empty()) return (fs::path(home) / ".cache" / "facet").string();
    return Error{"no cache folder: neither XDG_CACHE_HOME nor HOME is set"};
}

DirectoryCache::DirectoryCache(CacheOptions options) : options_(std::move(options)) {}

Result<CacheEntry> DirectoryCache::find(const std::string& key) {
    if (!valid_key(key)) return Error{"cache key '" + key + "': only letters, digits, '-', '_' and '.' are allowed"};
    const fs::path root(options_.directory);
    std::error_code ec;
    if (!fs::exists(root / key, ec)) return CacheEntry{};
    CacheEntry entry;
    {
        // Readers share the lock: several processes (or several holds in one) use an entry at once.
        auto shared = KeyLock::acquire(root / (key + ".lock"), true, true);
        if (!shared) return shared.error();
        if (!fs::exists(root / key, ec)) return entry;
        std::vector<ManifestFile> listed;
        entry.damage = check_entry(root / key, options_.check_contents, &listed);
        if (entry.damage.empty()) {
            for (const ManifestFile& f : listed) entry.files.push_back({f.name, f.size, f.hash});
            touch(root / key / manifest_name);
            entry.path = (root / key).string();
            entry.hold = std::make_shared<KeyLock>(std::move(shared.value()));
            return entry;
        }
    }
    // Damaged: removed under the exclusive lock, once no reader holds it.
    auto lock = KeyLock::acquire(root / (key + ".lock"), true);
    if (!lock) return lock.error();
    if (!fs::exists(root / key, ec)) return entry;
    std::vector<ManifestFile> listed;
    entry.damage = check_entry(root / key, options_.check_contents, &listed);
    if (!entry.damage.empty()) {
        fs::remove_all(root / key, ec);
        if (ec) return Error{(root / key).string() + ": damaged (" + entry.damage + ") and cannot be removed: " + ec.message()};
        return entry;
    }
    for (const ManifestFile& f : listed) entry.files.push_back({f.name, f.size, f.hash});
    touch(root / key / manifest_name);
    entry.path = (root / key).string();
    lock->share();
    entry.hold = std::make_shared<KeyLock>(std::move(lock.value()));
    return entry;
}

Result<CacheEntry> DirectoryCache::get_or_fill(const std::string& key, const Fill& fill) {
    if (!valid_key(key)) return Error{"cache key '" + key + "': only letters, digits, '-', '_' and '.' are allowed"};
    const fs::path root(options_.directory);
    const fs::path entry_dir = root / key;
    std::error_code ec;
    fs::create_directories(root / ".staging", ec);
    if (ec) return Error{root.string() + ": cannot create the cache folder: " + ec.message()};

    // A whole entry is used under the shared lock; filling or repairing takes it exclusively.
    auto found = find(key);
    if (!found) return found.error();
    if (!found->path.empty()) return found;
    CacheEntry entry;
    entry.damage = found->damage;
    {
        auto lock = KeyLock::acquire(root / (key + ".lock"), true);
        if (!lock) return lock.error();
        if (fs::exists(entry_dir, ec)) {
            std::vector<ManifestFile> listed;
            const std::string damage = check_entry(entry_dir, options_.check_contents, &listed);
            if (damage.empty()) {  // another process filled it while this one waited
                for (const ManifestFile& f : listed) entry.files.push_back({f.name, f.size, f.hash});
                touch(entry_dir / manifest_name);
                entry.path = entry_dir.string();
                lock->share();
                entry.hold = std::make_shared<KeyLock>(std::move(lock.value()));
                return entry;
            }
            entry.damage = damage;
            fs::remove_all(entry_dir, ec);
            if (ec) return Error{entry_dir.string() + ": damaged (" + damage + ") and cannot be removed: " + ec.message()};
        }

        static std::atomic<unsigned> counter{0};
        const fs::path staging = root / ".staging" / (key + "." + std::to_string(::getpid()) + "." + std::to_string(counter++));
        fs::remove_all(staging, ec);
        fs::create_directories(staging, ec);
        if (ec) return Error{staging.string() + ": cannot create: " + ec.message()};
        auto cleanup = [&] {
            std::error_code ignore;
            fs::remove_all(staging, ignore);
        };
        Status filled = Error{"interrupted"};
        try {
            filled = fill(staging.string());
        } catch (...) {
            cleanup();  // the caller's exception (an interruption) leaves no partial entry
            throw;
        }
        if (!filled) {
            cleanup();
            return filled.error();
        }
        auto files = describe(staging);
        if (!files) {
            cleanup();
            return files.error();
        }
        {
            std::ofstream out(staging / manifest_name, std::ios::trunc);
            out << manifest_header << '\n';
            for (const auto& f : files.value()) {
                out << f.size << ' ' << f.hash << ' ' << f.name << '\n';
                entry.files.push_back({f.name, f.size, f.hash});
            }
            out.flush();
            if (!out) {
                cleanup();
                return Error{(staging / manifest_name).string() + ": cannot write"};
            }
        }
        fs::rename(staging, entry_dir, ec);
        if (ec) {
            cleanup();
            return Error{entry_dir.string() + ": cannot move the new entry into place: " + ec.message()};
        }
        entry.built = true;
        entry.path = entry_dir.string();
        lock->share();
        entry.hold = std::make_shared<KeyLock>(std::move(lock.value()));
    }
    if (Status evicted = evict(key); !evicted) return evicted.error();
    return entry;
}

Status check_cache_file(const CacheEntry& entry, const std::string& name, std::span<const std::byte> bytes) {
    for (const CacheFile& f : entry.files) {
        if (f.name != name) continue;
        if (bytes.size() != f.size_bytes)
            return Error{name + ": " + std::to_string(bytes.size()) + " bytes, the manifest says " +
                         std::to_string(f.size_bytes)};
        const std::string hash = Hash64{}.add(bytes.data(), bytes.size()).hex();
        if (hash != f.hash) return Error{name + ": contents differ from the manifest (hash " + hash + ", expected " + f.hash + ")"};
        return Ok{};
    }
    return Error{name + ": not in the manifest"};
}

Status DirectoryCache::remove(const std::string& key) {
    if (!valid_key(key)) return Error{"cache key '" + key + "': only letters, digits, '-', '_' and '.' are allowed"};
    const fs::path root(options_.directory);
    auto lock = KeyLock::acquire(root / (key + ".lock"), true);
    if (!lock) return lock.error();
    std::error_code ec;
    fs::remove_all(root / key, ec);
    if (ec) return Error{(root / key).string() + ": cannot be removed: " + ec.message()};
    return Ok{};
}

std::uint64_t DirectoryCache::size_bytes() const {
    std::uint64_t total = 0;
    std::error_code ec;
    for (fs::directory_iterator it(options_.directory, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_directory() && it->path().filename().string()[0] != '.') total += manifest_bytes(it->path());
    return total;
}

Status DirectoryCache::evict(const std::string& keep) {
    struct Candidate {
        fs::path dir;
        std::uint64_t bytes;
        fs::file_time_type used;
    };
    std::vector<Candidate> entries;
    std::uint64_t total = 0;
    std::error_code ec;
    for (fs::directory_iterator it(options_.directory, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!it->is_directory() || name[0] == '.') continue;
        const std::uint64_t bytes = manifest_bytes(it->path());
        total += bytes;
        std::error_code time_ec;
        const auto used = fs::last_write_time(it->path() / manifest_name, time_ec);
        if (name != keep) entries.push_back({it->path(), bytes, time_ec ? fs::file_time_type::min() : used});
    }
    if (ec) return Error{options_.directory + ": cannot list: " + ec.message()};
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.used < b.used; });
    for (const Candidate& c : entries) {
        if (total <= options_.max_bytes) break;
        // An entry another process holds (filling or reading it) stays.
        auto lock = KeyLock::acquire(fs::path(options_.directory) / (c.dir.filename().string() + ".lock"), false);
        if (!lock) continue;
        fs::remove_all(c.dir, ec);
        if (ec) return Error{c.dir.string() + ": cannot evict: " + ec.message()};
        total -= std::min(total, c.bytes);
    }
    return Ok{};
}

}  // namespace facet
