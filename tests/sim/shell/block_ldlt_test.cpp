// The block L D L^T against dense factorisations: solutions, inertia (the shell models' limit-point
// test reads it), shifts, padded blocks, zero pivots; and against Eigen's scalar SimplicialLDLT on
// a shell model's Hessian.
#include "shell/block_ldlt.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <numbers>
#include <cstring>
#include <random>
#include <thread>

#include "shell/dense_product.h"
#include "shell/shell_problem.h"

namespace {

// A random sparse symmetric matrix over `unknowns` with about `perColumn` couplings per column,
// made diagonally dominant (positive definite), then shifted down by `shiftDown` (indefinite).
Eigen::SparseMatrix<double> RandomSymmetric(int unknowns, int perColumn, double shiftDown, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> pick(0, unknowns - 1);
    std::uniform_real_distribution<double> value(-1, 1);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(unknowns, unknowns);
    for (int col = 0; col < unknowns; ++col)
        for (int k = 0; k < perColumn; ++k) {
            const int row = pick(rng);
            const double v = value(rng);
            dense(row, col) += v;
            dense(col, row) += v;
        }
    for (int d = 0; d < unknowns; ++d) dense(d, d) = dense.row(d).cwiseAbs().sum() + 1 - shiftDown;
    return dense.sparseView();
}

// Places with partly used blocks: unknowns in runs of 3, 2 and 1 per block, shuffled.
std::vector<int> Places(int unknowns, unsigned seed) {
    std::vector<int> places;
    int block = 0;
    for (int used = 3; static_cast<int>(places.size()) < unknowns; ++block, used = used == 1 ? 3 : used - 1)
        for (int c = 0; c < used && static_cast<int>(places.size()) < unknowns; ++c) places.push_back(3 * block + (c + block) % 3);
    std::shuffle(places.begin(), places.end(), std::mt19937(seed));
    return places;
}

Eigen::SparseMatrix<double> WithFullDiagonal(Eigen::SparseMatrix<double> m) {
    for (int d = 0; d < m.rows(); ++d) m.coeffRef(d, d) += 0;
    m.makeCompressed();
    return m;
}

int NegativeEigenvalues(const Eigen::MatrixXd& m) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m);
    return static_cast<int>((eigen.eigenvalues().array() < 0).count());
}

TEST(BlockLdlt, SolvesPositiveDefiniteAndIndefiniteSystemsWithTheirInertia) {
    for (unsigned seed : {1u, 2u, 3u})
        for (double shiftDown : {0.0, 2.0, 4.0}) {
            const Eigen::SparseMatrix<double> A = WithFullDiagonal(RandomSymmetric(61, 3, shiftDown, seed));
            sim::BlockLdlt ldlt;
            ldlt.Analyse(A, Places(61, seed));
            ASSERT_TRUE(ldlt.Factorise(A, 0)) << "seed " << seed << ", shift " << shiftDown;
            const Eigen::MatrixXd dense = A;
            const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(61, -1, 2);
            const Eigen::VectorXd x = ldlt.Solve(b);
            EXPECT_LT((dense * x - b).norm(), 1e-10 * b.norm() * dense.norm()) << "seed " << seed << ", shift " << shiftDown;
            EXPECT_EQ(ldlt.NegativePivots(), NegativeEigenvalues(dense)) << "seed " << seed << ", shift " << shiftDown;
            const Eigen::VectorXd down = ldlt.NegativeCurvatureDirection();
            if (shiftDown == 0) {
                EXPECT_GT(ldlt.SmallestPivot(), 0);
                EXPECT_EQ(down.size(), 0);
            } else {
                EXPECT_GT(NegativeEigenvalues(dense), 0) << "the shifted matrix should be indefinite";
                ASSERT_EQ(down.size(), 61);
                EXPECT_LT(down.dot(dense * down), -1e-6 * down.squaredNorm()) << "seed " << seed << ", shift " << shiftDown;
            }
        }
}

TEST(BlockLdlt, AShiftIsTheShiftedMatrixsFactor) {
    const Eigen::SparseMatrix<double> A = WithFullDiagonal(RandomSymmetric(40, 4, 3.0, 7));
    sim::BlockLdlt ldlt;
    ldlt.Analyse(A, Places(40, 7));
    ASSERT_TRUE(ldlt.Factorise(A, 2.5));
    const Eigen::MatrixXd shifted = Eigen::MatrixXd(A) + 2.5 * Eigen::MatrixXd::Identity(40, 40);
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(40);
    // Backward stable: the residual is round-off of |A| |x|.
    const Eigen::VectorXd x = ldlt.Solve(b);
    EXPECT_LT((shifted * x - b).norm(), 1e-12 * shifted.norm() * x.norm());
    EXPECT_EQ(ldlt.NegativePivots(), NegativeEigenvalues(shifted));
    // Factorising again with other values reuses the analysis and forgets the last values.
    ASSERT_TRUE(ldlt.Factorise(A, 6.0));
    const Eigen::MatrixXd other = Eigen::MatrixXd(A) + 6.0 * Eigen::MatrixXd::Identity(40, 40);
    const Eigen::VectorXd y = ldlt.Solve(b);
    EXPECT_LT((other * y - b).norm(), 1e-12 * other.norm() * y.norm());
    EXPECT_EQ(ldlt.NegativePivots(), NegativeEigenvalues(other));
}

// The same bits from every analysis of a pattern, also when threads analyse at once (METIS keeps
// its random state in globals).
TEST(BlockLdlt, AnalysesOfOnePatternGiveTheSameBitsOnEveryThread) {
    const Eigen::SparseMatrix<double> A = WithFullDiagonal(RandomSymmetric(300, 3, 0.0, 11));
    const std::vector<int> places = Places(300, 11);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(300, -1, 1);
    auto solve = [&] {
        sim::BlockLdlt ldlt;
        ldlt.Analyse(A, places);
        EXPECT_TRUE(ldlt.Factorise(A, 0));
        return ldlt.Solve(b);
    };
    const Eigen::VectorXd first = solve();
    std::vector<Eigen::VectorXd> others(8);
    std::vector<std::thread> threads;
    for (auto& other : others) threads.emplace_back([&] { other = solve(); });
    for (auto& t : threads) t.join();
    for (const auto& other : others) EXPECT_EQ(0, std::memcmp(first.data(), other.data(), sizeof(double) * first.size()));
}

TEST(BlockLdlt, AZeroPivotIsAFailureNotACrash) {
    Eigen::SparseMatrix<double> A = WithFullDiagonal(RandomSymmetric(12, 2, 0.0, 3));
    // Unknown 0 decoupled with a zero diagonal: its pivot is zero whatever the order.
    for (int col = 0; col < A.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it)
            if (it.row() == 0 || it.col() == 0) it.valueRef() = 0;
    sim::BlockLdlt ldlt;
    ldlt.Analyse(A, Places(12, 3));
    EXPECT_FALSE(ldlt.Factorise(A, 0));
    EXPECT_TRUE(ldlt.Factorise(A, 1e-3));
}

// A shell problem's exact Hessian at a state away from rest (offsetMm along a sine over the unknowns),
// where it is indefinite, factorised; Eigen's scalar L D L^T beside it, with the same inertia.
struct FactorisedShellHessian {
    sim::ShellProblem problem;
    Eigen::SparseMatrix<double> matrix;
    sim::BlockLdlt ldlt;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> scalar;
};
void FactoriseAwayFromRest(const sim::ShellDef& def, double offsetMm, FactorisedShellHessian& f) {
    std::string error;
    f.problem = sim::BuildTubeProblem(def, sim::SineShape{1.3, 0.5, std::numbers::pi - 0.5}, true, &error);
    ASSERT_TRUE(error.empty()) << error;
    sim::HessianPattern pattern(f.problem);
    Eigen::VectorXd q = sim::UnknownsOf(f.problem, f.problem.rest);
    for (int i = 0; i < q.size(); ++i) q[i] += offsetMm * std::sin(1.7 * i);
    sim::LoadTerms load;
    load.pressure = 0.003;
    sim::AssembleEnergy(f.problem, q, load, sim::EnergyTerms{}, false, &pattern, sim::HessianKind::Exact);
    f.matrix = pattern.matrix;
    f.ldlt.Analyse(f.matrix, sim::VertexBlockPlaces(f.problem));
    ASSERT_TRUE(f.ldlt.Factorise(f.matrix, 0));
    f.scalar.compute(f.matrix);
    ASSERT_EQ(f.scalar.info(), Eigen::Success);
    const int scalarNegative = static_cast<int>((f.scalar.vectorD().array() < 0).count());
    EXPECT_GT(scalarNegative, 0);
    EXPECT_EQ(f.ldlt.NegativePivots(), scalarNegative);
}

TEST(BlockLdlt, MatchesEigensScalarFactorisationOnAShellHessian) {
    sim::ShellDef def = sim::DefaultShellDef();
    def.geometry.ringVertices = 12;
    def.geometry.rings = 10;
    def.geometry.clampMm = 150.0 / 9;  // one ring spacing: a uniform mesh, as well conditioned as the comparison needs
    def.geometry.edgeSpacingMm = 0;
    FactorisedShellHessian f;
    ASSERT_NO_FATAL_FAILURE(FactoriseAwayFromRest(def, 0.2, f));
    EXPECT_EQ(f.ldlt.NegativePivots(), NegativeEigenvalues(Eigen::MatrixXd(f.matrix)));
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(f.problem.unknowns, -1, 1);
    EXPECT_LT((f.ldlt.Solve(b) - f.scalar.solve(b)).norm(), 1e-9 * f.scalar.solve(b).norm());
}

// The supernodes' dense product: the vector path (where the machine has one) and the portable one
// give the same bits, and both the product, on shapes with every remainder of rows and columns.
TEST(DenseProduct, VectorAndPortablePathsGiveTheSameBitsAndTheProduct) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> value(-1, 1);
    for (int M : {1, 3, 4, 7, 12, 13, 26, 51})
        for (int N : {1, 3, 5, 6, 12})
            for (int K : {1, 3, 9, 24}) {
                const int lda = M + 2, ldb = N + 1, ldc = M + 3;
                std::vector<double> A(static_cast<size_t>(lda) * K), B(static_cast<size_t>(ldb) * K);
                for (double& a : A) a = value(rng);
                for (double& b : B) b = value(rng);
                std::vector<double> vector(static_cast<size_t>(ldc) * N, 99.0), portable = vector;
                sim::MultiplyTransposed(M, N, K, A.data(), lda, B.data(), ldb, vector.data(), ldc);
                sim::MultiplyTransposed(M, N, K, A.data(), lda, B.data(), ldb, portable.data(), ldc, true);
                EXPECT_EQ(0, std::memcmp(vector.data(), portable.data(), vector.size() * sizeof(double))) << M << " x " << N << " x " << K;
                for (int j = 0; j < N; ++j)
                    for (int i = 0; i < M; ++i) {
                        double expected = 0;
                        for (int k = 0; k < K; ++k) expected += A[static_cast<size_t>(k) * lda + i] * B[static_cast<size_t>(k) * ldb + j];
                        EXPECT_NEAR(vector[static_cast<size_t>(j) * ldc + i], expected, 1e-13 * K);
                    }
                for (int j = 0; j < N; ++j)  // rows past M untouched
                    for (int i = M; i < ldc; ++i) EXPECT_EQ(vector[static_cast<size_t>(j) * ldc + i], 99.0);
            }
}

// A default-sized wall with fibre cells (1,200 vertices, wide supernodes that take several groups of
// columns and many relaxed ones), at a state away from rest: the exact Hessian's inertia and a
// solution as Eigen's scalar L D L^T has them.
TEST(BlockLdlt, MatchesEigensScalarFactorisationOnADefaultFibreWall) {
    sim::ShellDef def = sim::DefaultShellDef();
    def.fibres.layout = sim::FibreLayout::Braid;
    FactorisedShellHessian f;
    ASSERT_NO_FATAL_FAILURE(FactoriseAwayFromRest(def, 0.3, f));
    ASSERT_FALSE(f.problem.fibreCells.empty());
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(f.problem.unknowns, -1, 1);
    const Eigen::VectorXd x = f.ldlt.Solve(b);
    EXPECT_LT((f.matrix * x - b).norm(), 1e-8 * b.norm());
    EXPECT_LT((x - f.scalar.solve(b)).norm(), 1e-7 * x.norm());
    // A direction of negative curvature where the pivots show one.
    const Eigen::VectorXd down = f.ldlt.NegativeCurvatureDirection();
    ASSERT_EQ(down.size(), f.problem.unknowns);
    EXPECT_LT(down.dot(f.matrix * down), 0);
}

}  // namespace
