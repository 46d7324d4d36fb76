// The L D L^T factorisation of a sparse symmetric matrix in 3 x 3 blocks, for the shell models'
// Newton solves (docs/models/shell.md sections 6 and 11). Their Hessians couple vertices, three coordinates
// each: working on a vertex's block at a time does 27 multiply-adds per index read where a scalar
// factorisation does one, and stores a ninth of the indices. No pivoting, as Eigen's
// SimplicialLDLT: D is block diagonal, each 3 x 3 block factorised L D L^T in turn, so the pivots
// are a scalar factorisation's (in this order) and their signs give the matrix's inertia.
//
// Analyse once per pattern (the ordering and the factor's structure), then Factorise and Solve as
// often as the values change. Factorise and Solve are pure functions of the values: the same bits
// on every thread.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace sim {

class BlockLdlt {
public:
    // The pattern of the matrices to come (full symmetric, compressed, with its diagonal; values
    // ignored) and each unknown's place, 3 * block + coordinate. A block may use fewer than three
    // places (a partly held vertex; the clamp's axial unknown): the others are padded with an
    // identity that couples to nothing. Orders the blocks by nested dissection (METIS).
    void Analyse(const Eigen::SparseMatrix<double>& pattern, const std::vector<int>& placeOf);
    bool Analysed() const { return analysed_; }

    // Factorises H + shift I (H with the analysed pattern). False when a pivot is zero or not finite.
    bool Factorise(const Eigen::SparseMatrix<double>& H, double shift);

    // x = (H + shift I)^-1 b, after a successful Factorise.
    Eigen::VectorXd Solve(const Eigen::VectorXd& b) const;

    // The pivots' signs (padding excluded): by Sylvester's law of inertia, the numbers of negative
    // eigenvalues; the smallest pivot (positive for a positive definite matrix).
    int NegativePivots() const;
    double SmallestPivot() const;
    // A direction of negative curvature, y^T (H + shift I) y < 0, when a pivot is negative (else
    // empty): L^-T applied to the most negative block's eigenvector of D.
    Eigen::VectorXd NegativeCurvatureDirection() const;

    long FactorBlocks() const { return static_cast<long>(rowOfL_.size()); }  // 3 x 3 blocks of L below the diagonal

private:
    using Block = Eigen::Matrix3d;
    // A vector over the unknowns in blocks (new order) and back; y <- L^-T y.
    std::vector<Eigen::Vector3d> ToBlocks(const Eigen::VectorXd& b) const;
    Eigen::VectorXd FromBlocks(const std::vector<Eigen::Vector3d>& y) const;
    void SolveTransposedL(std::vector<Eigen::Vector3d>& y) const;
    bool analysed_ = false;
    int blocks_ = 0;
    std::vector<int> placeOf_;      // per unknown: 3 * (block in the new order) + coordinate
    std::vector<char> used_;        // per new block and coordinate: an unknown's (1) or padding (0)
    std::vector<int> parent_;       // elimination tree over the new blocks (-1: a root)
    // The matrix's blocks above the diagonal, column by column (new order): rows and, per
    // nonzero of H, where its value goes (9 per block, then the diagonal blocks; -1: below).
    std::vector<int> upperStart_, upperRow_, valueSlot_;
    // L's blocks below the diagonal, column by column: start, rows, values.
    std::vector<int> columnStart_, rowOfL_;
    std::vector<Block> valuesOfL_;
    std::vector<Block> dInverse_;   // per block: the inverse of D's 3 x 3 block
    std::vector<double> pivots_;    // per block and coordinate
    // Workspace of Factorise.
    std::vector<double> gathered_;
    std::vector<Block> row_;
    std::vector<int> filled_, flag_, stack_, path_;
};

}  // namespace sim
