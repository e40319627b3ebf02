#include "cmd_random_stack.h"
#include "common_options.h"
#include "output.h"
#include "random_stack.h"
#include "stack.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace gonio {

namespace {

struct RandomStackSettings {
    uint32_t seed = 1;
    uint64_t count = 1;
    std::string out;   // "": print to stdout
};

OptionTable random_stack_options(RandomStackSettings& a) {
    return {
        seed_option(a.seed, "which stacks: the same seed, the same stacks (default 1)"),
        {"--count", "K", "how many stacks, 1 to 100000 (default 1)",
         [&a](const std::string& v) { a.count = parse_count("--count", v); }},
        {"--out", "DIR", "write each stack to DIR/random-SEED-i.toml (default: print them to stdout)",
         [&a](const std::string& v) { a.out = v; }},
    };
}

// Each stack is checked by parsing its own text back.
int run_random_stack(RandomStackSettings& a, const std::vector<std::string>& operands) {
    if (!operands.empty()) usage_error("random-stack takes no positional arguments (--seed N --count K --out DIR)");
    if (a.count < 1 || a.count > 100000) usage_error("--count must be in [1, 100000]");
    if (!a.out.empty()) fs::create_directories(a.out);
    for (uint64_t i = 0; i < a.count; ++i) {
        std::string text = random_stack_toml(a.seed, i);
        Stack s = parse_stack_string(text, "random-stack");   // what `gonio check` will read
        if (a.out.empty()) {
            std::printf("%s%s", i ? "\n# ----\n" : "", text.c_str());
        } else {
            std::string path = a.out + "/" + safe_file_name(s.name) + ".toml";
            std::ofstream(path) << text;
            std::printf("wrote %s (%zu layers)\n", path.c_str(), s.layers.size());
        }
    }
    return 0;
}

}   // namespace

Command random_stack_command() {
    return {"random-stack", "--seed N [--count K] [--out DIR]",
            "seeded random stacks over the whole valid parameter space, as TOML (stdout, or DIR/random-N-i.toml); "
            "same seed, same stacks",
            "", invocation(&random_stack_options, &run_random_stack)};
}

}   // namespace gonio
