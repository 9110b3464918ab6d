// A small binary archive for checkpoints: values in host byte order (the file records which),
// strings and vectors prefixed by their length, and the FNV-1a 64 checksum.
//
// BinaryWriter and BinaryReader have the same call operator, so one function template listing
// the fields of a struct serves for writing (with a const object) and reading (non-const):
//
//   template <class Ar, class T> void fields(Ar& ar, T& t) { ar(t.a); ar(t.b); }
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "particula/io/error.hpp"

namespace particula::io {

/// FNV-1a 64-bit hash of `bytes`, continuing from `hash`.
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash = 0xcbf29ce484222325ull);

/// Values copied byte for byte: arithmetic types, enums and plain structs of them (Vec2, Mat2).
template <class T>
concept RawValue = std::is_trivially_copyable_v<T> && std::is_standard_layout_v<T> && !std::is_pointer_v<T> &&
                   !std::is_same_v<T, bool>;

class BinaryWriter {
 public:
  template <RawValue T>
  void operator()(const T& v) {
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void operator()(bool v) { out_.push_back(v ? '\1' : '\0'); }
  void operator()(const std::string& s) {
    (*this)(static_cast<std::uint64_t>(s.size()));
    out_.append(s);
  }
  template <RawValue T>
  void operator()(const std::vector<T>& v) {
    (*this)(static_cast<std::uint64_t>(v.size()));
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }

  const std::string& bytes() const { return out_; }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

/// Reads what BinaryWriter wrote. Every read is bounds-checked: running past the end throws
/// IoError("<what>: truncated ..."), and so do a length prefix larger than the remaining bytes
/// and a bool byte other than 0 or 1. Vectors of structs are written by the caller as a length
/// (read back with read_size()) followed by each element's fields.
class BinaryReader {
 public:
  BinaryReader(std::string_view data, std::string what) : data_(data), what_(std::move(what)) {}

  template <RawValue T>
  void operator()(T& v) {
    std::memcpy(&v, take(sizeof(T)), sizeof(T));
  }
  void operator()(bool& v) {
    const unsigned char b = static_cast<unsigned char>(*take(1));
    if (b > 1) throw IoError(what_ + ": corrupted (invalid boolean)");
    v = b == 1;
  }
  void operator()(std::string& s) {
    const std::size_t n = read_size(1);
    s.assign(take(n), n);
  }
  template <RawValue T>
  void operator()(std::vector<T>& v) {
    const std::size_t n = read_size(sizeof(T));
    v.resize(n);
    if (n > 0) std::memcpy(v.data(), take(n * sizeof(T)), n * sizeof(T));
  }

  /// A length prefix of elements of at least `min_element_bytes` each, checked against the
  /// bytes left (so corrupted lengths never cause huge allocations).
  std::size_t read_size(std::size_t min_element_bytes) {
    std::uint64_t n = 0;
    (*this)(n);
    if (min_element_bytes > 0 && n > remaining() / min_element_bytes)
      throw IoError(what_ + ": corrupted or truncated (a length exceeds the data left)");
    return static_cast<std::size_t>(n);
  }

  std::size_t remaining() const { return data_.size() - pos_; }
  const std::string& what() const { return what_; }

 private:
  const char* take(std::size_t n) {
    if (n > remaining()) throw IoError(what_ + ": truncated (the data ends early)");
    const char* p = data_.data() + pos_;
    pos_ += n;
    return p;
  }

  std::string_view data_;
  std::size_t pos_ = 0;
  std::string what_;
};

}  // namespace particula::io
