// Block L D L^T, supernodal and left-looking (the scheme of CHOLMOD's supernodal factorisation, in
// 3 x 3 blocks for scalars): columns of L that share their structure below are stored as one dense
// panel, and what a panel receives from the panels below it is a dense product (dense_product.cpp)
// scattered into it, where a column at a time made the same sums 27 multiply-adds per block read.
// Nested dissection of a tube leaves most of the work in a few wide supernodes (a 30 x 30 wall with
// fibre cells: three quarters of it in supernodes 8 blocks wide or more).
//
// [SECTION] Analysis: the block graph, its ordering, the elimination tree, supernodes, where each value goes
// [SECTION] Factorisation
// [SECTION] Solve and inertia
#include "shell/block_ldlt.h"

#include "shell/dense_product.h"

#include <Eigen/Eigenvalues>
#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <metis.h>
#include <mutex>

namespace sim {

// ---------------------------------------------------------------------------------------------
// [SECTION] Analysis
// ---------------------------------------------------------------------------------------------

namespace {

// Each block's place in a fill-reducing order of the block graph (symmetric, diagonal included):
// METIS's nested dissection, which on a tube's mesh leaves 8 % fewer blocks in L than approximate
// minimum degree at 30 x 30 and 19 % fewer at 60 x 60 (40 % less factorisation time there); AMD
// (Eigen's) if METIS fails.
std::vector<int> FillReducingPositions(const Eigen::SparseMatrix<double>& graph) {
    const int blocks = static_cast<int>(graph.rows());
    std::vector<int> position(blocks);
    std::vector<idx_t> adjacencyStart(1, 0), adjacency;
    for (int col = 0; col < blocks; ++col) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(graph, col); it; ++it)
            if (it.row() != col) adjacency.push_back(static_cast<idx_t>(it.row()));
        adjacencyStart.push_back(static_cast<idx_t>(adjacency.size()));
    }
    idx_t vertices = blocks;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    std::vector<idx_t> order(blocks), inverse(blocks);  // new -> old, old -> new
    // METIS keeps its random state in globals, reseeded per call: one call at a time, or threads'
    // orders (and so the last bits of their results) would depend on each other's timing.
    static std::mutex metisMutex;
    std::unique_lock<std::mutex> lock(metisMutex);
    const bool ordered = blocks > 1 && METIS_NodeND(&vertices, adjacencyStart.data(), adjacency.data(), nullptr, options, order.data(), inverse.data()) == METIS_OK;
    lock.unlock();
    if (ordered) {
        for (int b = 0; b < blocks; ++b) position[b] = static_cast<int>(inverse[b]);
        return position;
    }
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;  // new -> old
    Eigen::AMDOrdering<int>()(graph, amd);
    for (int k = 0; k < blocks; ++k) position[amd.indices()[k]] = k;
    return position;
}

}  // namespace

void BlockLdlt::Analyse(const Eigen::SparseMatrix<double>& pattern, const std::vector<int>& placeOf) {
    assert(pattern.isCompressed() && pattern.rows() == pattern.cols() && static_cast<Eigen::Index>(placeOf.size()) == pattern.rows());
    const int unknowns = static_cast<int>(pattern.rows());
    blocks_ = 0;
    for (int place : placeOf) blocks_ = std::max(blocks_, place / 3 + 1);

    // The block graph and its fill-reducing order.
    std::vector<Eigen::Triplet<double>> links;
    for (int col = 0; col < unknowns; ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(pattern, col); it; ++it)
            links.emplace_back(placeOf[it.row()] / 3, placeOf[col] / 3, 1.0);
    for (int b = 0; b < blocks_; ++b) links.emplace_back(b, b, 1.0);
    Eigen::SparseMatrix<double> graph(blocks_, blocks_);
    graph.setFromTriplets(links.begin(), links.end());
    const std::vector<int> position = FillReducingPositions(graph);  // old -> new

    placeOf_.resize(unknowns);
    used_.assign(3 * blocks_, 0);
    for (int d = 0; d < unknowns; ++d) {
        placeOf_[d] = 3 * position[placeOf[d] / 3] + placeOf[d] % 3;
        used_[placeOf_[d]] = 1;
    }

    // Each column's blocks above the diagonal (new order), sorted.
    std::vector<std::vector<int>> above(blocks_);
    for (int col = 0; col < blocks_; ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(graph, col); it; ++it) {
            const int i = position[it.row()], k = position[col];
            if (i < k) above[k].push_back(i);
        }

    // The elimination tree and each column's rows below its diagonal (LDL's symbolic pass: row k
    // of L holds the columns met climbing the tree from each block above the diagonal in column k).
    std::vector<int> parent(blocks_, -1), flag(blocks_, -1);
    std::vector<std::vector<int>> structure(blocks_);
    for (int k = 0; k < blocks_; ++k) {
        std::sort(above[k].begin(), above[k].end());
        flag[k] = k;
        for (int start : above[k])
            for (int i = start; flag[i] != k; i = parent[i]) {
                if (parent[i] == -1) parent[i] = k;
                structure[i].push_back(k);
                flag[i] = k;
            }
    }

    // Supernodes: column j + 1 joins j's when it is j's parent, so that the supernode's columns all
    // fit in the rows of its first: itself, the columns after it and its last column's rows below.
    // Where it adds rows to the columns before it, they hold explicit zeros; a small supernode
    // takes many (a dense product on a few more entries beats a separate update per column), a
    // wide one few.
    superFirst_.assign(1, 0);
    factorBlocks_ = 0;
    long zeros = 0, entries = 0;  // the current supernode's explicit zeros and blocks below its diagonal
    for (int j = 0; j < blocks_; ++j) {
        factorBlocks_ += static_cast<long>(structure[j].size());
        const int width = j - superFirst_.back();  // columns before j in the current supernode
        bool joins = j > 0 && parent[j - 1] == j;
        if (joins) {
            const long added = static_cast<long>(width) * std::max<long>(0, static_cast<long>(structure[j].size()) + 1 - static_cast<long>(structure[j - 1].size()));
            const long newZeros = zeros + added, newEntries = entries + added + static_cast<long>(structure[j].size());
            const double allowed = width + 1 <= 4 ? 0.8 : width + 1 <= 16 ? 0.1 : 0.05;
            joins = added == 0 || newZeros <= allowed * newEntries;
            if (joins) {
                zeros = newZeros;
                entries = newEntries;
            }
        }
        if (!joins) {
            if (j > 0) superFirst_.push_back(j);
            zeros = 0;
            entries = static_cast<long>(structure[j].size());
        }
    }
    superFirst_.push_back(blocks_);
    const int supernodes = static_cast<int>(superFirst_.size()) - 1;
    superOf_.assign(blocks_, 0);
    rowStart_.assign(1, 0);
    rows_.clear();
    panelStart_.assign(1, 0);
    belowStart_.assign(1, 0);
    long largestUpdate = 0, longestPanel = 0;
    for (int s = 0; s < supernodes; ++s) {
        const int first = superFirst_[s], width = superFirst_[s + 1] - first;
        for (int k = first; k < first + width; ++k) superOf_[k] = s;
        for (int k = first; k < first + width; ++k) rows_.push_back(k);
        const int last = first + width - 1;
        rows_.insert(rows_.end(), structure[last].begin(), structure[last].end());
        rowStart_.push_back(static_cast<int>(rows_.size()));
        const long length = rowStart_[s + 1] - rowStart_[s];
        panelStart_.push_back(panelStart_[s] + 9 * length * width);
        belowStart_.push_back(belowStart_[s] + 9 * (length - width) * width);
        largestUpdate = std::max(largestUpdate, 9 * length * std::max<long>(width, length - width));
        longestPanel = std::max(longestPanel, 3 * length);
    }

    // Where each value of H goes: its block's place in its supernode's panel (lower blocks only).
    const auto localRow = [&](int s, int block) {
        const int* begin = rows_.data() + rowStart_[s];
        const int* end = rows_.data() + rowStart_[s + 1];
        return static_cast<int>(std::lower_bound(begin, end, block) - begin);
    };
    const auto place = [&](int rowPlace, int colPlace) {
        const int i = rowPlace / 3, k = colPlace / 3, s = superOf_[k];
        const long rows = 3L * (rowStart_[s + 1] - rowStart_[s]);
        return panelStart_[s] + (3L * (k - superFirst_[s]) + colPlace % 3) * rows + 3L * localRow(s, i) + rowPlace % 3;
    };
    slot_.assign(pattern.nonZeros(), -1);
    const int* outer = pattern.outerIndexPtr();
    const int* inner = pattern.innerIndexPtr();
    for (int col = 0; col < unknowns; ++col)
        for (int e = outer[col]; e < outer[col + 1]; ++e)
            if (placeOf_[inner[e]] / 3 >= placeOf_[col] / 3) slot_[e] = place(placeOf_[inner[e]], placeOf_[col]);
    diagonalSlot_.resize(3 * blocks_);
    for (int d = 0; d < 3 * blocks_; ++d) diagonalSlot_[d] = place(d, d);

    panel_.assign(panelStart_[supernodes], 0.0);
    below_.assign(belowStart_[supernodes], 0.0);
    dInverse_.assign(blocks_, Block::Identity());
    pivots_.assign(3 * blocks_, 1.0);
    localRow_.assign(blocks_, 0);
    head_.assign(supernodes, -1);
    next_.assign(supernodes, -1);
    position_.assign(supernodes, 0);
    update_.assign(largestUpdate, 0.0);
    group_.assign(longestPanel * 3 * kGroupColumns, 0.0);
    analysed_ = true;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Factorisation
// ---------------------------------------------------------------------------------------------

namespace {

// D's 3 x 3 block: its scalar L D L^T without pivoting (the pivots), and its inverse. False when a
// pivot is zero or not finite.
bool FactoriseDiagonal(const Eigen::Matrix3d& D, double pivots[3], Eigen::Matrix3d& inverse) {
    const double d0 = D(0, 0);
    const double l10 = D(1, 0) / d0, l20 = D(2, 0) / d0;
    const double d1 = D(1, 1) - l10 * D(1, 0);
    const double l21 = (D(2, 1) - l20 * D(1, 0)) / d1;
    const double d2 = D(2, 2) - l20 * D(2, 0) - l21 * l21 * d1;
    pivots[0] = d0;
    pivots[1] = d1;
    pivots[2] = d2;
    for (int c = 0; c < 3; ++c)
        if (!(pivots[c] != 0) || !std::isfinite(pivots[c])) return false;
    // D^-1 = L^-T diag(1/d) L^-1, with L^-1 unit lower triangular.
    Eigen::Matrix3d lInverse;
    lInverse << 1, 0, 0, -l10, 1, 0, l10 * l21 - l20, -l21, 1;
    inverse = lInverse.transpose() * Eigen::Vector3d(1 / d0, 1 / d1, 1 / d2).asDiagonal() * lInverse;
    return true;
}

}  // namespace

bool BlockLdlt::Factorise(const Eigen::SparseMatrix<double>& H, double shift) {
    assert(analysed_ && static_cast<size_t>(H.nonZeros()) == slot_.size());
    // H's lower blocks into the panels; padding's diagonal 1.
    std::fill(panel_.begin(), panel_.end(), 0.0);
    const double* values = H.valuePtr();
    for (size_t e = 0; e < slot_.size(); ++e)
        if (slot_[e] >= 0) panel_[slot_[e]] = values[e];
    for (int d = 0; d < 3 * blocks_; ++d) {
        double& diagonal = panel_[diagonalSlot_[d]];
        diagonal = used_[d] ? diagonal + shift : 1.0;
    }

    // Left-looking, a supernode at a time: each supernode's panel receives the updates of the
    // supernodes below it whose rows reach its columns (linked in head_ by the first row they have
    // not yet passed on), then is factorised densely.
    const int supernodes = static_cast<int>(superFirst_.size()) - 1;
    std::fill(head_.begin(), head_.end(), -1);
    for (int s = 0; s < supernodes; ++s) {
        const int first = superFirst_[s], width = Width(s), rowCount = Rows(s) / 3, stride = Rows(s);
        const int* rows = rows_.data() + rowStart_[s];
        double* P = Panel(s);
        for (int t = 0; t < rowCount; ++t) localRow_[rows[t]] = t;
        for (int d = head_[s], nextD; d != -1; d = nextD) {
            nextD = next_[d];
            const int* rowsD = rows_.data() + rowStart_[d];
            const int countD = Rows(d) / 3, widthD = Width(d);
            const int from = position_[d];
            int to = from;
            while (to < countD && rowsD[to] < superFirst_[s + 1]) ++to;
            const int m = countD - from, n = to - from;
            // L_d (its rows from `from` on) times (L D)_d^T (its rows in s's columns).
            // Only the lower blocks are wanted: in bands of kBandBlocks columns, each from its diagonal down.
            for (int jb = 0; jb < n; jb += kBandBlocks) {
                const int columns = std::min(kBandBlocks, n - jb);
                MultiplyTransposed(3 * (m - jb), 3 * columns, 3 * widthD, Panel(d) + 3 * (from + jb), Rows(d),
                                   below_.data() + belowStart_[d] + 3 * (from + jb - widthD), 3 * (countD - widthD), update_.data() + 9L * jb * m + 3 * jb, 3 * m);
            }
            for (int jb = 0; jb < n; ++jb) {
                double* column = P + 3L * (rowsD[from + jb] - first) * stride;
                for (int ib = jb; ib < m; ++ib) {
                    double* target = column + 3 * localRow_[rowsD[from + ib]];
                    const double* source = update_.data() + 9L * jb * m + 3 * ib;
                    for (int c = 0; c < 3; ++c)
                        for (int r = 0; r < 3; ++r) target[c * stride + r] -= source[c * 3 * m + r];
                }
            }
            if (to < countD) PassOn(d, to);
        }
        if (!FactorisePanel(s)) return false;
        if (rowCount > width) PassOn(s, width);
    }
    return true;
}

void BlockLdlt::PassOn(int d, int from) {
    position_[d] = from;
    const int ancestor = superOf_[rows_[rowStart_[d] + from]];
    next_[d] = head_[ancestor];
    head_[ancestor] = d;
}

// A supernode's panel, all updates from below received, factorised a group of columns at a time:
// each column of the group takes the updates of the group's columns before it, then gives D's block
// and L's column below it (L = A D^-1; the unscaled A = L D kept for the group in group_ and, for the
// rows below the supernode, in below_); then one dense product updates the columns after the group.
bool BlockLdlt::FactorisePanel(int s) {
    const int first = superFirst_[s], width = Width(s), rowCount = Rows(s) / 3, stride = Rows(s);
    double* P = Panel(s);
    double* W = below_.data() + belowStart_[s];
    const int strideW = 3 * (rowCount - width);
    double* U = group_.data();  // the group's columns, whole panel columns
    // C -= the product in update_ (M x N, leading dimension M).
    const auto subtract = [&](double* C, int M, int N) {
        for (int j = 0; j < N; ++j) {
            const double* source = update_.data() + static_cast<long>(j) * M;
            double* target = C + static_cast<long>(j) * stride;
            for (int i = 0; i < M; ++i) target[i] -= source[i];
        }
    };
    for (int c0 = 0; c0 < width; c0 += kGroupColumns) {
        const int c1 = std::min(width, c0 + kGroupColumns);
        for (int c = c0; c < c1; ++c) {
            double* column = P + 3L * c * stride;
            if (c > c0) {
                const int M = stride - 3 * c;
                MultiplyTransposed(M, 3, 3 * (c - c0), P + 3L * c0 * stride + 3 * c, stride, U + 3 * c, stride, update_.data(), M);
                subtract(column + 3 * c, M, 3);
            }
            Eigen::Matrix3d D;
            for (int q = 0; q < 3; ++q)
                for (int r = 0; r < 3; ++r) D(r, q) = column[q * stride + 3 * c + r];
            if (!FactoriseDiagonal(D, &pivots_[3 * (first + c)], dInverse_[first + c])) return false;
            const int M = stride - 3 * (c + 1);
            if (M == 0) continue;
            double* u = U + 3L * (c - c0) * stride;
            for (int q = 0; q < 3; ++q) std::copy_n(column + q * stride + 3 * (c + 1), M, u + q * stride + 3 * (c + 1));
            double inverseTransposed[9];
            for (int q = 0; q < 3; ++q)
                for (int r = 0; r < 3; ++r) inverseTransposed[3 * q + r] = dInverse_[first + c](q, r);
            MultiplyTransposed(M, 3, 3, u + 3 * (c + 1), stride, inverseTransposed, 3, column + 3 * (c + 1), stride);
            if (rowCount > width)
                for (int q = 0; q < 3; ++q) std::copy_n(u + q * stride + 3 * width, strideW, W + (3L * c + q) * strideW);
        }
        if (c1 == width) break;
        // Columns c1 .. width - 1, rows from their first diagonal block on: less L(group) (L D)(group)^T.
        const int M = stride - 3 * c1, N = 3 * (width - c1), K = 3 * (c1 - c0);
        MultiplyTransposed(M, N, K, P + 3L * c0 * stride + 3 * c1, stride, U + 3 * c1, stride, update_.data(), M);
        subtract(P + 3L * c1 * stride + 3 * c1, M, N);
    }
    return true;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Solve and inertia
// ---------------------------------------------------------------------------------------------

std::vector<double> BlockLdlt::ToBlocks(const Eigen::VectorXd& b) const {
    std::vector<double> y(3 * blocks_, 0.0);  // padding stays 0
    for (size_t d = 0; d < placeOf_.size(); ++d) y[placeOf_[d]] = b[d];
    return y;
}

Eigen::VectorXd BlockLdlt::FromBlocks(const std::vector<double>& y) const {
    Eigen::VectorXd x(placeOf_.size());
    for (size_t d = 0; d < placeOf_.size(); ++d) x[d] = y[placeOf_[d]];
    return x;
}

void BlockLdlt::SolveTransposedL(std::vector<double>& y) const {
    for (int s = static_cast<int>(superFirst_.size()) - 2; s >= 0; --s) {
        const int first = superFirst_[s], rowCount = Rows(s) / 3, stride = Rows(s);
        const int* rows = rows_.data() + rowStart_[s];
        const double* P = Panel(s);
        for (int c = Width(s) - 1; c >= 0; --c) {
            double sum[3] = {0, 0, 0};
            for (int t = c + 1; t < rowCount; ++t) {
                const double* block = P + 3L * c * stride + 3 * t;
                const double* x = &y[3 * rows[t]];
                for (int col = 0; col < 3; ++col) sum[col] += block[col * stride] * x[0] + block[col * stride + 1] * x[1] + block[col * stride + 2] * x[2];
            }
            for (int col = 0; col < 3; ++col) y[3 * (first + c) + col] -= sum[col];
        }
    }
}

Eigen::VectorXd BlockLdlt::Solve(const Eigen::VectorXd& b) const {
    std::vector<double> y = ToBlocks(b);
    for (size_t s = 0; s + 1 < superFirst_.size(); ++s) {
        const int first = superFirst_[s], rowCount = Rows(static_cast<int>(s)) / 3, stride = Rows(static_cast<int>(s));
        const int* rows = rows_.data() + rowStart_[s];
        const double* P = Panel(static_cast<int>(s));
        for (int c = 0; c < Width(static_cast<int>(s)); ++c) {
            const double x[3] = {y[3 * (first + c)], y[3 * (first + c) + 1], y[3 * (first + c) + 2]};
            for (int t = c + 1; t < rowCount; ++t) {
                const double* block = P + 3L * c * stride + 3 * t;
                double* target = &y[3 * rows[t]];
                for (int r = 0; r < 3; ++r) target[r] -= block[r] * x[0] + block[stride + r] * x[1] + block[2 * stride + r] * x[2];
            }
        }
    }
    for (int j = 0; j < blocks_; ++j) {
        const Eigen::Vector3d x = dInverse_[j] * Eigen::Vector3d(y[3 * j], y[3 * j + 1], y[3 * j + 2]);
        for (int r = 0; r < 3; ++r) y[3 * j + r] = x[r];
    }
    SolveTransposedL(y);
    return FromBlocks(y);
}

Eigen::VectorXd BlockLdlt::NegativeCurvatureDirection() const {
    int worst = -1;
    for (size_t k = 0; k < pivots_.size(); ++k)
        if (used_[k] && pivots_[k] < 0 && (worst < 0 || pivots_[k] < pivots_[worst])) worst = static_cast<int>(k);
    if (worst < 0) return Eigen::VectorXd();
    // D's block has the negative eigenvalue its pivot shows (Sylvester), and its inverse the same
    // eigenvectors: z with z^T D z < 0. Then y = L^-T z has y^T L D L^T y = z^T D z < 0.
    const int block = worst / 3;
    Eigen::SelfAdjointEigenSolver<Block> eigen(dInverse_[block]);
    std::vector<double> y(3 * blocks_, 0.0);
    for (int r = 0; r < 3; ++r) y[3 * block + r] = eigen.eigenvectors()(r, 0);  // eigenvalues ascending: the first is negative
    SolveTransposedL(y);
    return FromBlocks(y);
}

int BlockLdlt::NegativePivots() const {
    int count = 0;
    for (size_t k = 0; k < pivots_.size(); ++k) count += used_[k] && pivots_[k] < 0;
    return count;
}

double BlockLdlt::SmallestPivot() const {
    double smallest = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < pivots_.size(); ++k)
        if (used_[k]) smallest = std::min(smallest, pivots_[k]);
    return smallest;
}

}  // namespace sim
