#include "run_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace objscan::testing {

CommandResult RunCommand(const std::string& binary, const std::string& args) {
  namespace fs = std::filesystem;
  static std::atomic<int> counter{0};
  const fs::path err_file = fs::temp_directory_path() / ("objscan_test_err_" + std::to_string(::getpid()) + "_" +
                                                         std::to_string(counter++));
  const std::string cmd = binary + " " + args + " 2>" + err_file.string();
  CommandResult r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = ReadFile(err_file);
  fs::remove(err_file);
  return r;
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::filesystem::path ScratchPath(const std::string& name) {
  const std::filesystem::path p = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  return p;
}

int CountLines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace objscan::testing
