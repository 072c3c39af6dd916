#pragma once
// Names to dense indices 0, 1, 2, ... in the order first seen: how a scene file's material
// names become material slots. A flat open-addressing table over one arena of names: a
// million names in std::unordered_map cost scattered allocations and, measured on a
// 1M-material scene, 1.4 s of lookups. What remains is one cache and TLB miss per lookup in a
// big table (about 300 ns in this VM), which a caller hides by prefetching the slot early.
//
// A name's first slot comes from the top bits of its hash, which the slot keeps: doubling the
// table walks the old slots in order and writes the new ones in order too (a name in slot i
// moves to about 2i), where placing names by their hash again took a cache miss each.

#include <bit>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rtiow {

class NameIndex {
 public:
  static std::uint64_t hash(std::string_view name) { return std::hash<std::string_view>{}(name); }

  // Starts loading the slot where a name of this hash is looked up first.
  void prefetch(std::uint64_t hash) const {
    if (!slots_.empty()) __builtin_prefetch(&slots_[home(tag_of(hash))]);
  }

  // The index of `name` (whose hash() is `hash`), adding it as the next index if it is new.
  std::uint32_t intern(std::string_view name, std::uint64_t hash) {
    if (2 * (size() + 1) > slots_.size()) grow();
    const std::uint32_t tag = tag_of(hash);
    for (std::size_t i = home(tag);; i = (i + 1) & mask_) {
      const std::uint64_t slot = slots_[i];
      if (slot == 0) {
        const auto index = std::uint32_t(size());
        arena_.append(name);
        ends_.push_back(arena_.size());
        slots_[i] = (std::uint64_t(tag) << 32) | (std::uint64_t(index) + 1);
        return index;
      }
      const auto index = std::uint32_t(slot - 1);
      if (std::uint32_t(slot >> 32) == tag && this->name(index) == name) return index;
    }
  }

  std::size_t size() const { return ends_.size(); }

  std::string_view name(std::uint32_t index) const {
    const std::size_t begin = index == 0 ? 0 : ends_[index - 1];
    return std::string_view(arena_).substr(begin, ends_[index] - begin);
  }

 private:
  // The tag is the hash's top 32 bits. Fewer than 2^31 names fit a scene file (2 GiB at
  // most), so the table has at most 2^32 slots and a slot's position is the tag's top bits.
  static std::uint32_t tag_of(std::uint64_t hash) { return std::uint32_t(hash >> 32); }
  std::size_t home(std::uint32_t tag) const { return std::size_t(tag) >> shift_; }

  void grow() {
    const std::size_t capacity = slots_.empty() ? 64 : 2 * slots_.size();
    const int shift = 32 - std::countr_zero(capacity);
    std::vector<std::uint64_t> bigger(capacity, 0);
    for (const std::uint64_t slot : slots_) {
      if (slot == 0) continue;
      std::size_t i = std::size_t(slot >> 32) >> shift;
      while (bigger[i] != 0) i = (i + 1) & (capacity - 1);
      bigger[i] = slot;
    }
    slots_.swap(bigger);
    mask_ = capacity - 1;
    shift_ = shift;
  }

  // Each slot: (tag << 32) | (index + 1); 0 is empty. At most half full.
  std::vector<std::uint64_t> slots_;
  std::size_t mask_ = 0;
  int shift_ = 32;
  std::vector<std::size_t> ends_;  // where each name ends in the arena
  std::string arena_;
};

}  // namespace rtiow
