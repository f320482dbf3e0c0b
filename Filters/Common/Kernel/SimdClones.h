// SPDX-License-Identifier: BSD-3-Clause
// AV_SIMD_CLONES: marks a hot kernel for an AVX2/FMA clone chosen at load time (GCC function
// multi-versioning); the build itself targets baseline x86-64, so other CPUs and compilers get
// the plain version.
#ifndef av_SimdClones_h
#define av_SimdClones_h

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define AV_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define AV_SIMD_CLONES
#endif

#endif
