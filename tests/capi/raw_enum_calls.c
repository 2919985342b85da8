/* Calls that pass an arbitrary int where the C ABI takes an enum, as a C host may. In C the int
 * converts to the enum type; in C++ even loading such an enum value is undefined, and calling the
 * function through a pointer to another type is too, so the tests call through here. */
#include "raw_enum_calls.h"

vpStatus rawFluidGetField(vpFluidId fluid, int field, float* values, int64_t capacity) {
  return vpFluidGetField(fluid, (vpFluidField)field, values, capacity);
}
