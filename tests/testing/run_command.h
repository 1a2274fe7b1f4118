#pragma once
// Runs the objscan program for end-to-end tests and captures its exit code, stdout and stderr; the
// file helpers those tests share.
#include <filesystem>
#include <string>

namespace objscan::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs `binary args` through the shell; stderr goes to a private temporary file.
CommandResult RunCommand(const std::string& binary, const std::string& args);

// The number of lines of a command's output (its newlines).
int CountLines(const std::string& text);

// The whole content of a file ("" when it cannot be read).
std::string ReadFile(const std::filesystem::path& path);

// A path in the temporary folder for one test, unique to this process, with anything left there by
// an earlier run removed (the test creates it when it needs it to exist).
std::filesystem::path ScratchPath(const std::string& name);

}  // namespace objscan::testing
