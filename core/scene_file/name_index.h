#pragma once
// Names to dense indices 0, 1, 2, ... in the order first seen: how a scene file's material
// names become material slots. A flat open-addressing table over one arena of names: a
// million names in std::unordered_map cost scattered allocations and, measured on a
// 1M-material scene, 1.4 s of lookups. What remains is one cache and TLB miss per lookup in a
// big table (about 300 ns in this VM), which a caller hides by prefetching the slot early.

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
    if (!slots_.empty()) __builtin_prefetch(&slots_[hash & mask_]);
  }

  // The index of `name` (whose hash() is `hash`), adding it as the next index if it is new.
  std::uint32_t intern(std::string_view name, std::uint64_t hash) {
    if (2 * (size() + 1) > slots_.size()) grow();
    const auto tag = std::uint32_t(hash >> 32);
    for (std::size_t i = hash & mask_;; i = (i + 1) & mask_) {
      const std::uint64_t slot = slots_[i];
      if (slot == 0) {
        const auto index = std::uint32_t(names_.size());
        names_.push_back({arena_.size(), name.size(), hash});
        arena_.append(name);
        slots_[i] = (std::uint64_t(tag) << 32) | (std::uint64_t(index) + 1);
        return index;
      }
      const auto index = std::uint32_t(slot - 1);
      if (std::uint32_t(slot >> 32) == tag && this->name(index) == name) return index;
    }
  }

  std::size_t size() const { return names_.size(); }

  std::string_view name(std::uint32_t index) const {
    const Entry& e = names_[index];
    return std::string_view(arena_).substr(e.offset, e.length);
  }

 private:
  struct Entry {
    std::size_t offset, length;
    std::uint64_t hash;  // kept, so that growing need not hash again
  };

  void grow() {
    const std::size_t capacity = slots_.empty() ? 64 : 2 * slots_.size();
    slots_.assign(capacity, 0);
    mask_ = capacity - 1;
    for (std::uint32_t index = 0; index < names_.size(); ++index) {
      const std::uint64_t hash = names_[index].hash;
      std::size_t i = hash & mask_;
      while (slots_[i] != 0) i = (i + 1) & mask_;
      slots_[i] = ((hash >> 32) << 32) | (std::uint64_t(index) + 1);
    }
  }

  // Each slot: (hash tag << 32) | (index + 1); 0 is empty. At most half full.
  std::vector<std::uint64_t> slots_;
  std::size_t mask_ = 0;
  std::vector<Entry> names_;
  std::string arena_;
};

}  // namespace rtiow
