#include "cmd_random_stack.h"
#include "output.h"
#include "random_stack.h"
#include "stack.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace gonio {

// Each stack is checked by parsing its own text back.
int cmd_random_stack(const Args& a) {
    if (!a.positional.empty()) usage_error("random-stack takes no positional arguments (--seed N --count K --out DIR)");
    if (a.count < 1 || a.count > 100000) usage_error("--count must be in [1, 100000]");
    if (!a.out.empty()) fs::create_directories(a.out);
    for (uint64_t i = 0; i < a.count; ++i) {
        std::string text = random_stack_toml(a.sim.seed, i);
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

}   // namespace gonio
