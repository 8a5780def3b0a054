#pragma once
// The hot loops (E-step, M-step, assignment, angular step, binning) are compiled twice on x86-64
// Linux with GCC: for AVX2 and for the baseline; the loader picks the clone the CPU runs (ifunc).
// Both compute the same floats in the same order (no FMA contraction), so results do not depend
// on the CPU.

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define RELPLANE_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RELPLANE_SIMD_CLONES
#endif
