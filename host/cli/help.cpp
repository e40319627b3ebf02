#include "help.h"

#include <sstream>

namespace gonio {

namespace {

constexpr const char* kHelpTitle =
    "gonio " GONIO_VERSION " - a virtual gonio-photometer for layered materials (Vulkan compute)\n";
constexpr const char* kHelpTail =
    R"(Exit codes: 0 success; 2 refused input (a stack, sweep or state file that is invalid, with file:line, or an
option that cannot work; nothing is run); 1 a failure while running (a device error, a write that failed, a
Vulkan validation message under --validate, paths whose weight stopped being finite, a model whose values
could not be used).

Conventions (docs/PHYSICS.md): directions point away from the surface, z is the stack normal, the light
arrives from (theta_i, phi_i), phi_i = 0 unless --phi-i (simulate, compare, fit, nodes, a sweep's phi_i);
f excludes the cosine.
)";
constexpr size_t kSummaryColumn = 40;

// One entry of the list of commands: "  gonio NAME USAGE" (a line per form), the summary beside or under it.
std::string usage_entry(const std::string& name, const std::string& usage, const std::string& summary) {
    std::string h, form, last;
    std::istringstream in(usage);
    bool any = false;
    while (std::getline(in, form)) {
        if (any) h += last + "\n";
        last = "  gonio " + name + (form.empty() ? "" : " " + form);
        any = true;
    }
    if (!any) last = "  gonio " + name;
    if (last.size() + 2 > kSummaryColumn) {
        h += last + "\n";
        last.clear();
    }
    return h + last + std::string(kSummaryColumn - last.size(), ' ') + wrap(summary, kSummaryColumn, kSummaryColumn) +
           "\n";
}

std::string command_list(const std::vector<Command>& all) {
    std::string h = "usage:\n";
    for (const Command& c : all) h += usage_entry(c.name, c.usage, c.summary);
    return h + usage_entry("help | --help", "", "this text (gonio COMMAND --help: the command's usage and options)") +
           "\n";
}

bool has_visible_options(const OptionTable& t) {
    for (const Option& o : t)
        if (!o.hidden) return true;
    return false;
}

}   // namespace

std::string full_help(const std::vector<Command>& all) {
    std::string h = std::string(kHelpTitle) + "\n" + command_list(all);
    std::vector<Invocation> held;   // the tables `shown` points into
    held.reserve(all.size());
    ShownOptions shown;
    for (const Command& c : all) {
        if (c.passes_arguments_on) continue;
        held.push_back(c.start());
        if (has_visible_options(held.back().options)) h += options_section(c, held.back().options, &shown) + "\n";
        if (!c.notes.empty()) h += c.notes + "\n";
    }
    return h + kHelpTail;
}

std::string short_help(const std::vector<Command>& all) {
    return std::string(kHelpTitle) + "\n" + command_list(all) + kHelpTail;
}

std::string command_help(const Command& c) {
    std::string h = std::string(kHelpTitle) + "\nusage:\n" + usage_entry(c.name, c.usage, c.summary) + "\n";
    const Invocation inv = c.start();
    h += has_visible_options(inv.options) ? options_section(c, inv.options) : c.name + " takes no options.\n";
    h += "\n";
    if (!c.notes.empty()) h += c.notes + "\n";
    return h + kHelpTail;
}

}   // namespace gonio
