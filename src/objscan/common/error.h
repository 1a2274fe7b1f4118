#pragma once
// Errors at the edges (files, config, CLI) are exceptions naming the offending file or field;
// expected outcomes inside the method are status enums of each component.
#include <cstdio>
#include <stdexcept>
#include <string>

namespace objscan {

// `text` with every control character written as an escape (\n, \r, \t, \xHH), so that quoted file
// content (a YAML parser's "unknown escape character: <byte>", a malformed line) cannot break a
// message into several lines or send terminal control codes.
inline std::string OneLine(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7f) {
      out += ch;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\x%02x", c);
      out += buffer;
    }
  }
  return out;
}

// Bad input: a missing or corrupt file, a malformed value, an unknown key. what() is one line that
// names the file or field (control characters in the message are escaped: OneLine).
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(OneLine(message)) {}
};

// Invalid configuration value or unknown configuration key; what() names the key.
class ConfigError : public InputError {
 public:
  explicit ConfigError(const std::string& message) : InputError(message) {}
};

}  // namespace objscan
