// The one exception type of the engine: a single line naming what is wrong and how to fix it.
#pragma once

#include <stdexcept>
#include <string>

namespace rotors_sim {

class SimError : public std::runtime_error {
 public:
  explicit SimError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace rotors_sim
