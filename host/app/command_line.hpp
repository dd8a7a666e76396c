// The `binpick` command as a library: every verb on one CLI11 app, run from argv (main) or from
// options by name (the Python module's batch verbs, docs/python.md), with the same messages.
#pragma once

#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "host/core/cli_fwd.hpp"

namespace binpick::cli {

// A fresh app with every verb (an app parses once: its verbs keep their options in it).
std::unique_ptr<CLI::App> make_app();

// Parses and runs one command line (the arguments after the program's name). --help prints the
// verb's help to stdout and returns false; a usage error throws InputError "WHAT (see binpick
// VERB --help)"; the verb's own errors pass through. True when a verb ran.
bool run_command_line(CLI::App& app, const std::vector<std::string>& args);

// An option by its name without dashes ('_' or '-' between words): a flag's on/off, or its
// value(s) as text.
struct NamedOption {
  std::string name;
  std::variant<bool, std::vector<std::string>> value;
};

// The command line `VERB --name value ...` of the options, in their order: a flag set true is
// `--name`, false `--no-name` where the verb has it (else left out: off is a flag's default);
// several values follow one `--name` where the option takes several, else it is repeated.
// InputError for an unknown verb or option, a value for a flag or a flag's on/off for a value.
std::vector<std::string> command_line_of(CLI::App& app, const std::string& verb,
                                         const std::vector<NamedOption>& options);

}  // namespace binpick::cli
