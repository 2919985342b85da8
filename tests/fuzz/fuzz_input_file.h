// The readers under fuzzing take paths: each input is written to a file of the right
// extension in a directory of this process's own, then read back by the reader.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

namespace vp::fuzz {

inline std::string writeInput(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = "/tmp/vp_fuzz_" + std::to_string(::getpid()) + "_" + name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

}  // namespace vp::fuzz
