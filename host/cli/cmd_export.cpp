#include "cmd_export.h"
#include "input_file.h"

#include "python_tool.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace gonio {

namespace {

struct ExportSettings {
    std::string format, out;
    std::vector<std::string> source;   // --source ID, handed on to tools/export.py
};

OptionTable export_options(ExportSettings& a) {
    return {
        {"--format", "merl|rgl-bsdf",
         "MERL .binary (BRDF Explorer, libbsdf) or RGL .bsdf (Mitsuba 3's measured; needs pip's mitsuba)",
         [&a](const std::string& v) { a.format = v; }},
        {"--out", "FILE", "the file to write (required)", [&a](const std::string& v) { a.out = v; }},
        {"--source", "reference|MODEL_ID",
         "what to export: the reference or a model of a compare run (default "
         "reference)",
         [&a](const std::string& v) {
             a.source = {"--source", v};
         }},
    };
}

int run_export(ExportSettings& a, const std::vector<std::string>& operands) {
    if (operands.empty()) usage_error("export: which simulate / compare output directory?");
    if (operands.size() > 1)
        usage_error("export takes one output directory, got '" + operands[0] + "' and '" + operands[1] + "'");
    const std::string& dir = operands[0];
    if (a.format != "merl" && a.format != "rgl-bsdf") usage_error("export: --format merl or --format rgl-bsdf");
    if (a.out.empty()) usage_error("export: --out FILE");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(std::filesystem::path(dir) / "summary.json", ec))
        usage_error("export: " + dir + " holds no summary.json (a gonio simulate or compare output)");
    // the run's own files are its input: --out may not overwrite one (DIR/state.gonio destroyed its source)
    const std::filesystem::path out_path(a.out);
    if (std::filesystem::exists(out_path, ec) &&
        same_path(out_path.parent_path().empty() ? "." : out_path.parent_path().string(), dir))
        usage_error("export: --out " + a.out + " is a file of " + dir + ", the run it reads: give another");
    std::vector<std::string> args = {dir, "--format", a.format, "--out", a.out};
    args.insert(args.end(), a.source.begin(), a.source.end());
    const int status = run_python_command("export.py", args);
    if (status == 127)
        std::fprintf(stderr, "gonio: could not run %s (set GONIO_PYTHON)\n", python_interpreter().c_str());
    return status;
}

}   // namespace

Command export_command() {
    return {"export", "DIR --format merl|rgl-bsdf --out FILE [--source reference|MODEL_ID]",
            "a simulate / compare output over incident angles 0 to >= 80 degrees, at most 5 apart (--theta-i "
            "0,2,...,88), as a file renderers read: MERL .binary (BRDF Explorer, libbsdf) or RGL .bsdf (Mitsuba 3's "
            "measured; needs pip's mitsuba); runs tools/export.py (python/gonio)",
            "", invocation(&export_options, &run_export)};
}

}   // namespace gonio
