// Helpers shared by the Dynamixel unit tests: byte vectors and parsing a whole buffer.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "stride/hal/dynamixel/packet_parser.hpp"

namespace stride::hal::dxl::test {

using Bytes = std::vector<std::uint8_t>;

inline Bytes encode_with(std::size_t (*fn)(std::span<std::uint8_t>), std::size_t cap = 64) {
  Bytes out(cap);
  out.resize(fn(out));
  return out;
}

/// Feeds `bytes` in chunks of `chunk` (0 = all at once) and returns every packet parsed.
inline std::vector<Packet> parse_all(PacketParser& parser, std::span<const std::uint8_t> bytes,
                                     std::size_t chunk = 0) {
  std::vector<Packet> packets;
  Packet p;
  std::size_t offset = 0;
  if (chunk == 0) chunk = bytes.size() == 0 ? 1 : bytes.size();
  while (offset < bytes.size()) {
    const std::size_t n = std::min(chunk, bytes.size() - offset);
    std::size_t taken = 0;
    while (taken < n) {
      taken += parser.feed(bytes.subspan(offset + taken, n - taken));
      while (parser.next(p)) packets.push_back(p);
    }
    offset += n;
  }
  while (parser.next(p)) packets.push_back(p);
  return packets;
}

inline std::vector<Packet> parse_all(Protocol protocol, PacketParser::Role role,
                                     std::span<const std::uint8_t> bytes, std::size_t chunk = 0) {
  PacketParser parser(protocol, role);
  return parse_all(parser, bytes, chunk);
}

inline Bytes params_of(const Packet& p) {
  return Bytes(p.parameters().begin(), p.parameters().end());
}

}  // namespace stride::hal::dxl::test
