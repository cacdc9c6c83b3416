#pragma once
// SHA-256 (FIPS 180-4) of a byte string, as 64 lowercase hex digits: content hashes for caches
// (OpenSSL's EVP; a library failure throws std::runtime_error).
#include <string>

namespace helios::io {
std::string sha256_hex(const std::string& data);
}
