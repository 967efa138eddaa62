// SHA-256 through OpenSSL's EVP digest interface (libcrypto): one context per hasher, fed piece by piece.
#include "ccal/core/sha256.hpp"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <stdexcept>

namespace ccal {

struct Sha256::Context {
  EVP_MD_CTX* ctx = EVP_MD_CTX_new();
  bool spent = false;

  Context() {
    if (ctx == nullptr || EVP_DigestInit_ex(ctx, EVP_sha256(), nullptr) != 1) {
      EVP_MD_CTX_free(ctx);
      throw std::runtime_error("SHA-256: OpenSSL could not set up a digest");
    }
  }
  ~Context() { EVP_MD_CTX_free(ctx); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
};

Sha256::Sha256() : context_(std::make_unique<Context>()) {}
Sha256::~Sha256() = default;
Sha256::Sha256(Sha256&&) noexcept = default;
Sha256& Sha256::operator=(Sha256&&) noexcept = default;

Sha256& Sha256::update(std::string_view bytes) {
  if (!context_ || context_->spent) throw std::logic_error("Sha256::update after hex()");
  if (!bytes.empty() && EVP_DigestUpdate(context_->ctx, bytes.data(), bytes.size()) != 1)
    throw std::runtime_error("SHA-256: OpenSSL could not hash the bytes");
  return *this;
}

std::string Sha256::hex() {
  if (!context_ || context_->spent) throw std::logic_error("Sha256::hex called twice");
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_DigestFinal_ex(context_->ctx, digest, &size) != 1 || size != 32)
    throw std::runtime_error("SHA-256: OpenSSL could not finish the digest");
  context_->spent = true;
  std::string hex;
  hex.reserve(64);
  for (unsigned int k = 0; k < size; ++k) hex += fmt::format("{:02x}", digest[k]);
  return hex;
}

std::string sha256_hex(std::string_view bytes) { return Sha256{}.update(bytes).hex(); }

}  // namespace ccal
