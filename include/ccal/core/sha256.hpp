#pragma once
// SHA-256 (FIPS 180-4, "Secure Hash Standard", 2015) of a byte string, as 64 lower-case hex digits: the
// fingerprint of a configuration, a log or an observations file, so that a filed result can be matched to
// its files (`sha256sum FILE` prints the same digits).
#include <string>
#include <string_view>

namespace ccal {

std::string sha256_hex(std::string_view bytes);

}  // namespace ccal
