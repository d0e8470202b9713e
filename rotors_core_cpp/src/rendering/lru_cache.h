// A bounded cache for the renderer's GPU objects (meshes, textures, render targets, distortion
// maps): at most `capacity` entries when a frame starts, plus what that frame adds; the least
// recently used go first. Entries are dropped only when a frame starts (NextFrame), never while
// one is drawn, and never one that the frame before used: what a draw holds stays valid. Pinned
// entries (the unit primitives) stay.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>

namespace rotors_sim {
namespace rendering {

template <typename Key, typename Value>
class LruCache {
 public:
  explicit LruCache(size_t capacity) : capacity_(capacity) {}

  /// The entry, marked used in this frame; nullptr when there is none.
  Value* Find(const Key& key) {
    auto it = entries_.find(key);
    if (it == entries_.end()) return nullptr;
    it->second.last_used = frame_;
    return &it->second.value;
  }

  /// Adds (or replaces) the entry, used in this frame.
  Value& Insert(const Key& key, Value value, bool pinned = false) {
    auto it = entries_.find(key);
    if (it != entries_.end()) entries_.erase(it);
    Entry& entry = entries_.emplace(key, Entry{std::move(value), frame_, pinned}).first->second;
    return entry.value;
  }

  /// A new frame: while more than `capacity` entries are kept, the one used longest ago goes,
  /// unless the frame before used it.
  void NextFrame() {
    ++frame_;
    while (entries_.size() > capacity_) {
      auto oldest = entries_.end();
      for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (!it->second.pinned && (oldest == entries_.end() || it->second.last_used < oldest->second.last_used))
          oldest = it;
      if (oldest == entries_.end() || oldest->second.last_used + 1 >= frame_) return;
      entries_.erase(oldest);
      ++dropped_;
    }
  }

  size_t Size() const { return entries_.size(); }
  size_t Capacity() const { return capacity_; }
  /// Entries dropped so far.
  uint64_t Dropped() const { return dropped_; }
  template <typename F>
  void ForEach(F f) const {
    for (const auto& [key, entry] : entries_) f(key, entry.value);
  }

 private:
  struct Entry {
    Value value;
    uint64_t last_used;
    bool pinned;
  };
  size_t capacity_;
  uint64_t frame_ = 0;
  uint64_t dropped_ = 0;
  std::map<Key, Entry> entries_;
};

}  // namespace rendering
}  // namespace rotors_sim
