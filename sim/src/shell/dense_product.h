// The dense product the block factorisation's supernodes spend their time in.
#pragma once

namespace sim {

// C = A B^T with A M x K, B N x K and C M x N, column-major with leading dimensions lda, ldb, ldc.
// Each entry is its products summed over k in order by fused multiply-adds from zero: the same bits
// from the vector path (AVX2, chosen at run time) and the portable one (`portable`, which tests use
// to compare them), on any machine.
void MultiplyTransposed(int M, int N, int K, const double* A, int lda, const double* B, int ldb, double* C, int ldc, bool portable = false);

}  // namespace sim
