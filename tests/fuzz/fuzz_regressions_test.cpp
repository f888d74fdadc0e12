// The fuzz targets' inputs through the real parsers in every build, no clang needed
// (tests/fuzz/feed.h): each seed of tests/fuzz/corpus is accepted, or refused with an
// error naming the file when its name starts with bad_; each input a fuzz run once broke
// (tests/fuzz/regressions) is handled, accepted or refused, with every check holding.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "feed.h"

namespace fs = std::filesystem;
using namespace facet::fuzz;

namespace {

struct Target {
    const char* name;
    bool (*feed)(Bytes);
};

constexpr Target kTargets[] = {
    {"gltf", feed_gltf}, {"environment", feed_environment}, {"ktx2", feed_ktx2}, {"cli", feed_cli}};

std::vector<fs::path> inputs(const std::string& folder, const char* target) {
    std::vector<fs::path> files;
    const fs::path dir = fs::path(FACET_FUZZ_DIR) / folder / target;
    if (!fs::is_directory(dir)) return files;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file() && entry.path().filename().string().rfind("README", 0) != 0)
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<uint8_t> read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(FuzzCorpus, SeedsAreAcceptedUnlessNamedBad) {
    for (const Target& target : kTargets) {
        const std::vector<fs::path> seeds = inputs("corpus", target.name);
        EXPECT_GE(seeds.size(), 10u) << target.name << ": the corpus is missing";
        for (const fs::path& seed : seeds) {
            SCOPED_TRACE(seed.string());
            const bool bad = seed.filename().string().rfind("bad_", 0) == 0;
            bool accepted = false;
            EXPECT_NO_THROW(accepted = target.feed(read(seed)));
            EXPECT_EQ(accepted, !bad) << (bad ? "a malformed seed was accepted" : "a valid seed was refused");
        }
    }
}

TEST(FuzzRegressions, EveryInputIsHandled) {
    for (const Target& target : kTargets)
        for (const fs::path& input : inputs("regressions", target.name)) {
            SCOPED_TRACE(input.string());
            EXPECT_NO_THROW(target.feed(read(input)));
        }
}
