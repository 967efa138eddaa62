#pragma once
// SHA-256 (FIPS 180-4, "Secure Hash Standard", 2015) of a byte string, as 64 lower-case hex digits: the
// fingerprint of the configuration that a report names, so that a filed report can be matched to its file
// (`sha256sum FILE` prints the same digits).
#include <string>
#include <string_view>

namespace ccal::render {

std::string sha256_hex(std::string_view bytes);

}  // namespace ccal::render
