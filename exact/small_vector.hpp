// SmallVector<T, N>: a vector of trivially copyable values kept inline up to N elements, on the
// heap beyond: exact::Box (interval boxes of charts and Krawczyk systems, a few dimensions) is
// one, so the subdivision of certify/rvd.cpp allocates nothing per box for the usual dimensions.
// The subset of std::vector's interface the project uses; contiguous (pointer iterators).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <new>
#include <type_traits>

namespace delcert::exact {

template <class T, std::size_t N>
class SmallVector {
  static_assert(std::is_trivially_copyable_v<T> && std::is_default_constructible_v<T>);

 public:
  using value_type = T;
  using size_type = std::size_t;
  using difference_type = std::ptrdiff_t;
  using reference = T&;
  using const_reference = const T&;
  using pointer = T*;
  using const_pointer = const T*;
  using iterator = T*;
  using const_iterator = const T*;

  SmallVector() = default;
  explicit SmallVector(size_type n) { assign(n, T{}); }
  SmallVector(size_type n, const T& value) { assign(n, value); }
  template <class It, class = typename std::iterator_traits<It>::iterator_category>
  SmallVector(It first, It last) { assign(first, last); }
  SmallVector(std::initializer_list<T> init) { assign(init.begin(), init.end()); }
  SmallVector(const SmallVector& o) { assign(o.begin(), o.end()); }
  SmallVector(SmallVector&& o) noexcept { steal(o); }
  SmallVector& operator=(const SmallVector& o) {
    if (this != &o) assign(o.begin(), o.end());
    return *this;
  }
  SmallVector& operator=(SmallVector&& o) noexcept {
    if (this != &o) {
      release();
      steal(o);
    }
    return *this;
  }
  SmallVector& operator=(std::initializer_list<T> init) {
    assign(init.begin(), init.end());
    return *this;
  }
  ~SmallVector() { release(); }

  size_type size() const { return size_; }
  bool empty() const { return size_ == 0; }
  size_type capacity() const { return cap_; }
  T* data() { return ptr_; }
  const T* data() const { return ptr_; }
  iterator begin() { return ptr_; }
  iterator end() { return ptr_ + size_; }
  const_iterator begin() const { return ptr_; }
  const_iterator end() const { return ptr_ + size_; }
  const_iterator cbegin() const { return ptr_; }
  const_iterator cend() const { return ptr_ + size_; }
  T& operator[](size_type i) { return ptr_[i]; }
  const T& operator[](size_type i) const { return ptr_[i]; }
  T& front() { return ptr_[0]; }
  const T& front() const { return ptr_[0]; }
  T& back() { return ptr_[size_ - 1]; }
  const T& back() const { return ptr_[size_ - 1]; }

  void reserve(size_type n) {
    if (n <= cap_) return;
    T* p = static_cast<T*>(::operator new(n * sizeof(T)));
    const size_type size = size_;
    if (size > 0) std::memcpy(static_cast<void*>(p), ptr_, size * sizeof(T));
    release();
    ptr_ = p;
    cap_ = n;
    size_ = size;
  }
  void clear() { size_ = 0; }
  void resize(size_type n) { resize(n, T{}); }
  void resize(size_type n, const T& value) {
    if (n > cap_) reserve(std::max(n, 2 * cap_));
    for (size_type i = size_; i < n; ++i) ptr_[i] = value;
    size_ = n;
  }
  void assign(size_type n, const T& value) {
    size_ = 0;
    resize(n, value);
  }
  template <class It, class = typename std::iterator_traits<It>::iterator_category>
  void assign(It first, It last) {
    const auto n = static_cast<size_type>(std::distance(first, last));
    // The source may be this vector's own storage (v.assign(v.begin(), ...)): copy through a
    // temporary then.
    if (n > cap_) {
      SmallVector tmp;
      tmp.reserve(n);
      std::copy(first, last, tmp.ptr_);
      tmp.size_ = n;
      *this = std::move(tmp);
      return;
    }
    std::copy(first, last, ptr_);
    size_ = n;
  }
  void push_back(const T& value) {
    if (size_ == cap_) {
      const T copy = value;  // value may live in this vector
      reserve(2 * cap_);
      ptr_[size_++] = copy;
      return;
    }
    ptr_[size_++] = value;
  }
  template <class... Args>
  T& emplace_back(Args&&... args) {
    push_back(T{std::forward<Args>(args)...});
    return back();
  }
  void pop_back() { --size_; }
  // Inserts [first, last) (not from this vector) before pos.
  template <class It, class = typename std::iterator_traits<It>::iterator_category>
  iterator insert(const_iterator pos, It first, It last) {
    const auto at = static_cast<size_type>(pos - ptr_);
    const auto n = static_cast<size_type>(std::distance(first, last));
    if (size_ + n > cap_) reserve(std::max(size_ + n, 2 * cap_));
    std::memmove(static_cast<void*>(ptr_ + at + n), ptr_ + at, (size_ - at) * sizeof(T));
    std::copy(first, last, ptr_ + at);
    size_ += n;
    return ptr_ + at;
  }

  friend bool operator==(const SmallVector& a, const SmallVector& b) {
    return a.size_ == b.size_ && std::equal(a.begin(), a.end(), b.begin());
  }

 private:
  bool inline_storage() const { return ptr_ == reinterpret_cast<const T*>(local_); }
  void release() {
    if (!inline_storage()) ::operator delete(ptr_);
    ptr_ = reinterpret_cast<T*>(local_);
    cap_ = N;
    size_ = 0;
  }
  void steal(SmallVector& o) {
    if (o.inline_storage()) {
      std::memcpy(static_cast<void*>(local_), o.local_, o.size_ * sizeof(T));
      ptr_ = reinterpret_cast<T*>(local_);
      cap_ = N;
    } else {
      ptr_ = o.ptr_;
      cap_ = o.cap_;
      o.ptr_ = reinterpret_cast<T*>(o.local_);
      o.cap_ = N;
    }
    size_ = o.size_;
    o.size_ = 0;
  }

  alignas(T) unsigned char local_[N * sizeof(T)];
  T* ptr_ = reinterpret_cast<T*>(local_);
  size_type size_ = 0;
  size_type cap_ = N;
};

}  // namespace delcert::exact
