#include "host/app/command_line.hpp"

#include <algorithm>
#include <CLI/CLI.hpp>

#include <fmt/format.h>

#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"

namespace binpick::cli {

std::unique_ptr<CLI::App> make_app() {
  auto app = std::make_unique<CLI::App>(
      "binpick: bin picking with point pair features on OpenCL and Vulkan devices", "binpick");
  app->require_subcommand(1, 1);
  app->fallthrough(false);
  add_devices_verb(*app);
  add_parts_verb(*app);
  add_synth_verb(*app);
  add_train_verb(*app);
  add_detect_verb(*app);
  add_demo_verb(*app);
  add_eval_verb(*app);
  add_tune_verb(*app);
  add_run_verb(*app);
  add_bench_verb(*app);
  add_merge_verb(*app);
  return app;
}

bool run_command_line(CLI::App& app, const std::vector<std::string>& args) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
    return true;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help
      app.exit(e);
      return false;
    }
    throw InputError(fmt::format("{} (see binpick VERB --help)", e.what()));
  }
}

std::vector<std::string> command_line_of(CLI::App& app, const std::string& verb,
                                         const std::vector<NamedOption>& options) {
  const auto subs = app.get_subcommands([&](const CLI::App* a) { return a->get_name() == verb; });
  CLI::App* sub = subs.empty() ? nullptr : subs.front();
  if (!sub) throw InputError(fmt::format("binpick has no verb '{}'", verb));
  std::vector<std::string> line{verb};
  for (const NamedOption& o : options) {
    std::string name = o.name;
    std::replace(name.begin(), name.end(), '_', '-');
    const CLI::Option* option = sub->get_option_no_throw("--" + name);
    if (!option)
      throw InputError(fmt::format("binpick {} has no option --{}", verb, name));
    const bool flag = option->get_expected_max() == 0;
    if (const bool* on = std::get_if<bool>(&o.value)) {
      if (!flag)
        throw InputError(fmt::format("binpick {} --{}: a value expected, not {}", verb, name, *on));
      if (*on)
        line.push_back("--" + name);
      else if (sub->get_option_no_throw("--no-" + name))
        line.push_back("--no-" + name);
      continue;
    }
    if (flag)
      throw InputError(fmt::format("binpick {} --{}: a flag, True or False expected", verb, name));
    // Values an option takes together (--range 300 3000, --model a b) follow it once; an
    // option of one value is repeated.
    const auto& values = std::get<std::vector<std::string>>(o.value);
    const bool together = option->get_items_expected_max() > 1;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i == 0 || !together) line.push_back("--" + name);
      line.push_back(values[i]);
    }
  }
  return line;
}

}  // namespace binpick::cli
