// Reading input files safely: only regular files are read (a FIFO, a device or a folder given as
// an input is refused at once instead of hanging or failing obscurely), text inputs have a size
// bound, and every file is read once per run — its bytes' digest is kept for the render's
// fingerprint, so what was parsed is what is fingerprinted.
#pragma once

#include <cstdint>
#include <string>

namespace arbor {

// The largest text inputs arbor reads (docs/rendering.md, "Input limits"): TOML files (scenes,
// species) are written by hand and stay under 16 MiB; the other tree formats (L-system, template,
// skeleton, Arbaro XML) under 256 MiB; OBJ meshes under 2 GiB (the OBJ of a big tree is a few
// hundred MB). The largest shipped input is a few kB.
constexpr std::uint64_t kMaxTomlBytes = 16ull << 20;
constexpr std::uint64_t kMaxTextInputBytes = 256ull << 20;
constexpr std::uint64_t kMaxMeshBytes = 2048ull << 20;

// What a file that is not a regular file is, for messages: "a folder", "a FIFO (named pipe)",
// "a device", "a socket" (`mode` is stat's st_mode).
std::string file_kind(unsigned mode);

// "" when `path` names a regular file this process can read (after symlinks), else why not:
// "does not exist", "is a folder, not a file", "is a FIFO (named pipe), not a file", …
std::string input_file_problem(const std::string& path);

// InputError naming `path` unless it names an existing regular file (after symlinks): a missing
// file, a folder, a FIFO, a device or a socket is refused. `what` says what the file is for
// ("species", "bump map"); it starts the message: "PATH: error: species is a folder, not a file".
void check_input_file(const std::string& path, const std::string& what);

// The whole text of `path`, checked as above and bounded by kMaxTextInputBytes (InputError
// naming the file and its size past `max_bytes`). The bytes' digest is remembered (input_digest).
std::string read_text_input(const std::string& path, const std::string& what,
                            std::uint64_t max_bytes = kMaxTextInputBytes);

// A 64-bit hash of the bytes of `path`: those read by read_text_input when it read the file in
// this run, else read now (regular files only: InputError otherwise).
std::uint64_t input_digest(const std::string& path, const std::string& what);

// 64-bit FNV-1a of `size` bytes continued from `hash`.
std::uint64_t fnv1a_bytes(const void* data, std::size_t size,
                          std::uint64_t hash = 0xcbf29ce484222325ull);

}  // namespace arbor
