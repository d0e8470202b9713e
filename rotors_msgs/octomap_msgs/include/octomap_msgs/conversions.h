// octomap_msgs' conversion functions (the same names and behaviour as upstream's conversions.h):
// an OctoMap into octomap_msgs/Octomap (binary: occupied/free bits; full: with probabilities) and
// back. Header-only; link OctoMap where it is used.
#pragma once

#include <sstream>
#include <string>

#include <octomap/AbstractOcTree.h>
#include <octomap/AbstractOccupancyOcTree.h>
#include <octomap_msgs/Octomap.h>

namespace octomap_msgs {

namespace detail {
/// The tree written by `write` (its writeBinaryData or writeData) into msg.
template <class OctomapT, class WriteFn>
bool MapToMsg(const OctomapT& octomap, bool binary, WriteFn write, Octomap& msg) {
  msg.resolution = octomap.getResolution();
  msg.id = octomap.getTreeType();
  msg.binary = binary;
  std::stringstream data;
  if (!write(data)) return false;
  const std::string bytes = data.str();
  msg.data.assign(bytes.begin(), bytes.end());
  return true;
}
}  // namespace detail

/// The tree's occupied/free bits (writeBinaryData) into msg; false when the tree cannot write them.
template <class OctomapT>
bool binaryMapToMsg(const OctomapT& octomap, Octomap& msg) {
  return detail::MapToMsg(
      octomap, true, [&](std::ostream& s) { return octomap.writeBinaryData(s).good(); }, msg);
}

/// The whole tree with its node data (writeData) into msg.
template <class OctomapT>
bool fullMapToMsg(const OctomapT& octomap, Octomap& msg) {
  return detail::MapToMsg(
      octomap, false, [&](std::ostream& s) { return octomap.writeData(s).good(); }, msg);
}

/// A new tree (caller owns it) from a binary message; nullptr for an unknown tree type or bad data.
inline octomap::AbstractOcTree* binaryMsgToMap(const Octomap& msg) {
  if (!msg.binary) return nullptr;
  octomap::AbstractOcTree* tree = octomap::AbstractOcTree::createTree(msg.id, msg.resolution);
  auto* occupancy = dynamic_cast<octomap::AbstractOccupancyOcTree*>(tree);
  std::stringstream data(std::string(msg.data.begin(), msg.data.end()));
  if (!occupancy || !occupancy->readBinaryData(data)) {
    delete tree;
    return nullptr;
  }
  return tree;
}

/// A new tree (caller owns it) from a full message; nullptr for an unknown tree type or bad data.
inline octomap::AbstractOcTree* fullMsgToMap(const Octomap& msg) {
  if (msg.binary) return nullptr;
  octomap::AbstractOcTree* tree = octomap::AbstractOcTree::createTree(msg.id, msg.resolution);
  std::stringstream data(std::string(msg.data.begin(), msg.data.end()));
  if (!tree || !tree->readData(data)) {
    delete tree;
    return nullptr;
  }
  return tree;
}

/// Either kind of message.
inline octomap::AbstractOcTree* msgToMap(const Octomap& msg) {
  return msg.binary ? binaryMsgToMap(msg) : fullMsgToMap(msg);
}

}  // namespace octomap_msgs
