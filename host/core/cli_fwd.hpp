// CLI11's App and Option, declared only. The option headers take them by pointer, so they need
// no more; CLI11 is header-only and costs each file that includes it several seconds of compile
// time, which every test that includes an option header for its other declarations would pay.
// Files that build or read options include <CLI/CLI.hpp> themselves.
#pragma once

namespace CLI {
class App;
class Option;
}  // namespace CLI
