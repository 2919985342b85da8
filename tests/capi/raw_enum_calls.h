/* C calls into the C ABI with an arbitrary int for an enum parameter (raw_enum_calls.c). */
#ifndef VP_TESTS_RAW_ENUM_CALLS_H
#define VP_TESTS_RAW_ENUM_CALLS_H

#include "volphys/volphys.h"

#ifdef __cplusplus
extern "C" {
#endif

vpStatus rawFluidGetField(vpFluidId fluid, int field, float* values, int64_t capacity);

#ifdef __cplusplus
}
#endif

#endif
