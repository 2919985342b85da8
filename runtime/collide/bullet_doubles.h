// Bullet's vectors and transforms as doubles and back, for saved world states: Bullet's
// scalars (float or double) widen to double exactly, so a round trip keeps every bit.
#pragma once

#include <btBulletDynamicsCommon.h>

namespace vp {

inline void toDoubles(const btVector3& v, double* out) {
  for (int k = 0; k < 3; ++k) out[k] = v[k];
}

inline btVector3 btVectorFrom(const double* in) {
  return btVector3(btScalar(in[0]), btScalar(in[1]), btScalar(in[2]));
}

// The basis row by row, then the origin: 12 values.
inline void toDoubles(const btTransform& t, double* out) {
  for (int r = 0; r < 3; ++r) toDoubles(t.getBasis()[r], out + 3 * r);
  toDoubles(t.getOrigin(), out + 9);
}

inline btTransform btTransformFrom(const double* in) {
  btMatrix3x3 basis;
  for (int r = 0; r < 3; ++r) basis[r] = btVectorFrom(in + 3 * r);
  return btTransform(basis, btVectorFrom(in + 9));
}

}  // namespace vp
