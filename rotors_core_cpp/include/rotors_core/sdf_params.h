// One helper to read typed plugin parameters from <plugin> child elements.
#pragma once

#include <cctype>
#include <sstream>
#include <string>

#include <sdf/Element.hh>

#include "rotors_core/error.h"

namespace rotors_sim {

namespace detail {
/// Parses the whole of `text` as T (numbers, vectors "x y z", words); false if anything is left over.
template <typename T>
bool ParseText(const std::string& text, T* out) {
  std::istringstream in(text);
  T parsed;
  if (!(in >> parsed)) return false;
  in >> std::ws;
  if (!in.eof()) return false;
  *out = parsed;
  return true;
}
inline bool ParseText(const std::string& text, std::string* out) {
  const auto first = text.find_first_not_of(" \t\n\r");
  const auto last = text.find_last_not_of(" \t\n\r");
  *out = first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
  return true;
}
inline bool ParseText(const std::string& text, bool* out) {
  std::string word;
  ParseText(text, &word);
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));  // xacro writes True/False
  if (word == "true" || word == "1") {
    *out = true;
    return true;
  }
  if (word == "false" || word == "0") {
    *out = false;
    return true;
  }
  return false;
}
}  // namespace detail

/// Reads <name> into *value if present; returns whether it was present. A present but unparsable
/// value throws SimError naming the element and its text.
template <typename T>
bool ReadParam(const sdf::ElementPtr& sdf, const std::string& name, T* value) {
  if (!sdf || !sdf->HasElement(name)) return false;
  sdf::ElementPtr element = sdf->GetElement(name);
  const std::string text = element->GetValue() ? element->GetValue()->GetAsString() : std::string();
  if (!detail::ParseText(text, value)) {
    throw SimError("parameter <" + name + "> has the value '" + text + "', which does not parse as the expected type");
  }
  return true;
}

/// As ReadParam, but a missing element throws SimError("missing required parameter <name>").
template <typename T>
void RequireParam(const sdf::ElementPtr& sdf, const std::string& name, T* value) {
  if (!ReadParam(sdf, name, value)) {
    throw SimError("missing required parameter <" + name + ">");
  }
}

}  // namespace rotors_sim
