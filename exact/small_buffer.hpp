// A fixed-length buffer of n values, on the stack when n <= Cap (the usual small dimensions of
// charts and Krawczyk systems), else on the heap: the hot interval loops of exact/krawczyk.cpp
// and certify/rvd.cpp allocate nothing for m, k <= 4. Not copyable (its data pointer may point
// into itself).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace delcert::exact {

template <class T, std::size_t Cap>
class SmallBuffer {
 public:
  explicit SmallBuffer(std::size_t n) : n_(n) {
    if (n > Cap) heap_.resize(n);
    data_ = n > Cap ? heap_.data() : local_.data();
  }
  SmallBuffer(const SmallBuffer&) = delete;
  SmallBuffer& operator=(const SmallBuffer&) = delete;
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data_; }
  T* end() { return data_ + n_; }
  std::span<const T> span() const { return {data_, n_}; }

 private:
  std::size_t n_;
  std::array<T, Cap> local_{};
  std::vector<T> heap_;
  T* data_;
};

}  // namespace delcert::exact
