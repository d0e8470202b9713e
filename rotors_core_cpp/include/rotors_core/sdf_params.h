// Reading typed plugin parameters from <plugin> child elements: ReadParam / RequireParam on an
// element, and SdfParams, the reader every plugin gets (PluginBase::Params()), which records what
// was read so that the loader rejects the rest by name after Load().
#pragma once

#include <cctype>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sdf/Element.hh>

#include "rotors_core/error.h"
#include "rotors_params/param_record.h"

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

/// A plugin's parameters: typed reads that record each name asked for (ParamRecord).
class SdfParams {
 public:
  SdfParams() = default;
  explicit SdfParams(sdf::ElementPtr sdf) : sdf_(std::move(sdf)) {}
  const sdf::ElementPtr& Element() const { return sdf_; }
  bool Has(const std::string& name) {
    record_.Asked(name);
    return sdf_ && sdf_->HasElement(name);
  }
  template <typename T>
  bool Read(const std::string& name, T* value) {
    record_.Asked(name);
    return ReadParam(sdf_, name, value);
  }
  template <typename T>
  void Require(const std::string& name, T* value) {
    record_.Asked(name);
    RequireParam(sdf_, name, value);
  }
  /// A parameter the plugin takes without using it (e.g. Gazebo's <alwaysOn>); `why` documents it.
  void Accept(const std::string& name, const char* /*why*/) { record_.Asked(name); }
  /// True once the plugin read anything through this reader (a ported plugin that reads the
  /// element directly is not checked).
  bool Used() const { return !record_.Empty(); }
  /// Throws SimError("unknown parameter <x> (this plugin reads: ...)") for the first child element
  /// nobody asked for.
  void RejectUnread() const {
    if (!sdf_) return;
    std::vector<std::string> present;
    for (sdf::ElementPtr e = sdf_->GetFirstElement(); e; e = e->GetNextElement()) present.push_back(e->GetName());
    const std::vector<std::string> unread = record_.Unasked(present);
    if (!unread.empty())
      throw SimError("unknown parameter <" + unread.front() + "> (this plugin reads: " + record_.AskedList() + ")");
  }

 private:
  sdf::ElementPtr sdf_;
  rotors_params::ParamRecord record_;
};

template <typename T>
bool ReadParam(SdfParams& params, const std::string& name, T* value) {
  return params.Read(name, value);
}
template <typename T>
void RequireParam(SdfParams& params, const std::string& name, T* value) {
  params.Require(name, value);
}

}  // namespace rotors_sim
