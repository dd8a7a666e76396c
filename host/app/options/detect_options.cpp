#include "host/app/options/detect_options.hpp"

#include <CLI/CLI.hpp>
#include <set>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/params/param_table.hpp"
#include "host/detect/params/params_file.hpp"

namespace binpick::cli {

void add_detect_cli_options(CLI::App* verb, DetectCliOptions& a, const std::string& what,
                            const std::set<std::string>& skip) {
  verb->add_option("--params", a.params_file,
                   "JSON file of " + what + " parameters (from `binpick tune`); options given "
                   "here win");
  DetectParams& p = a.params;
  for (const ParamInfo& info : detect_param_table()) {
    const std::string name = info.name;
    if (skip.count(name)) continue;
    std::string help = what + ": " + info.help;
    if (!is_flag(info) && !is_text(info)) help += ", in " + range_text(info);
    CLI::Option* option = nullptr;
    if (is_flag(info)) {
      option = verb->add_flag(fmt::format("--{0},!--no-{0}", name),
                              p.*std::get<bool DetectParams::*>(info.member), help);
    } else if (is_count(info)) {
      std::int64_t& wide = a.counts[name];
      wide = p.*std::get<std::uint32_t DetectParams::*>(info.member);
      option = verb->add_option("--" + name, wide, help);
    } else if (is_text(info)) {
      option = verb->add_option("--" + name, p.*std::get<std::string DetectParams::*>(info.member),
                                help);
    } else {
      option = verb->add_option("--" + name, p.*std::get<double DetectParams::*>(info.member),
                                help);
    }
    a.options[name] = option->capture_default_str()->group(
        fmt::format("Detection parameters: {}", info.group));
  }
}

DetectParams resolve(const DetectCliOptions& a) {
  DetectParams p = a.params;
  for (const auto& [name, wide] : a.counts) {
    if (wide < 0 || wide > 1000000)
      throw InputError(fmt::format("--{} {} is out of range", name, wide));
    p.*std::get<std::uint32_t DetectParams::*>(find_param(name)->member) =
        static_cast<std::uint32_t>(wide);
  }
  if (!a.params_file.empty()) {
    std::set<std::string> given;
    for (const auto& [name, option] : a.options)
      if (option->count() > 0) given.insert(name);
    apply_params_file(a.params_file, p, given);
  }
  // Named as the user gave it: the option, or the parameter of the --params file.
  if (const auto bad = find_param_problem(p)) {
    const auto option = a.options.find(bad->name);
    const bool from_file = !a.params_file.empty() &&
                           (option == a.options.end() || option->second->count() == 0);
    const std::string name =
        from_file ? fmt::format("{}: {}", a.params_file, bad->name) : "--" + bad->name;
    throw InputError(fmt::format("{} {}", name, describe(*bad)));
  }
  return p;
}

}  // namespace binpick::cli
