// Byte records for the rank exchanges (the fiber record Model/FiberWire, Solver/Decomposition,
// Solver/LinkExchange, Parallel/TileExchange): plain copies of trivially copyable values in the
// host's byte order, read back in the order written. Files, whose byte order is fixed by their
// format, use Util/BinaryIO.h instead.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace fiberpli
{

/// Appends n values from v to out as raw bytes.
template <class T>
void appendBytes(std::vector<char>& out, const T* v, std::size_t n)
{
  const std::size_t at = out.size();
  out.resize(at + n * sizeof(T));
  if (n > 0)
    std::memcpy(out.data() + at, v, n * sizeof(T));
}

class ByteWriter
{
public:
  explicit ByteWriter(std::vector<char>& out)
    : out_(&out)
  {
  }
  template <class T>
  void put(const T& v)
  {
    appendBytes(*out_, &v, 1);
  }
  /// n values, without their count.
  template <class T>
  void put(const T* v, std::size_t n)
  {
    appendBytes(*out_, v, n);
  }
  /// The size, then the values.
  template <class T>
  void putVector(const std::vector<T>& v)
  {
    put<std::uint64_t>(v.size());
    appendBytes(*out_, v.data(), v.size());
  }

private:
  std::vector<char>* out_;
};

class ByteReader
{
public:
  explicit ByteReader(const std::vector<char>& in)
    : in_(&in)
  {
  }
  bool done() const { return at_ >= in_->size(); }
  template <class T>
  T get()
  {
    T v;
    get(&v);
    return v;
  }
  template <class T>
  void get(T* v, std::size_t n = 1)
  {
    if (n > 0)
      std::memcpy(v, in_->data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
  }
  /// Passes over n values of T without reading them.
  template <class T>
  void skip(std::size_t n)
  {
    at_ += n * sizeof(T);
  }
  /// What putVector wrote.
  template <class T>
  void getVector(std::vector<T>& v)
  {
    v.resize(get<std::uint64_t>());
    get(v.data(), v.size());
  }

private:
  const std::vector<char>* in_;
  std::size_t at_ = 0;
};

} // namespace fiberpli
