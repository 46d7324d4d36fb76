// The L D L^T factorisation of a sparse symmetric matrix in 3 x 3 blocks, for the shell models'
// Newton solves (docs/models/shell.md sections 6 and 11). Their Hessians couple vertices, three coordinates
// each: working on a vertex's block at a time does 27 multiply-adds per index read where a scalar
// factorisation does one, and stores a ninth of the indices; columns that share their structure are
// factorised together as dense panels (supernodes; block_ldlt.cpp). No pivoting, as Eigen's
// SimplicialLDLT: D is block diagonal, each 3 x 3 block factorised L D L^T in turn, so the pivots
// are a scalar factorisation's (in this order) and their signs give the matrix's inertia.
//
// Analyse once per pattern (the ordering and the factor's structure), then Factorise and Solve as
// often as the values change. Factorise and Solve are pure functions of the values: the same bits
// on every thread and on every machine (the dense products' vector path and portable path agree).
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

    long FactorBlocks() const { return factorBlocks_; }  // 3 x 3 blocks of L below the diagonal

private:
    using Block = Eigen::Matrix3d;
    // A vector over the unknowns in blocks (new order) and back; y <- L^-T y.
    std::vector<double> ToBlocks(const Eigen::VectorXd& b) const;
    Eigen::VectorXd FromBlocks(const std::vector<double>& y) const;
    void SolveTransposedL(std::vector<double>& y) const;
    // Supernode s's dense panel: its rows (3 per block row) by its columns, column by column.
    double* Panel(int s) { return panel_.data() + panelStart_[s]; }
    const double* Panel(int s) const { return panel_.data() + panelStart_[s]; }
    int Rows(int s) const { return 3 * (rowStart_[s + 1] - rowStart_[s]); }
    int Width(int s) const { return superFirst_[s + 1] - superFirst_[s]; }
    bool analysed_ = false;
    int blocks_ = 0;
    long factorBlocks_ = 0;
    std::vector<int> placeOf_;      // per unknown: 3 * (block in the new order) + coordinate
    std::vector<char> used_;        // per new block and coordinate: an unknown's (1) or padding (0)
    // Supernodes: runs of consecutive block columns of L with one structure below their diagonal
    // blocks, stored as dense panels (docs/performance.md, the shell models' speed).
    std::vector<int> superFirst_;   // per supernode: its first block column; one past the last at the end
    std::vector<int> superOf_;      // per block column: its supernode
    std::vector<int> rowStart_, rows_;  // per supernode: its block rows, its own columns' first
    std::vector<long> panelStart_;  // per supernode: where its panel starts in panel_
    std::vector<long> belowStart_;  // per supernode: where its rows below its columns start in below_
    std::vector<long> slot_;        // per nonzero of H: its place in panel_ (-1: above the diagonal)
    std::vector<long> diagonalSlot_;  // per block and coordinate: its diagonal entry's place in panel_
    std::vector<double> panel_;     // L's columns (the diagonal blocks' places hold D's blocks)
    std::vector<double> below_;     // per supernode: its rows below its columns times D (L D), column by column
    std::vector<Block> dInverse_;   // per block: the inverse of D's 3 x 3 block
    std::vector<double> pivots_;    // per block and coordinate
    // Workspace of Factorise.
    std::vector<int> localRow_, head_, next_, position_;
    std::vector<double> update_, group_;
    static constexpr int kGroupColumns = 4;  // block columns factorised before one dense product updates the rest
    static constexpr int kBandBlocks = 4;    // block columns of an update computed together, from their diagonal down
    bool FactorisePanel(int s);
    // Links supernode d into the list of the supernode that holds its row `from` (one of its rows
    // below its columns): the next whose panel d updates, starting there.
    void PassOn(int d, int from);
};

}  // namespace sim
