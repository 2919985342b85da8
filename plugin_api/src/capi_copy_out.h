// Copies of runtime arrays into host buffers, shared by the getters that hand out meshes and
// id lists, so every one checks capacities and reports them the same way.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/allocator.h"
#include "core/math_types.h"
#include "core/status.h"

namespace vp::capi {

// Triangle mesh into optional host arrays (any may be NULL); capacities are in vertices and
// triangles. `what` names the mesh in messages ("render mesh", "shape mesh").
inline Status copyMeshOut(const char* what, const Array<Vec3>& positions, const Array<Vec3>& normals,
                          const Array<std::array<int32_t, 3>>& triangles, float* outPositions,
                          float* outNormals, int32_t vertexCapacity, int32_t* outTriangles, int32_t triangleCapacity) {
  const int32_t nv = static_cast<int32_t>(positions.size()), nt = static_cast<int32_t>(triangles.size());
  if ((outPositions || outNormals) && vertexCapacity < nv)
    return fail(Status::InvalidArgument, "vertexCapacity = %d: the %s has %d vertices", vertexCapacity, what, nv);
  if (outTriangles && triangleCapacity < nt)
    return fail(Status::InvalidArgument, "triangleCapacity = %d: the %s has %d triangles", triangleCapacity, what, nt);
  for (int32_t i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k) {
      if (outPositions) outPositions[3 * i + k] = static_cast<float>(positions[i][k]);
      if (outNormals) outNormals[3 * i + k] = static_cast<float>(normals[i][k]);
    }
  if (outTriangles) std::memcpy(outTriangles, triangles.data(), sizeof(int32_t) * 3 * static_cast<size_t>(nt));
  return Status::Ok;
}

// The ids of a world's objects in slot order; a short buffer gets a prefix.
template <class Id, class Handle, class MakeId>
Status copyIdsOut(const std::vector<Handle>& handles, MakeId makeId, Id* outIds, int32_t capacity, int32_t* outCount) {
  if (capacity < 0) return fail(Status::InvalidArgument, "capacity = %d: must be >= 0", capacity);
  if (capacity > 0 && !outIds) return fail(Status::InvalidArgument, "outIds is NULL with capacity = %d", capacity);
  const int32_t n = static_cast<int32_t>(handles.size());
  for (int32_t i = 0; i < n && i < capacity; ++i) outIds[i] = makeId(handles[i]);
  *outCount = n < capacity ? n : capacity;
  return Status::Ok;
}

// A string with its terminator into a host buffer; *outLength = the bytes it needs. buffer NULL
// with capacity 0 asks only for the length; a short buffer gets nothing but the length. The
// ABI's strings end at their first NUL, so a name holding one is cut there.
inline Status copyStringOut(const std::string& text, char* buffer, int32_t capacity, int32_t* outLength) {
  if (capacity < 0) return fail(Status::InvalidArgument, "capacity = %d: must be >= 0", capacity);
  if (!buffer && capacity != 0)
    return fail(Status::InvalidArgument, "buffer is NULL with capacity = %d (capacity 0 asks for the length)", capacity);
  const size_t bytes = std::strlen(text.c_str()) + 1;
  if (bytes > static_cast<size_t>(INT32_MAX)) return fail(Status::Internal, "a name of %zu bytes", bytes);
  *outLength = static_cast<int32_t>(bytes);
  if (!buffer) return Status::Ok;
  if (static_cast<size_t>(capacity) < bytes)
    return fail(Status::InvalidArgument, "capacity = %d: the name needs %zu bytes with its terminator (*outLength)",
                capacity, bytes);
  std::memcpy(buffer, text.c_str(), bytes);
  return Status::Ok;
}

}  // namespace vp::capi
