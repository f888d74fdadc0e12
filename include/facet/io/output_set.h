#pragma once
// All-or-nothing outputs of one run (facet-bake's KTX2 files and bake.json, facet-render's
// image, views and NAME.json): every file is written to a temporary first, and only when
// all are written does commit() move them into place. A run that fails or stops before
// the commit leaves the files of an earlier run byte-identical and no temporary behind
// (the destructor removes them).
//
// The last file staged is the set's marker (bake.json, NAME.json): its old version goes
// before any other file is replaced and the new one arrives last, so a marker on disk
// always describes the files beside it. A process killed outright (SIGKILL, power loss)
// can leave only hidden temporaries (io/atomic_file.h: ".NAME.partial-PID.EXT", or
// ".NAME.previous-PID.EXT" during the commit's few renames) and, if it dies inside the
// commit, old and new whole files side by side without a marker; the next run over the
// same outputs removes the temporaries of dead processes.
#include <string>
#include <vector>

#include <facet/core/result.h>

namespace facet {

class OutputSet {
public:
    OutputSet() = default;
    ~OutputSet();
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;

    // The temporary to write the new `path` to (temporary_path(path)).
    std::string stage(const std::string& path);
    // `path`, left by an earlier run and not made by this one, disappears with the commit.
    void remove_with_commit(const std::string& path);

    // Moves every staged file into place in the order staged (the marker last) and
    // removes the files named by remove_with_commit. If a step fails, the files are put
    // back as they were and the error names the file. Signals are the caller's business:
    // programs that handle them block them around this (apps/interrupt.h).
    Status commit();

    // Staged temporaries that exist now (before the commit).
    std::vector<std::string> temporaries() const;
    bool committed() const { return committed_; }

private:
    struct Staged {
        std::string path, temp;
    };
    std::vector<Staged> staged_;
    std::vector<std::string> removals_;
    bool committed_ = false;
};

// Removes hidden temporaries of `path` (".STEM.partial-PID.EXT", ".STEM.previous-PID.EXT")
// left by processes that no longer run; returns how many.
size_t remove_stale_temporaries(const std::string& path);

}  // namespace facet
