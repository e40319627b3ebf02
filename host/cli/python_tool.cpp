#include "python_tool.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace fs = std::filesystem;

namespace gonio {

void run_python_tool(const std::string& script, const std::string& dir, const std::string& what) {
    const char* env = std::getenv("GONIO_PYTHON");
    std::string python = env ? env : (fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3");
    std::string cmd = "'" + python + "' '" + std::string(GONIO_SOURCE_DIR) + "/tools/" + script + "' '" + dir + "'";
    if (std::system(cmd.c_str()) != 0)
        std::fprintf(stderr, "gonio: warning: %s not made (%s failed; it needs Python 3 with matplotlib: apt-get install "
                     "python3-matplotlib, or set GONIO_PYTHON). The numbers are complete.\n", what.c_str(), cmd.c_str());
}

}  // namespace gonio
