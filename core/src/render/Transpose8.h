#pragma once
// Private to core: an 8 x 8 transpose of 64-bit elements in AVX-512 registers, for kernels that
// load one record per lane (eight consecutive 64-bit fields) and compute one field per register.
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

namespace octrace::detail {

/// field[f] element k := row[k] element f (row k: lane k's eight fields, in order).
[[gnu::target("avx512f")]] inline void transpose8(const __m512i row[8], __m512i field[8]) {
    __m512i t[8], u[8];
    for (int k = 0; k < 8; k += 2) {
        // The masked forms: GCC 12's plain unpacks read an undefined operand (-Wuninitialized).
        t[k] = _mm512_maskz_unpacklo_epi64(0xFF, row[k], row[k + 1]);      // fields 0, 2, 4, 6 of lanes k, k+1
        t[k + 1] = _mm512_maskz_unpackhi_epi64(0xFF, row[k], row[k + 1]);  // fields 1, 3, 5, 7
    }
    const __m512i lo = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0), hi = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
    for (int k = 0; k < 8; k += 4)
        for (int odd = 0; odd < 2; ++odd) {
            u[k + odd] = _mm512_permutex2var_epi64(t[k + odd], lo, t[k + 2 + odd]);      // fields 0|1, 4|5 of 4 lanes
            u[k + 2 + odd] = _mm512_permutex2var_epi64(t[k + odd], hi, t[k + 2 + odd]);  // fields 2|3, 6|7
        }
    // Field f < 4 from the first halves of u[f] and u[f + 4], field f + 4 from their second halves.
    const __m512i first = _mm512_set_epi64(11, 10, 9, 8, 3, 2, 1, 0), second = _mm512_set_epi64(15, 14, 13, 12, 7, 6, 5, 4);
    for (int f = 0; f < 4; ++f) {
        field[f] = _mm512_permutex2var_epi64(u[f], first, u[f + 4]);
        field[f + 4] = _mm512_permutex2var_epi64(u[f], second, u[f + 4]);
    }
}

/// transpose8 of doubles (the bits moved as they are).
[[gnu::target("avx512f")]] inline void transpose8(const __m512d row[8], __m512d field[8]) {
    __m512i r[8], f[8];
    for (int k = 0; k < 8; ++k) r[k] = _mm512_castpd_si512(row[k]);
    transpose8(r, f);
    for (int k = 0; k < 8; ++k) field[k] = _mm512_castsi512_pd(f[k]);
}

}  // namespace octrace::detail
#endif
