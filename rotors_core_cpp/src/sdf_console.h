// libsdformat prints its own multi-line diagnostics; the engine reports one line per error itself.
#pragma once

#include <string>

#include <sdf/Console.hh>
#include <sdf/Error.hh>

namespace rotors_sim {

inline void SilenceSdformatConsole() {
  static const bool done = [] {
    sdf::Console::Instance()->SetQuiet(true);
    return true;
  }();
  (void)done;
}

/// sdformat errors the engine ignores: inertias Gazebo classic accepts (the firefly's break the
/// triangle inequality).
inline bool IsCheckedByTheEngine(const sdf::Error& error) {
  return error.Code() == sdf::ErrorCode::LINK_INERTIA_INVALID;
}

/// An sdformat error on one line, with the element it is about when sdformat knows it
/// (".../sensor[@name=\"cam\"]").
inline std::string Describe(const sdf::Error& error) {
  std::string line = error.Message();
  if (error.XmlPath() && !error.XmlPath()->empty()) line += " (in " + *error.XmlPath() + ")";
  for (char& c : line)
    if (c == '\n') c = ' ';
  return line;
}

}  // namespace rotors_sim
