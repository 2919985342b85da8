#include "snapshot/state_stream.h"

#include <btBulletDynamicsCommon.h>

#include <cinttypes>
#include <cmath>
#include <cstddef>
#include <cstdio>

namespace vp {

namespace {

constexpr char kMagic[8] = {'V', 'P', 'S', 'T', 'A', 'T', 'E', '\0'};
// Raised whenever what a payload holds, or its order, changes.
constexpr uint32_t kFormatVersion = 14;
constexpr uint32_t kByteOrderMark = 0x01020304u;

struct Header {
  char magic[8];
  uint32_t version;
  uint32_t byteOrder;
  uint32_t doubleSize;
  uint32_t bulletScalarSize;
  uint64_t payloadSize;
  uint64_t checksum;
};
static_assert(sizeof(Header) == kStateHeaderBytes && offsetof(Header, checksum) == kStateChecksumOffset);

}  // namespace

uint64_t stateChecksum(const uint8_t* data, size_t size) {
  uint64_t h = 14695981039346656037ull;
  for (size_t i = 0; i < size; ++i) {
    h ^= data[i];
    h *= 1099511628211ull;
  }
  return h;
}

void StateWriter::bytes(const void* data, size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  payload_.insert(payload_.end(), p, p + size);
}

std::vector<uint8_t> StateWriter::finish() const {
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kFormatVersion;
  h.byteOrder = kByteOrderMark;
  h.doubleSize = sizeof(double);
  h.bulletScalarSize = sizeof(btScalar);
  h.payloadSize = payload_.size();
  h.checksum = stateChecksum(payload_.data(), payload_.size());
  std::vector<uint8_t> out(sizeof h + payload_.size());
  std::memcpy(out.data(), &h, sizeof h);
  if (!payload_.empty()) std::memcpy(out.data() + sizeof h, payload_.data(), payload_.size());
  return out;
}

StateReader::StateReader(const uint8_t* buffer, size_t size) {
  Header h{};
  if (size < sizeof h) {
    failWith(Status::ParseError, "size = " + std::to_string(size) + ": shorter than a saved state's header (" +
                                     std::to_string(sizeof h) + " bytes)");
    return;
  }
  std::memcpy(&h, buffer, sizeof h);
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0) {
    failWith(Status::ParseError, "buffer: not a VolPhys saved state (no \"VPSTATE\" mark at its start)");
    return;
  }
  if (h.version != kFormatVersion) {
    failWith(Status::VersionMismatch, "buffer: saved state format " + std::to_string(h.version) +
                                          "; this library reads format " + std::to_string(kFormatVersion));
    return;
  }
  if (h.byteOrder != kByteOrderMark || h.doubleSize != sizeof(double) || h.bulletScalarSize != sizeof(btScalar)) {
    failWith(Status::VersionMismatch, "buffer: saved by a build with another byte order or number sizes (double " +
                                          std::to_string(h.doubleSize) + " bytes, Bullet scalar " +
                                          std::to_string(h.bulletScalarSize) + ")");
    return;
  }
  if (h.payloadSize != size - sizeof h) {
    failWith(Status::ParseError, "size = " + std::to_string(size) + ": the saved state's header says " +
                                     std::to_string(h.payloadSize + sizeof h) + " bytes (truncated or padded)");
    return;
  }
  data_ = buffer + sizeof h;
  size_ = static_cast<size_t>(h.payloadSize);
  if (stateChecksum(data_, size_) != h.checksum)
    failWith(Status::ParseError, "buffer: the saved state's checksum does not match its content (corrupted)");
}

void StateReader::bytes(void* out, size_t size) {
  if (!ok() || size > size_ - offset_) {
    if (ok()) failWith(Status::ParseError, "buffer: the saved state ends before its content does");
    std::memset(out, 0, size);
    return;
  }
  if (size > 0) std::memcpy(out, data_ + offset_, size);
  offset_ += size;
}

bool StateReader::fits(uint64_t count, size_t elementSize) {
  if (count <= (size_ - offset_) / elementSize) return true;
  failWith(Status::ParseError, "buffer: the saved state ends before its content does");
  return false;
}

void StateReader::requireFinite(const char* what, const double* values, size_t count) {
  if (!ok()) return;
  for (size_t i = 0; i < count; ++i)
    if (!std::isfinite(values[i])) {
      failWith(Status::ParseError, std::string("buffer: ") + what + " holds a value that is not finite");
      return;
    }
}

void StateReader::outOfRange(const char* what) {
  failWith(Status::ParseError, std::string("buffer: ") + what + " is out of range");
}

void StateReader::expect(const char* what, uint64_t found, uint64_t expected) {
  if (ok() && found != expected) mismatch(what, found, expected);
}

void StateReader::mismatch(const char* what, uint64_t found, uint64_t expected) {
  failWith(Status::InvalidArgument, std::string("buffer: saved from another world: its ") + what + " is " +
                                        std::to_string(found) + "; this world's is " + std::to_string(expected));
}

void StateReader::tooMany(const char* what, uint64_t found, uint64_t limit) {
  failWith(Status::ParseError,
           std::string("buffer: ") + what + " = " + std::to_string(found) + ", more than " + std::to_string(limit));
}

Status StateReader::finish() {
  if (ok() && offset_ != size_)
    failWith(Status::ParseError, "buffer: " + std::to_string(size_ - offset_) +
                                     " bytes left over after the saved state's content");
  return status_;
}

Status StateReader::failWith(Status code, const std::string& message) {
  if (ok()) status_ = fail(code, "%s", message.c_str());
  return status_;
}

}  // namespace vp
