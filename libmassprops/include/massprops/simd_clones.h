#pragma once
/// @file
/// Functions compiled for more than one instruction set, the CPU's chosen when the library loads
/// (GCC's `target_clones`): loops that vectorize run with AVX2 — and AVX-512 where named — on the
/// machines that have them, and with the baseline's SSE2 elsewhere, from one binary. Every clone
/// computes the same bits: they vectorize across independent items, no reduction is reordered, and
/// the targets' -ffp-contract=off (massprops_set_floating_point) keeps AVX-512's FMAs out.
/// Plain functions under other compilers, other architectures and AddressSanitizer (whose
/// instrumentation the clones' resolver runs before).
///
///     MASSPROPS_CLONES_AVX2 void Scan(...);         // AVX2 or the baseline
///     MASSPROPS_CLONES_AVX2_AVX512 void Sum(...);   // x86-64-v4 (AVX-512), AVX2 or the baseline

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define MASSPROPS_CLONES_AVX2 __attribute__((target_clones("avx2", "default")))
#define MASSPROPS_CLONES_AVX2_AVX512 __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define MASSPROPS_CLONES_AVX2
#define MASSPROPS_CLONES_AVX2_AVX512
#endif
