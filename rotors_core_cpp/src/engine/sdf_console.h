// libsdformat prints its own multi-line diagnostics; the engine reports one line per error itself.
#pragma once

#include <sdf/Console.hh>

namespace rotors_sim {

inline void SilenceSdformatConsole() {
  static const bool done = [] {
    sdf::Console::Instance()->SetQuiet(true);
    return true;
  }();
  (void)done;
}

}  // namespace rotors_sim
