// The byte format of a world's saved state (vpWorldSaveState / vpWorldRestoreState).
//
//   header   magic "VPSTATE\0", format version, byte-order mark, sizes of double and of
//            Bullet's scalar, payload size, checksum of the payload (64-bit FNV-1a: any
//            change of a single byte changes it)
//   payload  the values in the order the writer put them, in the machine's own layout
//            (a buffer is for the same build on the same kind of machine; the header
//            rejects others)
//
// The reader never reads past the payload: every read is bounds-checked, and the first
// failure is kept (later reads return zeros) so a parse reads straight through and checks
// once. A count read from the buffer is checked against what the world expects before it
// sizes anything, so a corrupted buffer cannot make the reader allocate wildly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/allocator.h"
#include "core/status.h"

namespace vp {

class StateWriter {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof(T));
  }
  // Its length, then its elements.
  template <class T, class A>
  void array(const std::vector<T, A>& a) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(static_cast<uint64_t>(a.size()));
    bytes(a.data(), a.size() * sizeof(T));
  }
  void bytes(const void* data, size_t size);
  void doubles(const double* data, size_t count) { bytes(data, count * sizeof(double)); }

  // The header and the payload, ready to hand out.
  std::vector<uint8_t> finish() const;

 private:
  std::vector<uint8_t> payload_;
};

class StateReader {
 public:
  // Checks the header (magic, version, layout, size, checksum); on failure ok() is false
  // and status() names what is wrong.
  StateReader(const uint8_t* buffer, size_t size);

  template <class T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v{};
    bytes(&v, sizeof(T));
    return v;
  }
  // An array that must have exactly `expected` elements (`what` names it in the error).
  template <class T, class A>
  void array(std::vector<T, A>* out, uint64_t expected, const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    const uint64_t n = value<uint64_t>();
    if (!ok()) return;
    if (n != expected) {
      mismatch(what, n, expected);
      return;
    }
    if (!fits(n, sizeof(T))) return;
    out->resize(static_cast<size_t>(n));
    bytes(out->data(), static_cast<size_t>(n) * sizeof(T));
  }
  // An array of at most `limit` elements (lists that change length, like contacts).
  template <class T, class A>
  void arrayUpTo(std::vector<T, A>* out, uint64_t limit, const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    const uint64_t n = value<uint64_t>();
    if (!ok()) return;
    if (n > limit) {
      tooMany(what, n, limit);
      return;
    }
    if (!fits(n, sizeof(T))) return;
    out->resize(static_cast<size_t>(n));
    bytes(out->data(), static_cast<size_t>(n) * sizeof(T));
  }
  void bytes(void* out, size_t size);
  // Whether `count` elements of `elementSize` bytes are left to read (fails if not).
  bool has(uint64_t count, size_t elementSize) { return ok() && fits(count, elementSize); }
  void doubles(double* out, size_t count) { bytes(out, count * sizeof(double)); }
  // Fails unless every value is finite (`what` names them).
  void requireFinite(const char* what, const double* values, size_t count);
  // Fails with "buffer: <what> is out of range" (a value a valid state cannot hold).
  void outOfRange(const char* what);
  // A value the world must have (a count, a kind, an id): a different one fails with
  // "the buffer's <what> is <found>; this world's is <expected>".
  void expect(const char* what, uint64_t found, uint64_t expected);

  bool ok() const { return status_ == Status::Ok; }
  // The first failure (its message is the thread's last error), or Ok.
  Status status() const { return status_; }
  // After the last read: anything left over is an error too.
  Status finish();

 private:
  bool fits(uint64_t count, size_t elementSize);
  void mismatch(const char* what, uint64_t found, uint64_t expected);
  void tooMany(const char* what, uint64_t found, uint64_t limit);
  Status failWith(Status code, const std::string& message);

  const uint8_t* data_ = nullptr;
  size_t size_ = 0, offset_ = 0;
  Status status_ = Status::Ok;
};

// The checksum of the format (64-bit FNV-1a).
uint64_t stateChecksum(const uint8_t* data, size_t size);

// Where the header ends (the payload begins) and where in it the payload's checksum lies.
constexpr size_t kStateHeaderBytes = 40, kStateChecksumOffset = 32;

}  // namespace vp
