// Hot loops built for several x86-64 instruction sets and picked when the library loads
// (GCC's function multiversioning, through an ifunc): a binary built for the x86-64 baseline,
// as a distributed one must be, still runs its vectorized loops with AVX2 or AVX-512 where
// the machine has them. Put VP_ISA_CLONES in front of a function's definition.
//
// Every clone gives the baseline's bits (NaN payloads aside): floating-point contraction is off
// wherever the runtime is compiled (runtime/CMakeLists.txt), so clones with FMA do not fuse a
// multiply and an add, and vector lanes round like scalars. Elsewhere (other compilers, GCC
// before 12, which lacks arch= clones, other architectures) the macro is empty, and so it is
// under ThreadSanitizer, which instruments the ifunc resolvers that the loader runs before
// TSan's runtime has started. The clones' ifunc symbols ignore -fvisibility=hidden;
// libvolphys.so's version script keeps them local.
//
// A clone is compiled for its instruction set, but what it calls is not: a helper (a template,
// a lambda) that holds the loop must be inlined into the clone, which VP_CLONE_INLINE forces
// (GCC otherwise outlines a lambda called from two places, and its loop runs on the baseline).
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12 && defined(__x86_64__) && defined(__linux__) && \
    !defined(__SANITIZE_THREAD__)
#define VP_ISA_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define VP_ISA_CLONES
#endif

#if defined(__GNUC__)
#define VP_CLONE_INLINE __attribute__((always_inline))
#else
#define VP_CLONE_INLINE
#endif
