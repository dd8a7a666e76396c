// The `binpick` command: parses the verb, runs it, and is the only place where an error
// becomes a message on stderr and an exit status.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "host/app/verbs.hpp"
#include "host/core/error.hpp"
#include "host/core/keep_freed_memory.hpp"

int main(int argc, char** argv) {
  binpick::keep_freed_memory();  // before any thread starts
  CLI::App app{"binpick: bin picking with point pair features on OpenCL and Vulkan devices"};
  app.require_subcommand(1, 1);
  app.fallthrough(false);
  binpick::cli::add_devices_verb(app);
  binpick::cli::add_parts_verb(app);
  binpick::cli::add_synth_verb(app);
  binpick::cli::add_train_verb(app);
  binpick::cli::add_detect_verb(app);
  binpick::cli::add_demo_verb(app);
  binpick::cli::add_eval_verb(app);
  binpick::cli::add_tune_verb(app);
  binpick::cli::add_run_verb(app);
  binpick::cli::add_bench_verb(app);
  binpick::cli::add_merge_verb(app);
  try {
    app.parse(argc, argv);
    return 0;
  } catch (const CLI::ParseError& e) {
    // --help (exit code 0) prints the help; a usage error is bad input: one line and 2, like
    // every other.
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "binpick: error: " << e.what() << " (see binpick VERB --help)\n";
    return 2;
  } catch (const binpick::InputError& e) {
    std::cerr << "binpick: error: " << e.what() << "\n";
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A directory that cannot be made or renamed: a full disk, a read-only or missing output.
    std::cerr << "binpick: error: " << e.what() << "\n";
    return 2;
  } catch (const binpick::DeviceError& e) {
    std::cerr << "binpick: device error: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "binpick: internal error: " << e.what() << "\n";
    return 4;
  }
}
