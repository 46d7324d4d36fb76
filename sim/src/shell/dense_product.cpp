// C = A B^T for the block factorisation's dense panels (block_ldlt.cpp): column-major, no Eigen
// types across the boundary (a translation unit that builds Eigen for another instruction set than
// the rest breaks its alignment and inline functions), each entry summed over k in order by fused
// multiply-adds from zero, so that every path gives the same bits.
#include "shell/dense_product.h"

#include <cmath>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SIM_DENSE_PRODUCT_AVX2 1
#endif

namespace sim {

namespace {

// Entry (i, j) of A B^T: sum over k in order, each term fused.
inline double Entry(int i, int j, int K, const double* A, int lda, const double* B, int ldb) {
    double sum = 0;
    for (int k = 0; k < K; ++k) sum = std::fma(A[static_cast<long>(k) * lda + i], B[static_cast<long>(k) * ldb + j], sum);
    return sum;
}

void MultiplyPortable(int M, int N, int K, const double* A, int lda, const double* B, int ldb, double* C, int ldc) {
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < M; ++i) C[static_cast<long>(j) * ldc + i] = Entry(i, j, K, A, lda, B, ldb);
}

#ifdef SIM_DENSE_PRODUCT_AVX2
// Three columns at a time (the factorisation's blocks are 3 wide): rows in tiles of 12 (three 4-wide
// accumulators a column), then of 4, then the last rows and any columns past a multiple of three
// entry by entry, with the same sums.
template <int Vectors>
__attribute__((target("avx2,fma"), always_inline)) inline void Tile(int K, const double* a, int lda, const double* b, int ldb, double* c, int ldc) {
    __m256d sum[3][Vectors];
    for (int j = 0; j < 3; ++j)
        for (int v = 0; v < Vectors; ++v) sum[j][v] = _mm256_setzero_pd();
    for (int k = 0; k < K; ++k, a += lda, b += ldb) {
        __m256d column[Vectors];
        for (int v = 0; v < Vectors; ++v) column[v] = _mm256_loadu_pd(a + 4 * v);
        for (int j = 0; j < 3; ++j) {
            const __m256d scale = _mm256_broadcast_sd(b + j);
            for (int v = 0; v < Vectors; ++v) sum[j][v] = _mm256_fmadd_pd(column[v], scale, sum[j][v]);
        }
    }
    for (int j = 0; j < 3; ++j)
        for (int v = 0; v < Vectors; ++v) _mm256_storeu_pd(c + static_cast<long>(j) * ldc + 4 * v, sum[j][v]);
}

__attribute__((target("avx2,fma"))) void MultiplyAvx2(int M, int N, int K, const double* A, int lda, const double* B, int ldb, double* C,
                                                      int ldc) {
    const int wholeColumns = N - N % 3;
    for (int j = 0; j < wholeColumns; j += 3) {
        int i = 0;
        for (; i + 12 <= M; i += 12) Tile<3>(K, A + i, lda, B + j, ldb, C + static_cast<long>(j) * ldc + i, ldc);
        for (; i + 4 <= M; i += 4) Tile<1>(K, A + i, lda, B + j, ldb, C + static_cast<long>(j) * ldc + i, ldc);
        for (int jj = j; jj < j + 3; ++jj)
            for (int r = i; r < M; ++r) C[static_cast<long>(jj) * ldc + r] = Entry(r, jj, K, A, lda, B, ldb);
    }
    for (int j = wholeColumns; j < N; ++j)
        for (int i = 0; i < M; ++i) C[static_cast<long>(j) * ldc + i] = Entry(i, j, K, A, lda, B, ldb);
}

bool HasAvx2() {
    static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return has;
}
#endif

}  // namespace

void MultiplyTransposed(int M, int N, int K, const double* A, int lda, const double* B, int ldb, double* C, int ldc, bool portable) {
#ifdef SIM_DENSE_PRODUCT_AVX2
    if (!portable && HasAvx2()) {
        MultiplyAvx2(M, N, K, A, lda, B, ldb, C, ldc);
        return;
    }
#endif
    (void)portable;
    MultiplyPortable(M, N, K, A, lda, B, ldb, C, ldc);
}

}  // namespace sim
