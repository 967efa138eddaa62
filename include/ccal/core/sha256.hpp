#pragma once
// SHA-256 (FIPS 180-4, "Secure Hash Standard", 2015) of a byte string, as 64 lower-case hex digits: the
// fingerprint of a configuration, a log or an observations file, so that a filed result can be matched to
// its files (`sha256sum FILE` prints the same digits).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace ccal {

std::string sha256_hex(std::string_view bytes);

// The same digest of bytes that come in pieces (a file read block by block): update() with each piece in
// order, then hex() once. sha256_hex(a + b) == (Sha256{}.update(a), .update(b), .hex()).
class Sha256 {
 public:
  Sha256& update(std::string_view bytes);
  std::string hex();  // the digest of everything given; the hasher is spent afterwards

 private:
  std::array<std::uint32_t, 8> state_;
  std::array<unsigned char, 64> block_{};  // the bytes of the block not yet full
  std::size_t held_ = 0;                   // how many of block_ are given
  std::uint64_t length_ = 0;               // bytes given in all
  bool started_ = false;
};

}  // namespace ccal
