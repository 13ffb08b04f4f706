// Little-endian bytes of a datagram written by hand, not by the code under test: the device
// protocol's tests build packets with these and compare them with what the encoder writes.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace gf::test {

inline void putU32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

inline void putF64(std::vector<std::uint8_t>& b, double d) {
  std::uint64_t v;
  std::memcpy(&v, &d, sizeof v);
  for (int i = 0; i < 8; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

inline void putF32(std::vector<std::uint8_t>& b, float f) {
  std::uint32_t v;
  std::memcpy(&v, &f, sizeof v);
  putU32(b, v);
}

}  // namespace gf::test
