// input_file.h: a file from outside (a stack, sweep, model or values file, an #include) read as data: only a regular
// file (not a directory, a device or a FIFO), and only up to a size, both refused with the reason before anything is
// read, so that /dev/zero or a runaway file cannot make gonio read without bound.
#pragma once
#include <cstdint>
#include <string>

namespace gonio {

// The largest text file gonio reads whole: a stack, sweep, model or #include file (the shipped ones are under 40 KiB)
constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t(4) << 20;
// The largest values file (`gonio score`: a row per node; a million nodes in text is about 60 MB)
constexpr std::uintmax_t kMaxValuesFileBytes = std::uintmax_t(1) << 30;

// "" where `path` is a regular file of at most max_bytes, else why not ("is a directory, not a file", "is 5 GiB; a
// stack file is at most 4 MiB").
std::string input_file_refusal(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

// The whole file, where input_file_refusal is ""; else throws StackError(path, 0, why) (stack.h: "PATH:0: why").
// Reads at most max_bytes + 1 bytes (a file that grows while it is read is refused too). what: "stack file", ...
std::string read_input_file(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes = kMaxTextFileBytes);

// Whether two paths name the same file or directory (an output that would overwrite an input of the same command):
// the same existing file, or the same path once made absolute and normal
bool same_path(const std::string& a, const std::string& b);

// "4 MiB", "1.5 GiB", "812 bytes"
std::string byte_size_text(std::uintmax_t bytes);

}   // namespace gonio
