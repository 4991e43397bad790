// An immutable array that copies share: the library's own vector, or memory a caller lends (a
// NumPy array from Python) kept alive by the caller's handle, so that a mesh given as arrays is not
// copied.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace roving {

template <class T>
class SharedArray {
 public:
  SharedArray() = default;
  // Takes over `values` (implicit: a vector is the common case).
  SharedArray(std::vector<T> values)
      : vector_(std::make_shared<std::vector<T>>(std::move(values))),
        data_(vector_->data()),
        size_(vector_->size()) {}
  // Reads `size` values at `data`, which stay valid and unchanged while `lender` lives.
  SharedArray(const T* data, std::size_t size, std::shared_ptr<const void> lender)
      : lender_(std::move(lender)), data_(data), size_(size) {}

  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  // True where the values are a caller's memory, not a copy.
  bool lent() const { return lender_ != nullptr; }

  std::vector<T> to_vector() const { return std::vector<T>(begin(), end()); }
  friend bool operator==(const SharedArray& a, const SharedArray& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }

  // The values as a vector of one's own: moved out when this array is the vector's only holder,
  // copied otherwise. Leaves this array empty.
  std::vector<T> release() {
    std::vector<T> out = vector_ && vector_.use_count() == 1 ? std::move(*vector_) : to_vector();
    *this = SharedArray();
    return out;
  }

 private:
  std::shared_ptr<std::vector<T>> vector_;  // the values when they are the library's own
  std::shared_ptr<const void> lender_;      // what keeps lent values alive
  const T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace roving
