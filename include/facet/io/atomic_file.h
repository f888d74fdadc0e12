#pragma once
// Outputs appear whole or not at all: write to a temporary name in the same directory,
// then rename (atomic on POSIX file systems). A failed or interrupted write leaves no
// partial file under the final name. Runs that write several files make them appear
// together with an OutputSet (io/output_set.h).
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include <facet/core/result.h>

namespace facet {

// The hidden name a new (kind "partial") or previous (kind "previous") version of `path`
// lives under beside it: ".STEM.KIND-PID.EXT" (same folder, so a rename is atomic; same
// extension, as writers choose the format by it). Only a process killed outright
// (SIGKILL, power loss) leaves such a file behind, never a partial file under `path`.
std::string temporary_path(const std::string& path, const char* kind = "partial");

// Calls write(temp_path); renames temp_path to `path` when it succeeds, removes it when
// it fails or throws. The temporary keeps the extension (writers choose format by it).
Status write_atomically(const std::string& path, const std::function<Status(const std::string&)>& write);

// Writes text (JSON, logs) atomically.
Status write_text_file(const std::string& path, const std::string& text);
// Writes bytes (a file encoded ahead, io/image_io.h encode_hdr_image) atomically.
Status write_binary_file(const std::string& path, std::span<const uint8_t> bytes);

// Creates `dir` and its parents; an error names the directory and the reason
// (exists as a file, permission denied, ...).
Status ensure_directory(const std::string& dir);

}  // namespace facet
