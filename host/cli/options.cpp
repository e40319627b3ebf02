#include "options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace gonio {

namespace {

std::string& usage_command() {
    static std::string name;
    return name;
}

// "--a --b --c": the options of a table that its help lists
std::string option_names(const OptionTable& options) {
    std::string list;
    for (const Option& o : options)
        if (!o.hidden) list += (list.empty() ? "" : " ") + o.name;
    return list;
}

// An option the command does not take: exit 2, saying whether it is another command's, and the command's own.
[[noreturn]] void refuse_option(const Command& cmd, const OptionTable& options, const std::string& opt,
                                const std::vector<Command>& all) {
    std::string takers;
    for (const Command& c : all)
        if (c.name != cmd.name && !c.passes_arguments_on && find_option(c.start().options, opt))
            takers += (takers.empty() ? "" : ", ") + c.name;
    const std::string own = option_names(options);
    usage_error((takers.empty() ? "unknown option " + opt + " for `gonio " + cmd.name + "`"
                                : "option " + opt + " does not apply to `gonio " + cmd.name + "`") +
                (own.empty() ? " (it takes no options)" : " (its options: " + own + ")") +
                (takers.empty() ? "" : "; " + opt + " is an option of " + takers));
}

}   // namespace

void set_usage_command(const std::string& name) { usage_command() = name; }

[[noreturn]] void usage_error(const std::string& msg) { throw UsageError(msg); }

void print_usage_error(const std::string& msg) {
    const std::string where = usage_command().empty() ? "gonio --help" : "gonio " + usage_command() + " --help";
    std::fprintf(stderr, "gonio: %s\n(run `%s` for usage)\n", msg.c_str(), where.c_str());
}

const Option* find_option(const OptionTable& options, const std::string& name) {
    for (const Option& o : options)
        if (o.name == name) return &o;
    return nullptr;
}

std::vector<std::string> parse_options(const Command& cmd, const OptionTable& options,
                                       const std::vector<std::string>& args, const std::vector<Command>& all) {
    std::vector<std::string> operands;
    std::vector<std::pair<std::string, std::string>> given;   // each non-repeatable option given, and its value
    auto once = [&](const Option& o, const std::string& value) {
        if (o.repeatable) return;
        for (const auto& [name, first] : given)
            if (name == o.name)
                usage_error(o.name + " given twice" +
                            (o.value ? " (" + o.name + " " + first + ", then " + o.name + " " + value + ")" : "") +
                            ": give it once");
        given.emplace_back(o.name, value);
    };
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& s = args[i];
        if (s.rfind("--", 0) != 0) {
            operands.push_back(s);
            continue;
        }
        const Option* o = find_option(options, s);
        if (!o) refuse_option(cmd, options, s, all);
        if (!o->value) {
            once(*o, "");
            o->set("");
            continue;
        }
        if (i + 1 >= args.size()) usage_error(s + " needs a value");
        if (args[i + 1].empty()) usage_error(s + " needs a value, got an empty one");
        once(*o, args[i + 1]);
        o->set(args[++i]);
    }
    return operands;
}

std::string wrap(const std::string& text, size_t indent, size_t first) {
    constexpr size_t kWidth = 116;
    std::string out, word;
    size_t col = first;
    bool line_start = true;
    auto put_word = [&] {
        if (word.empty()) return;
        if (!line_start && col + 1 + word.size() > kWidth) {
            out += "\n" + std::string(indent, ' ');
            col = indent;
            line_start = true;
        }
        if (!line_start) {
            out += ' ';
            ++col;
        }
        out += word;
        col += word.size();
        line_start = false;
        word.clear();
    };
    for (char c : text) {
        if (c == ' ' || c == '\n') put_word();
        if (c == '\n') {
            out += "\n" + std::string(indent, ' ');
            col = indent;
            line_start = true;
        } else if (c != ' ')
            word += c;
    }
    put_word();
    return out;
}

std::string options_section(const Command& cmd, const OptionTable& options, ShownOptions* shown) {
    constexpr size_t kHelpColumn = 24;
    static const ShownOptions none;
    const ShownOptions& before = shown ? *shown : none;
    std::string h = cmd.name + " options:\n";
    std::vector<std::pair<std::string, std::string>> as_before;   // (command, its options named here)
    for (const Option& o : options) {
        if (o.hidden) continue;
        const std::string* by = nullptr;
        for (const auto& [c, p] : before)
            if (p->name == o.name && p->help == o.help &&
                std::string(p->value ? p->value : "") == (o.value ? o.value : "")) {
                by = &c;
                break;
            }
        if (by) {
            auto it = std::find_if(as_before.begin(), as_before.end(), [&](const auto& e) { return e.first == *by; });
            if (it == as_before.end()) it = as_before.insert(as_before.end(), {*by, ""});
            it->second += " " + o.name;
            continue;
        }
        std::string line = "  " + o.name + (o.value ? " " + std::string(o.value) : "");
        line += line.size() + 2 <= kHelpColumn ? std::string(kHelpColumn - line.size(), ' ') : "  ";
        h += line + wrap(o.help, kHelpColumn, line.size()) + "\n";
    }
    for (const auto& [c, names] : as_before) h += "  " + wrap("and, as for " + c + " above:" + names, 4, 2) + "\n";
    if (shown)
        for (const Option& o : options) shown->push_back({cmd.name, &o});
    return h;
}

double parse_number(const std::string& opt, const std::string& v) {
    char* end = nullptr;
    double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !std::isfinite(d)) usage_error(opt + ": expected a number, got '" + v + "'");
    return d;
}

uint64_t parse_count(const std::string& opt, const std::string& v) {
    double d = parse_number(opt, v);
    if (d < 0 || d != std::floor(d)) usage_error(opt + ": expected a whole non-negative number, got '" + v + "'");
    // a count is read through a double, exact up to 2^53; a larger one would be rounded unseen
    constexpr double kMaxExactCount = 9007199254740992.0;
    if (d > kMaxExactCount)
        usage_error(opt + ": a count of at most 9007199254740992 (2^53, the largest a double holds exactly), got '" +
                    v + "'");
    return uint64_t(d);
}

// A,B,... where an item A:B:S is the range A, A + S, ... up to B (B itself where S divides B - A)
std::vector<double> parse_list(const std::string& opt, const std::string& v) {
    std::vector<double> out;
    size_t i = 0;
    while (i <= v.size()) {
        size_t j = v.find(',', i);
        if (j == std::string::npos) j = v.size();
        const std::string item = v.substr(i, j - i);
        const size_t c1 = item.find(':');
        if (c1 == std::string::npos) {
            out.push_back(parse_number(opt, item));
        } else {
            const size_t c2 = item.find(':', c1 + 1);
            if (c2 == std::string::npos || item.find(':', c2 + 1) != std::string::npos)
                usage_error(opt + ": a range is FROM:TO:STEP, got '" + item + "'");
            const double a = parse_number(opt, item.substr(0, c1)),
                         b = parse_number(opt, item.substr(c1 + 1, c2 - c1 - 1)),
                         step = parse_number(opt, item.substr(c2 + 1));
            if (!(step > 0) || !(b >= a)) usage_error(opt + ": the range " + item + " needs TO >= FROM and STEP > 0");
            const double n = std::floor((b - a) / step + 1e-9);
            if (n >= 10000) usage_error(opt + ": the range " + item + " has more than 10000 values");
            for (int k = 0; k <= int(n); ++k) out.push_back(std::round((a + k * step) * 1e9) / 1e9);
        }
        i = j + 1;
    }
    return out;
}

}   // namespace gonio
