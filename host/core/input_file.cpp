#include "input_file.h"
#include "stack.h"   // StackError

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

namespace gonio {

namespace fs = std::filesystem;

std::string byte_size_text(std::uintmax_t bytes) {
    char buf[64];
    if (bytes < 1024) return std::to_string(bytes) + " bytes";
    const char* units[] = {"KiB", "MiB", "GiB", "TiB"};
    double v = double(bytes) / 1024;
    int u = 0;
    while (v >= 1024 && u < 3) v /= 1024, ++u;
    std::snprintf(buf, sizeof buf, "%.3g %s", v, units[u]);
    return buf;
}

bool same_path(const std::string& a, const std::string& b) {
    std::error_code ec1, ec2;
    if (fs::exists(a, ec1) && fs::exists(b, ec2)) {
        std::error_code ec;
        const bool same = fs::equivalent(a, b, ec);
        if (!ec) return same;
    }
    std::error_code ea, eb;
    const fs::path pa = fs::weakly_canonical(fs::absolute(a), ea), pb = fs::weakly_canonical(fs::absolute(b), eb);
    return !ea && !eb && pa == pb;
}

std::string input_file_refusal(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) return "cannot open the " + what + " for reading (no such file)";
    if (fs::is_directory(st)) return "is a directory, not a " + what;
    if (!fs::is_regular_file(st))
        return "is not a regular file (a device, a FIFO or a socket); a " + what + " is read from a file";
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) return "cannot read the size of the " + what;
    if (size > max_bytes)
        return "is " + byte_size_text(size) + "; a " + what + " is at most " + byte_size_text(max_bytes);
    return "";
}

std::string read_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
    const std::string why = input_file_refusal(path, what, max_bytes);
    if (!why.empty()) throw StackError(path, 0, why);
    std::ifstream f(path, std::ios::binary);
    if (!f) throw StackError(path, 0, "cannot open the " + what + " for reading");
    std::string text;
    std::vector<char> chunk(1 << 16);
    while (f) {
        f.read(chunk.data(), std::streamsize(chunk.size()));
        text.append(chunk.data(), size_t(f.gcount()));
        if (text.size() > max_bytes)
            throw StackError(path, 0,
                             "grew beyond " + byte_size_text(max_bytes) + " while read; a " + what + " is at most " +
                                 byte_size_text(max_bytes));
    }
    if (f.bad()) throw StackError(path, 0, "cannot read the " + what);
    return text;
}

}   // namespace gonio
