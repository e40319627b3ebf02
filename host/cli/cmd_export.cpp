#include "cmd_export.h"

#include "args.h"
#include "python_tool.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace gonio {

int cmd_export(int argc, char** argv) {
    std::vector<std::string> args;
    std::string dir, format, out;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](const char* opt) {
            if (i + 1 >= argc) usage_error(std::string(opt) + " needs a value");
            return std::string(argv[++i]);
        };
        if (a == "--format")
            format = value("--format");
        else if (a == "--out")
            out = value("--out");
        else if (a == "--source")
            args.insert(args.end(), {"--source", value("--source")});
        else if (a.rfind("--", 0) == 0)
            usage_error("unknown option " + a + " for export (it takes --format, --out, --source)");
        else if (dir.empty())
            dir = a;
        else
            usage_error("export takes one output directory, got '" + dir + "' and '" + a + "'");
    }
    if (dir.empty()) usage_error("export: which simulate / compare output directory?");
    if (format != "merl" && format != "rgl-bsdf") usage_error("export: --format merl or --format rgl-bsdf");
    if (out.empty()) usage_error("export: --out FILE");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(std::filesystem::path(dir) / "summary.json", ec))
        usage_error("export: " + dir + " holds no summary.json (a gonio simulate or compare output)");
    args.insert(args.begin(), {dir, "--format", format, "--out", out});
    const int status = run_python_command("export.py", args);
    if (status == 127)
        std::fprintf(stderr, "gonio: could not run %s (set GONIO_PYTHON)\n", python_interpreter().c_str());
    return status;
}

}   // namespace gonio
