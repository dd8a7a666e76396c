// The `binpick` command: runs the command line, and is the only place where an error becomes a
// message on stderr and an exit status.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "host/app/command_line.hpp"
#include "host/core/error.hpp"
#include "host/core/keep_freed_memory.hpp"

int main(int argc, char** argv) {
  binpick::keep_freed_memory();  // before any thread starts
  try {
    const auto app = binpick::cli::make_app();
    binpick::cli::run_command_line(*app, std::vector<std::string>(argv + 1, argv + argc));
    return 0;
  } catch (const binpick::InputError& e) {  // a usage error among them
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
