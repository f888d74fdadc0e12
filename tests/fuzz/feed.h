#pragma once
// One function per fuzz target that hands an input to the real parser and checks the
// parser's contract on what comes back: an Error that names the file, or a result that
// holds what the loader promises (indices in range, finite values, ...); each returns
// whether the parser accepted the input. A broken
// contract throws ContractBroken; the fuzz targets let it escape (libFuzzer reports the
// abort as a crash), tests/fuzz_regressions_test.cpp expects none.
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include <facet/core/result.h>

namespace facet::fuzz {

using Bytes = std::span<const uint8_t>;

struct ContractBroken : std::logic_error {
    using std::logic_error::logic_error;
};

// glTF (.gltf JSON) or .glb (by its magic) through load_gltf. The input's directory also
// holds buffer.bin and texture.png, so that external uris resolve.
bool feed_gltf(Bytes input);
// An environment image (.hdr, .exr, .png, ... named by its magic) through
// load_environment, with sanitising off and on.
bool feed_environment(Bytes input);
// read_ktx2; a file that reads must write and read back identically.
bool feed_ktx2(Bytes input);
// A command line: the first line names the parser (facet-bake, facet-render,
// facet-viewer, facet-bench, light, views), each further line is one argument.
bool feed_cli(Bytes input);

// A private directory for the inputs: /dev/shm/facet-fuzz-<pid> (no disk writes), else
// under the system's temporary directory; removed at exit.
const std::string& work_dir();
// Writes the input to work_dir()/name and returns the path.
std::string write_input(Bytes input, const std::string& name);

// Every failure a user can cause is one message naming the file first (design.md).
void expect_names_file(const Error& error, const std::string& path);

}  // namespace facet::fuzz

// Checks one promise; the message is built only when it is broken.
#define FACET_FUZZ_EXPECT(condition, message)                                                       \
    do {                                                                                           \
        if (!(condition)) throw ::facet::fuzz::ContractBroken(std::string(__FILE__ ":") +         \
                                                               std::to_string(__LINE__) + ": " + \
                                                               (message));                        \
    } while (0)
