#include "python_tool.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace fs = std::filesystem;

namespace gonio {

namespace {

// 'text' for the shell, a quote inside written as '\''
std::string shell_quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

}   // namespace

std::string python_interpreter() {
    if (const char* env = std::getenv("GONIO_PYTHON")) return env;
    std::error_code ec;
    const fs::path venv = fs::read_symlink("/proc/self/exe", ec).parent_path() / "venv" / "bin" / "python";
    if (!ec && fs::exists(venv, ec)) return venv.string();
    return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

namespace {

std::string python_command_line(const std::string& script, const std::vector<std::string>& args) {
    std::string cmd =
        shell_quoted(python_interpreter()) + " " + shell_quoted(std::string(GONIO_SOURCE_DIR) + "/tools/" + script);
    for (const auto& a : args) cmd += " " + shell_quoted(a);
    return cmd;
}

}   // namespace

int run_python_command(const std::string& script, const std::vector<std::string>& args) {
    // what gonio printed so far goes out before the tool's own lines (stdout into a file is block-buffered: the
    // tool's "wrote ..." landed inside a line of compare's table)
    std::cout.flush();
    std::fflush(nullptr);
    const int status = std::system(python_command_line(script, args).c_str());
    if (status == -1) return 127;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

void run_python_tool(const std::string& script, const std::string& dir, const std::string& what) {
    if (run_python_command(script, {dir}) != 0)
        std::fprintf(stderr,
                     "gonio: warning: %s not made (%s failed; it needs Python 3 with matplotlib: apt-get install "
                     "python3-matplotlib, or set GONIO_PYTHON). The numbers are complete.\n",
                     what.c_str(), python_command_line(script, {dir}).c_str());
}

}   // namespace gonio
