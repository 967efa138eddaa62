// SHA-256 as FIPS 180-4 §6.2 states it: 64-byte blocks, the message padded with a 1 bit, zeros and its
// length in bits (§5.1.1), eight 32-bit working variables and 64 rounds per block.
#include "ccal/core/sha256.hpp"

#include <fmt/format.h>

#include <array>
#include <bit>
#include <cstdint>

namespace ccal {
namespace {

// §4.2.2: the first 32 bits of the fractional parts of the cube roots of the first 64 primes.
constexpr std::array<std::uint32_t, 64> kRound = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

// §5.3.3: the first 32 bits of the fractional parts of the square roots of the first 8 primes.
constexpr std::array<std::uint32_t, 8> kInitial = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                                   0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};

void compress(std::array<std::uint32_t, 8>& h, const unsigned char* block) {
  std::array<std::uint32_t, 64> w{};
  for (int t = 0; t < 16; ++t)
    w[t] = std::uint32_t(block[4 * t]) << 24 | std::uint32_t(block[4 * t + 1]) << 16 |
           std::uint32_t(block[4 * t + 2]) << 8 | std::uint32_t(block[4 * t + 3]);
  for (int t = 16; t < 64; ++t) {  // §6.2.2 step 1, σ0 and σ1 of §4.1.2
    const std::uint32_t s0 = std::rotr(w[t - 15], 7) ^ std::rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
    const std::uint32_t s1 = std::rotr(w[t - 2], 17) ^ std::rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
    w[t] = w[t - 16] + s0 + w[t - 7] + s1;
  }
  std::uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4], f = h[5], g = h[6], k = h[7];
  for (int t = 0; t < 64; ++t) {  // Σ1, Ch, Σ0, Maj of §4.1.2
    const std::uint32_t t1 =
        k + (std::rotr(e, 6) ^ std::rotr(e, 11) ^ std::rotr(e, 25)) + ((e & f) ^ (~e & g)) + kRound[t] + w[t];
    const std::uint32_t t2 =
        (std::rotr(a, 2) ^ std::rotr(a, 13) ^ std::rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
    k = g;
    g = f;
    f = e;
    e = d + t1;
    d = c;
    c = b;
    b = a;
    a = t1 + t2;
  }
  h[0] += a, h[1] += b, h[2] += c, h[3] += d, h[4] += e, h[5] += f, h[6] += g, h[7] += k;
}

}  // namespace

Sha256& Sha256::update(std::string_view bytes) {
  if (!started_) state_ = kInitial, started_ = true;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  std::size_t k = 0;
  length_ += bytes.size();
  if (held_ > 0) {  // complete the held block first
    for (; k < bytes.size() && held_ < 64; ++k) block_[held_++] = data[k];
    if (held_ < 64) return *this;
    compress(state_, block_.data());
    held_ = 0;
  }
  for (; k + 64 <= bytes.size(); k += 64) compress(state_, data + k);
  for (; k < bytes.size(); ++k) block_[held_++] = data[k];
  return *this;
}

std::string Sha256::hex() {
  if (!started_) state_ = kInitial, started_ = true;
  // The held bytes, the 1 bit, zeros to 56 mod 64 bytes, and the length in bits (big-endian), §5.1.1.
  std::array<unsigned char, 128> tail{};
  for (std::size_t k = 0; k < held_; ++k) tail[k] = block_[k];
  tail[held_] = 0x80;
  const std::size_t tail_size = held_ < 56 ? 64 : 128;
  const std::uint64_t bits = length_ * 8;
  for (int k = 0; k < 8; ++k)
    tail[tail_size - 1 - std::size_t(k)] = static_cast<unsigned char>(bits >> (8 * k));
  for (std::size_t k = 0; k < tail_size; k += 64) compress(state_, tail.data() + k);
  std::string hex;
  for (std::uint32_t v : state_) hex += fmt::format("{:08x}", v);
  return hex;
}

std::string sha256_hex(std::string_view bytes) { return Sha256{}.update(bytes).hex(); }

}  // namespace ccal
