// SHA-256 (core/sha256.hpp) against the FIPS 180-2 examples, and the fingerprint a configuration carries.
#include "ccal/core/sha256.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "ccal/io/config_file.hpp"

namespace ccal {
namespace {

TEST(Sha256, FipsExamples) {
  // FIPS 180-2, Appendix B (one block, two blocks: 56 bytes fill the first block's length field, a million
  // 'a'), and the empty message.
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, PiecesGiveTheDigestOfTheWhole) {
  // Every split of a 200-byte message into two pieces, and pieces of 1, 63, 64 and 65 bytes (across the block
  // boundary, at it, and whole blocks with remainders), give the one-shot digest.
  std::string message;
  for (int k = 0; k < 200; ++k) message += char('a' + k % 26);
  const std::string whole = sha256_hex(message);
  for (std::size_t cut = 0; cut <= message.size(); ++cut)
    EXPECT_EQ(Sha256{}.update(message.substr(0, cut)).update(message.substr(cut)).hex(), whole) << cut;
  for (std::size_t piece : {1u, 63u, 64u, 65u}) {
    Sha256 h;
    for (std::size_t at = 0; at < message.size(); at += piece) h.update(message.substr(at, piece));
    EXPECT_EQ(h.hex(), whole) << piece;
  }
  EXPECT_EQ(Sha256{}.hex(), sha256_hex(""));
}

TEST(Sha256, ASpentHasherIsRefused) {
  // hex() finishes the digest: more bytes or a second hex() would hash a message nobody gave.
  Sha256 h;
  h.update("abc");
  EXPECT_EQ(h.hex(), sha256_hex("abc"));
  EXPECT_THROW(h.update("d"), std::logic_error);
  EXPECT_THROW(h.hex(), std::logic_error);
}

}  // namespace
}  // namespace ccal
