// Errors are exceptions that carry their context (the failing call, the file, the build log).
// They become an exit status and one message on stderr only in main().
#pragma once

#include <stdexcept>
#include <string>

namespace binpick {

// Bad input from the user (a file, an option): reported as is, exit status 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A device, driver or library call that failed: exit status 3.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace binpick
