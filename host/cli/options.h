// options.h: a command of gonio and its options as one table (Option): from the table come the parsing, the refusals
// (usage_error: the message, then exit 2) and the options section of `gonio CMD --help`. Also the parsers of the
// values that the tables share (numbers, counts, lists of angles).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

// One option: its name (--paths), the name of its value in the help (N; nullptr: a flag, which takes no value), what
// it does (one paragraph, wrapped by the help; a '\n' starts a new line) and what it sets (given the value, "" for a
// flag). A setter refuses a value that cannot work with usage_error.
struct Option {
    std::string name;
    const char* value = nullptr;
    std::string help;
    std::function<void(const std::string&)> set;
    bool hidden = false;   // left out of the help and of the refusals' lists (a switch for gonio's own tests)
    bool repeatable = false;   // may be given more than once (each value to the setter); else a second is refused
};
using OptionTable = std::vector<Option>;

// A command's settings, made fresh, with the table whose setters fill them and the run that uses them.
struct Invocation {
    OptionTable options;
    std::function<int(const std::vector<std::string>& operands)> run;   // operands: the arguments not options
    std::shared_ptr<void> settings;   // what the setters and run refer to, kept alive with them
};

// A command of gonio: what `gonio --help` lists, what `gonio NAME --help` prints, and what main runs.
struct Command {
    std::string name;
    std::string usage;   // its arguments after `gonio NAME` (one form per line; "" none)
    std::string summary;   // what it does: one paragraph in gonio --help's list of commands
    std::string notes;   // printed after its options by its --help (what it writes, ...); "" none
    std::function<Invocation()> start;
    bool passes_arguments_on = false;   // every argument, --help too, goes unparsed to its run (gonio view)
};

// An Invocation of fresh Settings: the table `options` makes for them, and `run` on them.
template <class Settings>
std::function<Invocation()> invocation(OptionTable (*options)(Settings&),
                                       int (*run)(Settings&, const std::vector<std::string>&)) {
    return [options, run] {
        auto s = std::make_shared<Settings>();
        return Invocation{options(*s), [s, run](const std::vector<std::string>& operands) { return run(*s, operands); },
                          s};
    };
}

// The settings and table of a command that takes no options.
struct NoSettings {};
inline OptionTable no_options(NoSettings&) { return {}; }

// The operands of `gonio CMD ARGS...` (the arguments that do not start with --), each option given to its setter in
// the order of ARGS. An option that `options` lacks is refused, naming it, the command, whether another of `all`
// takes it, and the command's own options; so is an option without its value, and one given twice that is not
// repeatable (naming both values: the last would otherwise win unseen).
std::vector<std::string> parse_options(const Command& cmd, const OptionTable& options,
                                       const std::vector<std::string>& args, const std::vector<Command>& all);
// "CMD options:" and each option of the table but the hidden ones: its name and value, and its help wrapped at 116
// columns beside and under it. With `shown` (the options printed before, by command), an option printed before with
// the same name, value and help is only named, "as for CMD above"; the section's options are added to it.
using ShownOptions = std::vector<std::pair<std::string, const Option*>>;
std::string options_section(const Command& cmd, const OptionTable& options, ShownOptions* shown = nullptr);
// `text` wrapped at 116 columns: its first line from `first` (its column), the lines after it indented by `indent`.
std::string wrap(const std::string& text, size_t indent, size_t first);
// The table's option of that name (null if none).
const Option* find_option(const OptionTable& options, const std::string& name);

// Which command's usage usage_error points to: `gonio NAME --help` (main sets it; "": `gonio --help`).
void set_usage_command(const std::string& name);
// A refused command line (or the same options given in-process, gonio._core): main prints it with
// print_usage_error and exits 2; the Python module raises it as a ValueError. Not a std::invalid_argument, so that
// a command's own catch of those never catches it.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
// Throws UsageError(msg).
[[noreturn]] void usage_error(const std::string& msg);
// Prints "gonio: MSG" and where the usage is (`gonio CMD --help`) on stderr.
void print_usage_error(const std::string& msg);
// An option's value: a finite number; a whole non-negative number (1e6 is allowed); a comma-separated list of numbers.
double parse_number(const std::string& opt, const std::string& v);
uint64_t parse_count(const std::string& opt, const std::string& v);
std::vector<double> parse_list(const std::string& opt, const std::string& v);

}   // namespace gonio
