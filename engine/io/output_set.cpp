#include <facet/io/output_set.h>

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>

#include <facet/core/result.h>
#include <facet/io/atomic_file.h>

namespace facet {

namespace {

namespace fs = std::filesystem;

bool exists(const std::string& path) {
    std::error_code ec;
    return fs::exists(fs::symlink_status(path, ec));
}

void remove_quietly(const std::string& path) {
    std::error_code ignored;
    fs::remove(path, ignored);
}

// "STEM(.partial-PID|.previous-PID)+EXT" -> the PIDs; empty when `name` is not one.
std::vector<long> temporary_pids(std::string_view name, std::string_view stem, std::string_view ext) {
    std::vector<long> pids;
    if (name.substr(0, stem.size()) != stem) return {};
    name.remove_prefix(stem.size());
    for (;;) {
        if (name == ext) return pids;
        bool matched = false;
        for (std::string_view kind : {".partial-", ".previous-"})
            if (name.substr(0, kind.size()) == kind) {
                name.remove_prefix(kind.size());
                matched = true;
            }
        if (!matched) return {};
        size_t digits = 0;
        long pid = 0;
        while (digits < name.size() && digits < 10 && name[digits] >= '0' && name[digits] <= '9')
            pid = pid * 10 + (name[digits++] - '0');
        if (digits == 0) return {};
        pids.push_back(pid);
        name.remove_prefix(digits);
    }
}

bool process_gone(long pid) { return pid != ::getpid() && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH; }

}  // namespace

size_t remove_stale_temporaries(const std::string& path) {
    const fs::path target(path);
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    const std::string stem = target.stem().string(), ext = target.extension().string();
    size_t removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.size() < 2 || name[0] != '.') continue;
        // One dot hides a temporary; a temporary's own temporary (write_atomically of a
        // staged file) has two.
        std::vector<long> pids = temporary_pids(std::string_view(name).substr(1), stem, ext);
        if (pids.empty() && name[1] == '.') pids = temporary_pids(std::string_view(name).substr(2), stem, ext);
        if (pids.empty()) continue;
        bool stale = true;
        for (long pid : pids) stale = stale && process_gone(pid);
        if (stale && fs::remove(it->path(), ec)) ++removed;
    }
    return removed;
}

OutputSet::~OutputSet() {
    if (!committed_)
        for (const Staged& s : staged_) remove_quietly(s.temp);
}

std::string OutputSet::stage(const std::string& path) {
    for (const Staged& s : staged_)
        if (s.path == path) throw UsageError(path + ": staged twice in one output set");
    remove_stale_temporaries(path);
    staged_.push_back({path, temporary_path(path)});
    remove_quietly(staged_.back().temp);
    return staged_.back().temp;
}

void OutputSet::remove_with_commit(const std::string& path) { removals_.push_back(path); }

std::vector<std::string> OutputSet::temporaries() const {
    std::vector<std::string> out;
    if (!committed_)
        for (const Staged& s : staged_)
            if (exists(s.temp)) out.push_back(s.temp);
    return out;
}

Status OutputSet::commit() {
    if (committed_) throw UsageError("an output set commits once");
    for (const Staged& s : staged_) {
        if (!exists(s.temp)) return Error{s.path + ": the new file was not written; nothing was replaced"};
        std::error_code ec;
        if (fs::is_directory(s.path, ec)) return Error{s.path + ": is a directory; nothing was replaced"};
    }
    // Every file the commit replaces or removes keeps a second name until the end, so a
    // failure halfway can put the old set back (a hard link costs nothing; a copy where
    // the file system has none).
    struct Previous {
        std::string path, backup;
    };
    std::vector<Previous> previous;
    auto drop_backups = [&] {
        for (const Previous& p : previous) remove_quietly(p.backup);
    };
    std::vector<std::string> replaced;
    for (const Staged& s : staged_) replaced.push_back(s.path);
    replaced.insert(replaced.end(), removals_.begin(), removals_.end());
    for (const std::string& path : replaced) {
        if (!exists(path)) continue;
        const std::string backup = temporary_path(path, "previous");
        remove_quietly(backup);
        if (::link(path.c_str(), backup.c_str()) != 0) {
            std::error_code ec;
            fs::copy_file(path, backup, fs::copy_options::overwrite_existing, ec);
            if (ec) {
                drop_backups();
                return Error{path + ": cannot keep the previous version while replacing it: " + ec.message() +
                             "; nothing was replaced"};
            }
        }
        previous.push_back({path, backup});
    }
    size_t moved = 0;
    auto restore = [&] {
        for (size_t i = 0; i < moved; ++i) remove_quietly(staged_[i].path);
        for (const Previous& p : previous) {
            std::error_code ec;
            fs::rename(p.backup, p.path, ec);
        }
    };
    // The marker's old version first, then the removals, then the new files in order.
    std::error_code ec;
    if (!staged_.empty()) fs::remove(staged_.back().path, ec);
    for (const std::string& path : removals_)
        if (!ec) fs::remove(path, ec);
    if (ec) {
        restore();
        return Error{"cannot remove a previous output: " + ec.message() + "; the previous files are restored"};
    }
    for (; moved < staged_.size(); ++moved) {
        fs::rename(staged_[moved].temp, staged_[moved].path, ec);
        if (ec) {
            const std::string path = staged_[moved].path;
            restore();
            return Error{path + ": cannot move the new file into place: " + ec.message() +
                         "; the previous files are restored"};
        }
    }
    drop_backups();
    committed_ = true;
    return Ok{};
}

}  // namespace facet
