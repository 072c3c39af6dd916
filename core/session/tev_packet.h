#pragma once
// tev's IPC packets, as its IpcPacket reads them (what pbrt-v4's --display-server writes): the
// size (32 bits, little-endian, itself included), the type, then the fields: booleans as a byte,
// strings ending in a zero byte, integers and floats little-endian.

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

namespace rtiow::tev {

// Packet types (tev's IpcPacket::EType).
inline constexpr char kCreateImage = 4;
inline constexpr char kUpdateImageV3 = 6;

class Packet {
 public:
  explicit Packet(char type) : bytes_(4, '\0') { bytes_.push_back(type); }
  Packet& flag(bool value) {
    bytes_.push_back(value ? '\1' : '\0');
    return *this;
  }
  Packet& text(const std::string& value) {
    bytes_.append(value).push_back('\0');
    return *this;
  }
  template <typename Int>
  Packet& integer(Int value) {
    const auto bits = static_cast<std::make_unsigned_t<Int>>(value);
    for (std::size_t i = 0; i < sizeof(Int); ++i) bytes_.push_back(char((bits >> (8 * i)) & 0xff));
    return *this;
  }
  Packet& number(float value) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return integer(bits);
  }
  void reserve(std::size_t more) { bytes_.reserve(bytes_.size() + more); }
  // The packet's bytes, its size filled in.
  std::string done() {
    const auto size = std::uint32_t(bytes_.size());
    for (std::size_t i = 0; i < 4; ++i) bytes_[i] = char((size >> (8 * i)) & 0xff);
    return std::move(bytes_);
  }

 private:
  std::string bytes_;
};

}  // namespace rtiow::tev
