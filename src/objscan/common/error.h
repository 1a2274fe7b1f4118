#pragma once
// Errors at the edges (files, config, CLI) are exceptions naming the offending file or field;
// expected outcomes inside the method are status enums of each component.
#include <stdexcept>
#include <string>

namespace objscan {

// Bad input: a missing or corrupt file, a malformed value, an unknown key. what() is one line that
// names the file or field.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Invalid configuration value or unknown configuration key; what() names the key.
class ConfigError : public InputError {
 public:
  explicit ConfigError(const std::string& message) : InputError(message) {}
};

}  // namespace objscan
