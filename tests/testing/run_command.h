#pragma once
// Runs the objscan program for end-to-end tests and captures its exit code, stdout and stderr.
#include <string>

namespace objscan::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs `binary args` through the shell; stderr goes to a private temporary file.
CommandResult RunCommand(const std::string& binary, const std::string& args);

}  // namespace objscan::testing
