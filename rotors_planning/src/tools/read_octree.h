// The tools' shared start: an OcTree read from a .bt named on the command line.
#pragma once

#include <cstdio>
#include <memory>

#include <octomap/OcTree.h>

namespace rotors_planning {

/// The tree in `path`, or nullptr after one line on stderr naming the tool and the file.
inline std::unique_ptr<octomap::OcTree> ReadOcTree(const char* tool, const char* path) {
  auto tree = std::make_unique<octomap::OcTree>(0.1);
  if (!tree->readBinary(path)) {
    std::fprintf(stderr, "%s: cannot read '%s' as a binary OctoMap (.bt)\n", tool, path);
    return nullptr;
  }
  return tree;
}

}  // namespace rotors_planning
