#pragma once
// SHA-256 (FIPS 180-4, "Secure Hash Standard", 2015) of a byte string, as 64 lower-case hex digits: the
// fingerprint of a configuration, a log or an observations file, so that a filed result can be matched to
// its files (`sha256sum FILE` prints the same digits). Computed by OpenSSL's libcrypto, which uses the
// processor's SHA instructions where it has them: a run log is hashed as it is read, and the hash would
// otherwise cost more than the reduction (docs/model.md §12).
#include <memory>
#include <string>
#include <string_view>

namespace ccal {

std::string sha256_hex(std::string_view bytes);

// The same digest of bytes that come in pieces (a file read block by block): update() with each piece in
// order, then hex() once. sha256_hex(a + b) == (Sha256{}.update(a), .update(b), .hex()).
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(Sha256&&) noexcept;
  Sha256& operator=(Sha256&&) noexcept;

  Sha256& update(std::string_view bytes);
  std::string hex();  // the digest of everything given; the hasher is spent afterwards

 private:
  struct Context;  // OpenSSL's digest context
  std::unique_ptr<Context> context_;
};

}  // namespace ccal
