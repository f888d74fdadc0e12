// The on-disk cache behind the bake cache (facet/cache/directory_cache.h): atomic entries,
// damage detected and rebuilt, two processes filling one entry, LRU eviction under a bound.
#include <facet/cache/directory_cache.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace facet;

namespace {

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("facet_cache_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    return dir;
}

std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void write(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

// Writes two files whose contents follow from the key; counts its calls in `calls`.
DirectoryCache::Fill filler(const std::string& key, int* calls, size_t bytes = 1000) {
    return [=](const std::string& dir) -> Status {
        if (calls) ++*calls;
        write(fs::path(dir) / "a.bin", std::string(bytes, key.empty() ? 'x' : key[0]));
        fs::create_directories(fs::path(dir) / "sub");
        write(fs::path(dir) / "sub" / "b.json", "{\"key\": \"" + key + "\"}\n");
        return Ok{};
    };
}

}  // namespace

TEST(DirectoryCache, MissThenHitWithTheSameFiles) {
    const fs::path root = fresh_dir("hit");
    DirectoryCache cache({root.string()});
    int calls = 0;
    auto first = cache.get_or_fill("k1", filler("k1", &calls));
    ASSERT_TRUE(first) << first.error().message;
    EXPECT_TRUE(first->built);
    EXPECT_TRUE(first->damage.empty());
    auto second = cache.get_or_fill("k1", filler("k1", &calls));
    ASSERT_TRUE(second) << second.error().message;
    EXPECT_FALSE(second->built);
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(first->path, second->path);
    EXPECT_EQ(read(fs::path(second->path) / "sub" / "b.json"), "{\"key\": \"k1\"}\n");
    EXPECT_EQ(cache.size_bytes(), 1000u + read(fs::path(second->path) / "sub" / "b.json").size());
    auto found = cache.find("k1");
    ASSERT_TRUE(found);
    EXPECT_EQ(found->path, first->path);
    auto absent = cache.find("k2");
    ASSERT_TRUE(absent);
    EXPECT_TRUE(absent->path.empty());
    // No staging folder is left behind.
    EXPECT_TRUE(fs::is_empty(root / ".staging"));
    fs::remove_all(root);
}

TEST(DirectoryCache, DamagedEntriesAreReportedAndRebuiltNeverUsed) {
    const fs::path root = fresh_dir("damage");
    DirectoryCache cache({root.string()});
    int calls = 0;
    ASSERT_TRUE(cache.get_or_fill("k", filler("k", &calls)));
    const fs::path a = root / "k" / "a.bin";

    // Truncated.
    fs::resize_file(a, 10);
    auto truncated = cache.get_or_fill("k", filler("k", &calls));
    ASSERT_TRUE(truncated) << truncated.error().message;
    EXPECT_TRUE(truncated->built);
    EXPECT_NE(truncated->damage.find("a.bin: 10 bytes, the manifest says 1000"), std::string::npos) << truncated->damage;
    EXPECT_EQ(read(a), std::string(1000, 'k'));
    // This process's own hold blocks a repair: an error, not a hang.
    write(a, "short");
    auto self_held = cache.get_or_fill("k", filler("k", &calls));
    ASSERT_FALSE(self_held);
    EXPECT_NE(self_held.error().message.find("this process still holds the entry"), std::string::npos);
    truncated->hold.reset();

    // Same size, other bytes.
    write(a, std::string(999, 'k') + "!");
    auto changed = cache.get_or_fill("k", filler("k", &calls));
    ASSERT_TRUE(changed);
    EXPECT_NE(changed->damage.find("a.bin: contents differ"), std::string::npos) << changed->damage;
    EXPECT_EQ(read(a), std::string(1000, 'k'));
    changed->hold.reset();

    // A file gone, then the manifest gone (an entry someone else half-wrote).
    fs::remove(root / "k" / "sub" / "b.json");
    auto missing = cache.find("k");
    ASSERT_TRUE(missing);
    EXPECT_TRUE(missing->path.empty());
    EXPECT_NE(missing->damage.find("sub/b.json: missing"), std::string::npos) << missing->damage;
    EXPECT_FALSE(fs::exists(root / "k"));
    ASSERT_TRUE(cache.get_or_fill("k", filler("k", &calls)));
    fs::remove(root / "k" / DirectoryCache::manifest_name);
    auto no_manifest = cache.get_or_fill("k", filler("k", &calls));
    ASSERT_TRUE(no_manifest);
    EXPECT_NE(no_manifest->damage.find("no manifest"), std::string::npos) << no_manifest->damage;
    EXPECT_EQ(calls, 5);  // the refused repair built nothing
    fs::remove_all(root);
}

// check_contents off: the cache checks sizes only and hands the manifest to the reader,
// which checks what it reads (check_cache_file) and removes an entry that differs.
TEST(DirectoryCache, AReaderChecksTheContentsItReads) {
    const fs::path root = fresh_dir("reader");
    CacheOptions options{root.string()};
    options.check_contents = false;
    DirectoryCache cache(options);
    int calls = 0;
    auto filled = cache.get_or_fill("k", filler("k", &calls));
    ASSERT_TRUE(filled) << filled.error().message;
    ASSERT_EQ(filled->files.size(), 2u);
    EXPECT_EQ(filled->files[0].name, "a.bin");
    EXPECT_EQ(filled->files[0].size_bytes, 1000u);
    EXPECT_EQ(filled->files[1].name, "sub/b.json");
    filled->hold.reset();
    auto as_bytes = [](const std::string& text) {
        return std::span<const std::byte>(reinterpret_cast<const std::byte*>(text.data()), text.size());
    };

    // Same size, one byte changed: the cache (sizes only) hands it out, the reader finds it.
    write(root / "k" / "a.bin", std::string(500, 'k') + "!" + std::string(499, 'k'));
    auto hit = cache.get_or_fill("k", filler("k", &calls));
    ASSERT_TRUE(hit) << hit.error().message;
    EXPECT_FALSE(hit->built);
    EXPECT_TRUE(hit->damage.empty());
    const std::string a = read(fs::path(hit->path) / "a.bin");
    Status checked = check_cache_file(*hit, "a.bin", as_bytes(a));
    ASSERT_FALSE(checked);
    EXPECT_NE(checked.error().message.find("a.bin: contents differ from the manifest"), std::string::npos)
        << checked.error().message;
    EXPECT_TRUE(check_cache_file(*hit, "sub/b.json", as_bytes(read(fs::path(hit->path) / "sub" / "b.json"))));
    EXPECT_FALSE(check_cache_file(*hit, "c.bin", as_bytes("x")));
    EXPECT_FALSE(check_cache_file(*hit, "a.bin", as_bytes(std::string(1000, 'k') + "x")));  // a size differs

    // Removed, then built again whole.
    hit->hold.reset();
    ASSERT_TRUE(cache.remove("k"));
    EXPECT_FALSE(fs::exists(root / "k"));
    auto rebuilt = cache.get_or_fill("k", filler("k", &calls));
    ASSERT_TRUE(rebuilt) << rebuilt.error().message;
    EXPECT_TRUE(rebuilt->built);
    EXPECT_TRUE(check_cache_file(*rebuilt, "a.bin", as_bytes(read(fs::path(rebuilt->path) / "a.bin"))));
    EXPECT_EQ(calls, 2);
    // A truncated file is still found by the cache itself.
    rebuilt->hold.reset();
    fs::resize_file(root / "k" / "a.bin", 10);
    auto truncated = cache.find("k");
    ASSERT_TRUE(truncated);
    EXPECT_TRUE(truncated->path.empty());
    EXPECT_NE(truncated->damage.find("a.bin: 10 bytes"), std::string::npos) << truncated->damage;
    fs::remove_all(root);
}

TEST(DirectoryCache, AFailedFillLeavesNothing) {
    const fs::path root = fresh_dir("fail");
    DirectoryCache cache({root.string()});
    auto failed = cache.get_or_fill("k", [](const std::string& dir) -> Status {
        write(fs::path(dir) / "half.bin", "half");
        return Error{"the bake failed"};
    });
    ASSERT_FALSE(failed);
    EXPECT_EQ(failed.error().message, "the bake failed");
    EXPECT_FALSE(fs::exists(root / "k"));
    EXPECT_TRUE(fs::is_empty(root / ".staging"));
    EXPECT_THROW(cache.get_or_fill("k", [](const std::string& dir) -> Status {
        write(fs::path(dir) / "half.bin", "half");
        throw 130;  // a program's interruption unwinding through the fill
    }),
                 int);
    EXPECT_FALSE(fs::exists(root / "k"));
    EXPECT_TRUE(fs::is_empty(root / ".staging"));
    auto bad_key = cache.get_or_fill("../escape", filler("x", nullptr));
    ASSERT_FALSE(bad_key);
    EXPECT_NE(bad_key.error().message.find("only letters, digits"), std::string::npos);
    fs::remove_all(root);
}

// Two processes ask for the same missing entry at once: one fills, the other waits for
// the lock and finds it whole; both see identical, valid files.
TEST(DirectoryCache, TwoProcessesFillingOneEntryBothGetIdenticalValidFiles) {
    const fs::path root = fresh_dir("race");
    const fs::path log = root.string() + ".fills";
    fs::remove(log);
    pid_t children[2];
    for (pid_t& child : children) {
        child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            DirectoryCache cache({root.string()});
            auto entry = cache.get_or_fill("shared", [&](const std::string& dir) -> Status {
                std::ofstream(log, std::ios::app) << ::getpid() << '\n';
                std::this_thread::sleep_for(std::chrono::milliseconds(300));  // hold the fill open
                return filler("shared", nullptr, 200000)(dir);
            });
            const bool ok = entry && read(fs::path(entry->path) / "a.bin") == std::string(200000, 's');
            ::_exit(ok ? 0 : 1);
        }
    }
    for (pid_t child : children) {
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ASSERT_TRUE(WIFEXITED(status));
        EXPECT_EQ(WEXITSTATUS(status), 0);
    }
    // Exactly one fill ran.
    std::ifstream in(log);
    int lines = 0;
    for (std::string line; std::getline(in, line);) ++lines;
    EXPECT_EQ(lines, 1);
    DirectoryCache cache({root.string()});
    auto entry = cache.find("shared");
    ASSERT_TRUE(entry);
    EXPECT_FALSE(entry->path.empty());
    EXPECT_TRUE(entry->damage.empty());
    fs::remove_all(root);
    fs::remove(log);
}

TEST(DirectoryCache, LeastRecentlyUsedEntriesGoFirstAndHeldOnesStay) {
    const fs::path root = fresh_dir("lru");
    // Room for three entries of ~1 KB.
    DirectoryCache cache({root.string(), 3 * 1100});
    auto step = [] { std::this_thread::sleep_for(std::chrono::milliseconds(20)); };
    for (const char* key : {"a", "b", "c"}) {
        ASSERT_TRUE(cache.get_or_fill(key, filler(key, nullptr)));
        step();
    }
    ASSERT_TRUE(cache.find("a"));  // a is now the most recent; b the least
    step();
    ASSERT_TRUE(cache.get_or_fill("d", filler("d", nullptr)));
    EXPECT_TRUE(fs::exists(root / "a"));
    EXPECT_FALSE(fs::exists(root / "b"));
    EXPECT_TRUE(fs::exists(root / "c"));
    EXPECT_TRUE(fs::exists(root / "d"));
    EXPECT_LE(cache.size_bytes(), 3u * 1100u);
    step();

    // A reader holds c; a and d are used after it, so c is the least recent, yet e's
    // fill evicts a instead.
    auto held = cache.find("c");
    ASSERT_TRUE(held);
    step();
    ASSERT_TRUE(cache.find("a"));
    step();
    ASSERT_TRUE(cache.find("d"));
    step();
    ASSERT_TRUE(cache.get_or_fill("e", filler("e", nullptr)));
    EXPECT_TRUE(fs::exists(root / "c"));
    EXPECT_FALSE(fs::exists(root / "a"));
    EXPECT_TRUE(fs::exists(root / "d"));
    EXPECT_TRUE(fs::exists(root / "e"));
    // Released, c goes first under a tighter bound.
    held->hold.reset();
    DirectoryCache tighter({root.string(), 2 * 1100});
    ASSERT_TRUE(tighter.evict("e"));
    EXPECT_FALSE(fs::exists(root / "c"));
    EXPECT_TRUE(fs::exists(root / "d"));
    fs::remove_all(root);
}

TEST(DirectoryCache, DefaultFolderFollowsXdg) {
    EXPECT_EQ(default_cache_directory("/x/cache", "/home/u").value(), "/x/cache/facet");
    EXPECT_EQ(default_cache_directory("", "/home/u").value(), "/home/u/.cache/facet");
    EXPECT_EQ(default_cache_directory("relative", "/home/u").value(), "/home/u/.cache/facet");
    EXPECT_FALSE(default_cache_directory("", ""));
}
