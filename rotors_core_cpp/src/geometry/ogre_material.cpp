#include "rotors_core/geometry/ogre_material.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace geometry {

namespace fs = std::filesystem;

namespace {
struct Token {
  std::string text;
  int line = 0;
};

/// Words and braces, // comments dropped.
std::vector<Token> Tokenize(const std::string& text) {
  std::vector<Token> tokens;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = line.substr(0, line.find("//"));
    std::string word;
    auto flush = [&] {
      if (!word.empty()) tokens.push_back({word, number});
      word.clear();
    };
    for (char c : line) {
      if (c == '{' || c == '}') {
        flush();
        tokens.push_back({std::string(1, c), number});
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        flush();
      } else {
        word += c;
      }
    }
    flush();
  }
  return tokens;
}

std::array<float, 4> Colour(const std::vector<std::string>& args) {
  std::array<float, 4> rgba{1, 1, 1, 1};
  for (size_t i = 0; i < 4 && i < args.size(); ++i) rgba[i] = std::stof(args[i]);
  return rgba;
}
}  // namespace

std::map<std::string, OgreMaterial> ParseOgreMaterials(const std::string& text, const std::string& source) {
  const std::vector<Token> tokens = Tokenize(text);
  std::map<std::string, OgreMaterial> materials;
  // a statement is the words of one line; a block opens after its header statement
  std::vector<std::string> blocks;  // block kinds from the outside in: material, technique, pass, texture_unit
  OgreMaterial* current = nullptr;
  int passes_seen = 0, units_seen = 0;
  bool anisotropic = false;  // the current material's first texture unit asks for it
  size_t i = 0;
  auto fail = [&](const std::string& why, int line) {
    throw SimError(source + ":" + std::to_string(line) + ": " + why);
  };
  while (i < tokens.size()) {
    const Token& head = tokens[i];
    if (head.text == "}") {
      if (blocks.empty()) fail("'}' without a block", head.line);
      blocks.pop_back();
      ++i;
      continue;
    }
    // the statement: this line's words up to a brace
    std::vector<std::string> words;
    const int line = head.line;
    while (i < tokens.size() && tokens[i].line == line && tokens[i].text != "{" && tokens[i].text != "}")
      words.push_back(tokens[i++].text);
    const bool opens = i < tokens.size() && tokens[i].text == "{";
    if (opens) ++i;
    if (words.empty()) {
      if (opens) blocks.push_back("");
      continue;
    }
    const std::string& key = words[0];
    const std::vector<std::string> args(words.begin() + 1, words.end());
    if (opens) {
      if (key == "material") {
        if (!blocks.empty()) fail("a material inside another block", line);
        if (args.empty()) fail("a material without a name", line);
        if (current && !anisotropic) current->max_anisotropy = 1.0f;
        current = &materials[args[0]];
        passes_seen = units_seen = 0;
        anisotropic = false;
      } else if (key == "pass") {
        ++passes_seen;
      } else if (key == "texture_unit") {
        ++units_seen;
      }
      blocks.push_back(key);
      continue;
    }
    // attributes of the first pass and its first texture unit
    if (!current || passes_seen != 1) continue;
    try {
      if (blocks.back() == "pass" && key == "ambient" && !args.empty()) current->ambient = Colour(args);
      if (blocks.back() == "pass" && key == "diffuse" && !args.empty()) current->diffuse = Colour(args);
      if (blocks.back() == "texture_unit" && units_seen == 1) {
        if (key == "texture" && !args.empty()) current->texture = args[0];
        if (key == "scale" && args.size() >= 2) current->scale = {std::stof(args[0]), std::stof(args[1])};
        if (key == "max_anisotropy" && !args.empty()) current->max_anisotropy = std::stof(args[0]);
        // OGRE's keyword, and the misspelling RotorS' scripts carry
        if (key == "filtering" && !args.empty() && (args[0] == "anisotropic" || args[0] == "anistropic"))
          anisotropic = true;
      }
    } catch (const std::exception&) {
      fail("'" + key + "' needs numbers", line);
    }
  }
  if (!blocks.empty()) throw SimError(source + ": a block is not closed (missing '}')");
  if (current && !anisotropic) current->max_anisotropy = 1.0f;  // max_anisotropy counts with the filter only
  return materials;
}

OgreMaterial FindOgreMaterial(const std::vector<std::string>& uris, const std::string& name) {
  std::vector<fs::path> folders, files;
  for (const auto& uri : uris) {
    const fs::path p(uri);
    if (fs::is_directory(p)) {
      folders.push_back(p);
      for (const auto& entry : fs::directory_iterator(p))
        if (entry.path().extension() == ".material") files.push_back(entry.path());
    } else if (p.extension() == ".material") {
      files.push_back(p);
      folders.push_back(p.parent_path());
    }
  }
  std::string searched;
  for (const auto& file : files) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    const auto materials = ParseOgreMaterials(text.str(), file.string());
    const auto it = materials.find(name);
    searched += (searched.empty() ? "" : ", ") + file.string();
    if (it == materials.end()) continue;
    OgreMaterial m = it->second;
    if (!m.texture.empty()) {
      std::string found;
      for (const auto& folder : folders)
        if (fs::exists(folder / m.texture)) {
          found = (folder / m.texture).lexically_normal().string();
          break;
        }
      if (found.empty())
        throw SimError("material '" + name + "' (" + file.string() + "): texture '" + m.texture +
                       "' is in none of the script's folders");
      m.texture = found;
    }
    return m;
  }
  throw SimError("material '" + name + "' is in none of the .material files of the script's <uri>s (" +
                 (searched.empty() ? std::string("none found") : searched) + ")");
}

}  // namespace geometry
}  // namespace rotors_sim
