// SHA-256 (FIPS 180-4, Secure Hash Standard, Sect. 6.2) of a byte string or a file, as 64
// lowercase hexadecimal digits: the fingerprint of the SID files a result was computed
// from (provenance).
#pragma once

#include <cstdint>
#include <string>

namespace ffriga {

class Sha256 {
 public:
  Sha256();
  void update(const void* data, std::size_t size);
  std::string hexDigest();  // finishes; the object is spent afterwards

 private:
  void compress(const unsigned char* block);
  std::uint32_t h_[8];
  unsigned char buffer_[64];
  std::size_t used_ = 0;
  std::uint64_t length_ = 0;  // bytes
};

std::string sha256Hex(const std::string& bytes);
// Throws InputError if the file cannot be read.
std::string sha256OfFile(const std::string& path);

}  // namespace ffriga
