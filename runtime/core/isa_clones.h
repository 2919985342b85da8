// Hot loops built for several x86-64 instruction sets and picked when the library loads
// (GCC's function multiversioning, through an ifunc): a binary built for the x86-64 baseline,
// as a distributed one must be, still runs its vectorized loops with AVX2 or AVX-512 where
// the machine has them. Put VP_ISA_CLONES in front of a function's definition.
//
// Every clone gives the same bits as the baseline: the runtime is compiled with floating-point
// contraction off (runtime/CMakeLists.txt), so the clones that have FMA do not fuse a multiply
// and an add (which rounds once instead of twice), and vector lanes round like scalars.
// Elsewhere (other compilers, other architectures) the macro is empty.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define VP_ISA_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define VP_ISA_CLONES
#endif
