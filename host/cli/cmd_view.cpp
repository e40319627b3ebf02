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

namespace {

// The viewer is its own binary, so that gonio needs no display libraries; its arguments, --help too, are its own.
int run_view(NoSettings&, const std::vector<std::string>& arguments) {
    std::error_code ec;
    fs::path self = fs::read_symlink("/proc/self/exe", ec);
    fs::path viewer = (ec ? fs::path(program_invocation_name) : self).parent_path() / "gonio-view";
    if (!fs::exists(viewer)) {
        std::fprintf(stderr,
                     "gonio view: the viewer was not built (%s is missing): it needs GLFW and Dear ImGui "
                     "(Debian: apt-get install libglfw3-dev libimgui-dev libstb-dev), then ./run build\n",
                     viewer.c_str());
        return 1;
    }
    std::vector<char*> args{const_cast<char*>(viewer.c_str())};
    for (const std::string& a : arguments) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(viewer.c_str(), args.data());
    std::fprintf(stderr, "gonio view: cannot run %s: %s\n", viewer.c_str(), std::strerror(errno));
    return 1;
}

}   // namespace

Command view_command() {
    Command c{"view", "STACK.toml [options]",
              "the interactive viewer (a window; runs gonio-view, built beside gonio when GLFW and Dear ImGui are "
              "installed; gonio view --help)",
              "", invocation(&no_options, &run_view)};
    c.passes_arguments_on = true;
    return c;
}

}   // namespace gonio
