// SHA-256 (FIPS 180-4, Secure Hash Standard) of a byte string or a file, as 64 lowercase
// hexadecimal digits: the fingerprint of the SID files a result was computed from
// (provenance). Computed by OpenSSL's libcrypto (EVP interface), which uses the processor's
// SHA extensions where it has them: a 1.2 GB SID is hashed in ~0.6 s instead of ~4 s with a
// portable implementation (benchmarks/README.md).
#pragma once

#include <cstddef>
#include <string>

struct evp_md_ctx_st;

namespace ffriga {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(const void* data, std::size_t size);
  std::string hexDigest();  // finishes; the object is spent afterwards

 private:
  evp_md_ctx_st* context_ = nullptr;
};

std::string sha256Hex(const std::string& bytes);
// Throws InputError if the file cannot be read.
std::string sha256OfFile(const std::string& path);

}  // namespace ffriga
