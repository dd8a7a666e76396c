// Every verb of the `binpick` command adds itself to the CLI11 app through one of these.
// A verb parses its options into a struct it owns and runs in its callback; errors are thrown
// (binpick::InputError for bad input) and turned into one message and an exit status in main.
#pragma once

#include "host/core/cli_fwd.hpp"

namespace binpick::cli {

void add_devices_verb(CLI::App& app);
void add_parts_verb(CLI::App& app);
void add_synth_verb(CLI::App& app);
void add_train_verb(CLI::App& app);
void add_detect_verb(CLI::App& app);
void add_demo_verb(CLI::App& app);
void add_eval_verb(CLI::App& app);
void add_tune_verb(CLI::App& app);
void add_run_verb(CLI::App& app);
void add_bench_verb(CLI::App& app);
void add_merge_verb(CLI::App& app);

}  // namespace binpick::cli
