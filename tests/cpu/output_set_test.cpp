// OutputSet (io/output_set.h): a run's files appear together at the commit or not at all;
// a set dropped before its commit leaves the earlier files byte-identical and no
// temporary; a commit that cannot start names the file and replaces nothing; leftovers of
// killed processes are cleared by the next run over the same outputs.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>

#include <facet/io/atomic_file.h>
#include <facet/io/output_set.h>
#include "support/output_files.h"

namespace {

using namespace facet;
using namespace facet::test;

void write(const std::string& path, const std::string& text) { ASSERT_TRUE(write_text_file(path, text)); }

TEST(OutputSet, CommitMovesEveryFileAndRemovesWhatTheRunNoLongerMakes) {
    TempDir dir("output_set_commit");
    write((dir / "a.txt").string(), "old a");
    write((dir / "stale.json").string(), "old stale");
    write((dir / "marker.json").string(), "old marker");
    OutputSet set;
    const std::string a = set.stage((dir / "a.txt").string()), b = set.stage((dir / "b.exr").string()),
                      marker = set.stage((dir / "marker.json").string());
    EXPECT_EQ(fs::path(a).filename().string(), ".a.partial-" + std::to_string(::getpid()) + ".txt");
    EXPECT_EQ(fs::path(b).extension(), ".exr");  // writers choose the format by it
    write(a, "new a");
    write(b, "new b");
    write(marker, "new marker");
    set.remove_with_commit((dir / "stale.json").string());
    EXPECT_EQ(set.temporaries().size(), 3u);
    EXPECT_EQ(file_bytes(dir / "a.txt"), "old a");
    ASSERT_TRUE(set.commit());
    const auto files = snapshot(dir.path);
    EXPECT_EQ(names(files), (std::vector<std::string>{"a.txt", "b.exr", "marker.json"}));
    EXPECT_EQ(files.at("a.txt"), "new a");
    EXPECT_EQ(files.at("b.exr"), "new b");
    EXPECT_EQ(files.at("marker.json"), "new marker");
}

TEST(OutputSet, DroppedBeforeTheCommitLeavesTheEarlierFilesAndNoTemporary) {
    TempDir dir("output_set_dropped");
    write((dir / "a.txt").string(), "old a");
    write((dir / "marker.json").string(), "old marker");
    const auto before = snapshot(dir.path);
    {
        OutputSet set;
        write(set.stage((dir / "a.txt").string()), "new a");
        write(set.stage((dir / "new.txt").string()), "new");
        set.stage((dir / "marker.json").string());  // never written: the run stopped
        EXPECT_EQ(snapshot(dir.path).size(), 4u);
    }
    EXPECT_TRUE(snapshot(dir.path) == before);
}

TEST(OutputSet, ACommitThatCannotStartReplacesNothing) {
    TempDir dir("output_set_refused");
    write((dir / "a.txt").string(), "old a");
    fs::create_directories(dir / "b.txt" / "in the way");
    write((dir / "marker.json").string(), "old marker");
    const auto before = snapshot(dir.path);
    {
        OutputSet set;
        write(set.stage((dir / "a.txt").string()), "new a");
        write(set.stage((dir / "b.txt").string()), "new b");
        write(set.stage((dir / "marker.json").string()), "new marker");
        Status s = set.commit();
        ASSERT_FALSE(s);
        EXPECT_NE(s.error().message.find("b.txt: is a directory"), std::string::npos) << s.error().message;
        EXPECT_FALSE(set.committed());
    }
    EXPECT_TRUE(snapshot(dir.path) == before);
    {
        OutputSet set;
        set.stage((dir / "a.txt").string());  // staged, never written
        Status s = set.commit();
        ASSERT_FALSE(s);
        EXPECT_NE(s.error().message.find("a.txt: the new file was not written"), std::string::npos);
    }
    EXPECT_TRUE(snapshot(dir.path) == before);
}

TEST(OutputSet, TemporariesOfKilledProcessesAreClearedByTheNextRun) {
    TempDir dir("output_set_stale");
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ASSERT_GT(child, 0);
    int raw;
    ::waitpid(child, &raw, 0);  // gone: its pid names the leftovers of a killed run
    const std::string dead = std::to_string(child), alive = std::to_string(::getppid());
    for (const std::string name : {".a.partial-" + dead + ".exr", "..a.partial-" + dead + ".partial-" + dead + ".exr",
                                   ".a.previous-" + dead + ".exr", ".a.partial-" + alive + ".exr",
                                   ".ab.partial-" + dead + ".exr", ".a.partial-" + dead + ".png"})
        std::ofstream(dir / name) << "left";
    EXPECT_EQ(remove_stale_temporaries((dir / "a.exr").string()), 3u);
    std::vector<std::string> kept = {".a.partial-" + alive + ".exr", ".a.partial-" + dead + ".png",
                                     ".ab.partial-" + dead + ".exr"};
    std::sort(kept.begin(), kept.end());  // as the snapshot lists them, whatever the digits
    EXPECT_EQ(names(snapshot(dir.path)), kept);
}

}  // namespace
