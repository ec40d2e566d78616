// SHA-256 (FIPS 180-4), used to name the exact input files in a certificate. Small and
// self-contained so that the certifier does not depend on a crypto library.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace delcert::certify::detail {

class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  std::array<std::uint8_t, 32> digest();  // finishes the hash; call once
  static std::string hex(std::string_view bytes);  // lowercase hex digest of `bytes`

 private:
  void block(const std::uint8_t* p);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> buf_{};
  std::size_t buf_len_ = 0;
  std::uint64_t total_ = 0;  // bytes hashed so far
};

}  // namespace delcert::certify::detail
