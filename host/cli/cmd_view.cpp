#include "cmd_view.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace gonio {

// The viewer is its own binary, so that gonio needs no display libraries.
int cmd_view(int argc, char** argv) {
    std::error_code ec;
    fs::path self = fs::read_symlink("/proc/self/exe", ec);
    fs::path viewer = (ec ? fs::path(argv[0]) : self).parent_path() / "gonio-view";
    if (!fs::exists(viewer)) {
        std::fprintf(stderr,
                     "gonio view: the viewer was not built (%s is missing): it needs GLFW and Dear ImGui "
                     "(Debian: apt-get install libglfw3-dev libimgui-dev libstb-dev), then ./run build\n",
                     viewer.c_str());
        return 1;
    }
    std::vector<char*> args{const_cast<char*>(viewer.c_str())};
    for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
    args.push_back(nullptr);
    execv(viewer.c_str(), args.data());
    std::fprintf(stderr, "gonio view: cannot run %s: %s\n", viewer.c_str(), std::strerror(errno));
    return 1;
}

}   // namespace gonio
