// The one exception type of the engine: a single line naming what is wrong and how to fix it.
#pragma once

#include <stdexcept>
#include <string>

namespace rotors_sim {

class SimError : public std::runtime_error {
 public:
  explicit SimError(const std::string& what) : std::runtime_error(what) {}
};

/// A caller's string as it goes into a one-line error: at most `max_chars` characters.
inline std::string Abbreviated(const std::string& text, size_t max_chars = 80) {
  if (text.size() <= max_chars) return text;
  return text.substr(0, max_chars) + "... (" + std::to_string(text.size() - max_chars) + " more characters)";
}

}  // namespace rotors_sim
