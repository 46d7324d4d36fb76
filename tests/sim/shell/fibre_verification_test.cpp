// Fibre-reinforced walls against closed forms (docs/models/shell.md section 7, issue 11): the ideal McKibben
// muscle, the magic angle, the pleated (meridian) and hoop limits, and the fibre energy's derivatives
// on both sides of its tension-only switch. Label `verification`.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "sim/batch.h"
#include "reproduce.h"
#include "shell/shell_problem.h"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMagicAngleDeg = 54.7356103172;  // atan(sqrt(2))

double Cos(double degrees) { return std::cos(degrees * kPi / 180); }
double Sin(double degrees) { return std::sin(degrees * kPi / 180); }

// A long braided tube with an almost inextensible braid (k_f = 1e4 mu h) and a wall that is soft
// against the pressure (P = p R / (mu h) = 50): an ideal McKibben muscle between its end clamps.
sim::EvalJob McKibben(double angleDeg, double pressureKpa = 10, sim::ShellLoad load = sim::ShellLoad::Inflate) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Membrane);
    job.shape = sim::CylinderShape{};
    sim::GeometryDef& g = job.Shell().geometry;
    g.radiusMm = 5;
    g.lengthMm = 100;
    g.thicknessMm = 1;
    g.ringVertices = 24;
    g.rings = 0;  // near-equilateral
    job.Shell().material = sim::MaterialDef{};
    job.Shell().material.muKpa = 1;
    job.Shell().material.elongationAtBreak = 100;  // the check is of the braid, not of the rubber's limits
    job.Shell().load.kind = load;
    job.Shell().load.pressureKpa = pressureKpa;
    job.Shell().load.steps = 8;
    job.Shell().solver.selfContact = false;
    job.Shell().fibres.layout = sim::FibreLayout::Braid;
    job.Shell().fibres.angleDeg = angleDeg;
    job.Shell().fibres.stiffnessNPerMm = 1e4 * 1e-3 * g.thicknessMm;  // 1e4 mu h
    return job;
}

// Chou and Hannaford's blocked force at the initial length, N: p pi R0^2 (3 cos^2 a0 - 1) / sin^2 a0.
double ChouHannafordForceN(const sim::EvalJob& job) {
    const double angle = job.Shell().fibres.angleDeg, R0 = job.Shell().geometry.radiusMm;
    return job.Shell().load.pressureKpa * 1e-3 * kPi * R0 * R0 * (3 * Cos(angle) * Cos(angle) - 1) / (Sin(angle) * Sin(angle));
}


// The axial strain of the tube's middle third (rings H/3 to 2H/3), in percent, positive = shorter.
double MiddleContraction(const sim::EvalJob& job, const sim::SimResult& r) {
    const int R = job.Shell().geometry.ringVertices, H = sim::RingCount(job.Shell().geometry);
    auto ringZ = [&](const sim::Positions& x, int j) {
        double sum = 0;
        for (int i = 0; i < R; ++i) sum += x.z[j * R + i];
        return sum / R;
    };
    const int a = H / 3, b = 2 * H / 3;
    return 100 * (1 - (ringZ(r.final, b) - ringZ(r.final, a)) / (ringZ(r.initial, b) - ringZ(r.initial, a)));
}

}  // namespace

TEST(FibreClosedForms, AnIdealMcKibbenMuscleContractsToTheMagicAngle) {
    for (double angle : {20.0, 30.0}) {
        const sim::EvalJob job = McKibben(angle);
        const sim::SimResult r = sim::Evaluate(job);
        ASSERT_EQ(r.status, sim::Status::Ok) << testing_support::ReproduceCommand(job);
        const double ideal = 100 * (1 - Cos(kMagicAngleDeg) / Cos(angle));  // 38.6 % from 20 deg, 33.3 % from 30 deg
        EXPECT_NEAR(MiddleContraction(job, r), ideal, 2.0) << "free contraction of the middle section, percent; " << testing_support::ReproduceCommand(job);
        EXPECT_NEAR(r.shell.fibreAngleDeg, kMagicAngleDeg, 2.0) << "the braid ends near the magic angle; " << testing_support::ReproduceCommand(job);
        EXPECT_GT(r.contractionPercent, 0.8 * ideal) << "the whole tube, clamped ends included, contracts too";
    }
}

TEST(FibreClosedForms, TheBlockedForceIsChouAndHannafords) {
    const double angle = 30, pressureKpa = 10;
    const sim::EvalJob job = McKibben(angle, pressureKpa, sim::ShellLoad::Blocked);
    const sim::SimResult r = sim::Evaluate(job);
    ASSERT_EQ(r.status, sim::Status::Ok) << testing_support::ReproduceCommand(job);
    const double expected = ChouHannafordForceN(job);
    EXPECT_NEAR(r.shell.blockingForceN / expected, 1, 0.05) << "blocked force " << r.shell.blockingForceN << " N against " << expected << " N; "
                                                          << testing_support::ReproduceCommand(job);
}

// Every inflate evaluation reports a blocking force by pulling the clamp back from the free state,
// here from a muscle contracted by 31 %: it must be the state a blocked inflation reaches from rest
// (one equilibrium, two routes), and so Chou and Hannaford's force too.
TEST(FibreClosedForms, TheFreeMusclesBlockingForceIsTheBlockedInflations) {
    const double angle = 30, pressureKpa = 10;
    const sim::EvalJob freeJob = McKibben(angle, pressureKpa), blockedJob = McKibben(angle, pressureKpa, sim::ShellLoad::Blocked);
    const sim::SimResult free = sim::Evaluate(freeJob), blocked = sim::Evaluate(blockedJob);
    ASSERT_EQ(free.status, sim::Status::Ok) << testing_support::ReproduceCommand(freeJob);
    ASSERT_EQ(blocked.status, sim::Status::Ok) << testing_support::ReproduceCommand(blockedJob);
    EXPECT_GT(free.contractionPercent, 25) << "the free muscle contracts; " << testing_support::ReproduceCommand(freeJob);
    EXPECT_NEAR(free.shell.blockingForceN / blocked.shell.blockingForceN, 1, 1e-6)
        << "pulled back from the free state " << free.shell.blockingForceN << " N, blocked from rest " << blocked.shell.blockingForceN << " N; "
        << testing_support::ReproduceCommand(freeJob);
    EXPECT_NEAR(free.shell.blockingForceN / ChouHannafordForceN(freeJob), 1, 0.05) << testing_support::ReproduceCommand(freeJob);
}

TEST(FibreClosedForms, TheAxialStrainChangesSignAtTheMagicAngle) {
    for (double pressureKpa : {1.0, 3.0, 10.0}) {
        const sim::EvalJob below = McKibben(50, pressureKpa), above = McKibben(60, pressureKpa);
        const sim::SimResult a = sim::Evaluate(below), b = sim::Evaluate(above);
        ASSERT_EQ(a.status, sim::Status::Ok) << testing_support::ReproduceCommand(below);
        ASSERT_EQ(b.status, sim::Status::Ok) << testing_support::ReproduceCommand(above);
        EXPECT_GT(MiddleContraction(below, a), 0) << "50 deg contracts at " << pressureKpa << " kPa; " << testing_support::ReproduceCommand(below);
        EXPECT_LT(MiddleContraction(above, b), 0) << "60 deg extends at " << pressureKpa << " kPa; " << testing_support::ReproduceCommand(above);
    }
}

// On a real silicone tube: fibres along the meridian let it bulge and shorten (the pleated muscle);
// hoop fibres stop the bulge and it lengthens.
TEST(FibreClosedForms, MeridianFibresShortenAndHoopFibresLengthenWithoutBulging) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Membrane);
    job.shape = sim::CylinderShape{};
    job.Shell().geometry.lengthMm = 60;
    job.Shell().geometry.ringVertices = 24;
    job.Shell().load.pressureKpa = 1.2;  // P = p R / (mu h) = 0.38: below the plain tube's limit point (0.75)
    const sim::SimResult plain = sim::Evaluate(job);
    job.Shell().fibres.layout = sim::FibreLayout::Meridian;
    const sim::SimResult meridian = sim::Evaluate(job);
    job.Shell().fibres.layout = sim::FibreLayout::Hoop;
    const sim::SimResult hoop = sim::Evaluate(job);
    ASSERT_EQ(plain.status, sim::Status::Ok);
    ASSERT_EQ(meridian.status, sim::Status::Ok);
    ASSERT_EQ(hoop.status, sim::Status::Ok);
    EXPECT_LT(plain.contractionPercent, 0) << "the plain tube lengthens";
    EXPECT_GT(meridian.contractionPercent, 0) << "meridian fibres: it shortens as it bulges";
    EXPECT_LT(hoop.contractionPercent, 0) << "hoop fibres: it lengthens";
    auto middleRadius = [&](const sim::SimResult& r) {
        const int R = job.Shell().geometry.ringVertices, j = sim::RingCount(job.Shell().geometry) / 2;
        double sum = 0;
        for (int i = 0; i < R; ++i) sum += std::hypot(r.final.x[j * R + i], r.final.y[j * R + i]);
        return sum / R;
    };
    const double rest = job.Shell().geometry.radiusMm;
    EXPECT_GT(middleRadius(meridian), 1.1 * rest) << "meridian: bulges";
    EXPECT_LT(middleRadius(hoop), 1.01 * rest) << "hoop: does not bulge";
    EXPECT_LT(hoop.shell.maxFibreStrain, 0.01);
}

// Robust from no fibres to near-inextensible ones: every stiffness converges.
TEST(FibreSolver, ConvergesFromSlackToNearInextensibleFibres) {
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    job.shape = sim::SineShape{1.3, 0.5, kPi - 0.5};
    job.Shell().geometry.ringVertices = 16;
    job.Shell().geometry.rings = 24;
    job.Shell().load.pressureKpa = 1.2;
    job.Shell().fibres.layout = sim::FibreLayout::Braid;
    const double muH = sim::ShearModulusKpa(job.Shell().material) * 1e-3 * job.Shell().geometry.thicknessMm;
    for (double angle : {20.0, 54.7, 75.0})
        for (double ratio : {0.0, 1.0, 1e2, 1e4}) {
            job.Shell().fibres.angleDeg = angle;
            job.Shell().fibres.stiffnessNPerMm = ratio * muH;
            const sim::SimResult r = sim::Evaluate(job);
            EXPECT_EQ(r.status, sim::Status::Ok) << "braid at " << angle << " deg, k_f = " << ratio << " mu h";
        }
}

TEST(FibreDerivatives, TheFibreEnergyMatchesCentralDifferencesOnBothSidesOfTheSwitch) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int taut = 0, slack = 0;
    for (int trial = 0; trial < 200; ++trial) {
        sim::Matrix32 F;
        for (int k = 0; k < 6; ++k) F(k % 3, k / 3) = (k % 3 == k / 3 ? 1.0 : 0.0) + 0.3 * u(random);
        const double angle = kPi * u(random);
        const double a[2] = {std::cos(angle), std::sin(angle)};
        const double I4 = (F.col(0) * a[0] + F.col(1) * a[1]).squaredNorm();
        if (std::fabs(I4 - 1) < 1e-3) continue;  // the kink itself: no derivative to check
        (I4 > 1 ? taut : slack)++;
        sim::Vector6 g = sim::Vector6::Zero();
        sim::Matrix6 H = sim::Matrix6::Zero();
        const double k = 7.5;
        const double e = sim::FibreDensity(F, a, k, &g, &H);
        EXPECT_EQ(e == 0, I4 <= 1) << "tension only: zero energy exactly when slack";
        for (int c = 0; c < 6; ++c) {
            const double h = 1e-6;
            sim::Matrix32 plus = F, minus = F;
            plus(c % 3, c / 3) += h;
            minus(c % 3, c / 3) -= h;
            sim::Vector6 gp = sim::Vector6::Zero(), gm = sim::Vector6::Zero();
            const double numeric = (sim::FibreDensity(plus, a, k, &gp, nullptr) - sim::FibreDensity(minus, a, k, &gm, nullptr)) / (2 * h);
            EXPECT_NEAR(numeric, g[c], 1e-6 * std::max(1.0, std::fabs(g[c]))) << "trial " << trial;
            EXPECT_LT(((gp - gm) / (2 * h) - H.col(c)).lpNorm<Eigen::Infinity>(), 1e-5 * std::max(1.0, H.lpNorm<Eigen::Infinity>())) << "trial " << trial;
        }
        EXPECT_GE(Eigen::SelfAdjointEigenSolver<sim::Matrix6>(H).eigenvalues().minCoeff(), -1e-9) << "positive semi-definite";
    }
    EXPECT_GT(taut, 40);
    EXPECT_GT(slack, 40);
}

TEST(FibreDerivatives, AFibreReinforcedTubesEnergyMatchesCentralDifferences) {
    sim::ShellDef def;
    def.geometry.radiusMm = 4;
    def.geometry.lengthMm = 12;
    def.geometry.ringVertices = 8;
    def.geometry.rings = 7;
    def.geometry.clampMm = 2;  // one ring spacing: each clamp holds two rings
    def.fibres.layout = sim::FibreLayout::Braid;
    def.fibres.angleDeg = 35;
    def.fibres.stiffnessNPerMm = 0.5;
    std::string error;
    const sim::ShellProblem p = sim::BuildTubeProblem(def, sim::SineShape{1.3, 0.6, 2.4}, false, &error);
    ASSERT_TRUE(error.empty()) << error;
    ASSERT_EQ(p.fibreCells.size(), p.wall.size()) << "every triangle in a fibre cell per family: the cells' terms are what is checked";
    // Stretched 10 % so that most fibres are taut, then shaken.
    Eigen::VectorXd q = sim::UnknownsOf(p, p.rest) * 1.1;
    std::mt19937 random(3);
    std::uniform_real_distribution<double> u(-0.05, 0.05);
    for (int k = 0; k < q.size(); ++k) q[k] += u(random);
    const sim::EnergyTerms fibresOnly{false, false, false, false, false, true};
    sim::HessianPattern pattern(p);
    const sim::EnergyResult r = sim::AssembleEnergy(p, q, {}, fibresOnly, true, &pattern, sim::HessianKind::Exact);
    ASSERT_GT(r.energy, 0);
    const Eigen::MatrixXd H(pattern.matrix);
    const double h = 1e-6;
    for (int k = 0; k < q.size(); ++k) {
        Eigen::VectorXd plus = q, minus = q;
        plus[k] += h;
        minus[k] -= h;
        const auto ep = sim::AssembleEnergy(p, plus, {}, fibresOnly, true, nullptr, sim::HessianKind::Exact);
        const auto em = sim::AssembleEnergy(p, minus, {}, fibresOnly, true, nullptr, sim::HessianKind::Exact);
        EXPECT_NEAR((ep.energy - em.energy) / (2 * h), r.gradient[k], 1e-6 * std::max(1.0, r.gradient.lpNorm<Eigen::Infinity>()));
        EXPECT_LT(((ep.gradient - em.gradient) / (2 * h) - H.col(k)).lpNorm<Eigen::Infinity>(), 1e-5 * std::max(1.0, H.lpNorm<Eigen::Infinity>()));
    }
}

// Fibre cells (docs/models/shell.md section 7): a cell reads the same stretch as its triangles under
// a homogeneous strain, a curved rest surface included (|d| = 1 at rest, though the two facets' rest
// directions differ by 13 deg at 12 vertices a ring), and a band's border keeps the triangles on
// either side apart.
TEST(FibreCells, ACellReadsWhatItsTrianglesReadUnderAHomogeneousStrain) {
    sim::ShellDef def;
    def.geometry.ringVertices = 12;
    def.geometry.rings = 12;
    def.fibres.layout = sim::FibreLayout::Braid;
    def.fibres.angleDeg = 40;
    std::string error;
    const sim::ShellProblem p = sim::BuildTubeProblem(def, sim::CylinderShape{}, false, &error);
    ASSERT_TRUE(error.empty()) << error;
    ASSERT_EQ(p.fibreCells.size(), p.wall.size()) << "each triangle in one cell per family";
    // Swollen 20 % about the axis and stretched 10 % along it: every cell's fibre reads the tube's
    // stretch, as a triangle's own F a does, up to the facets' turn (each reads a facet, not the
    // cylinder: 0.23 % apart at 12 vertices a ring, the cell the nearer).
    sim::Positions x = p.rest;
    for (int v = 0; v < x.Size(); ++v) {
        x.x[v] *= 1.2;
        x.y[v] *= 1.2;
        x.z[v] *= 1.1;
    }
    const double tube = std::hypot(1.1 * Cos(40), 1.2 * Sin(40));
    for (const sim::FibreCell& cell : p.fibreCells) {
        const int t = cell.triangles[0], k = cell.family;
        EXPECT_NEAR(sim::FibreVector(p, t, k, p.rest).norm(), 1, 1e-12);
        const sim::Matrix32 F = sim::DeformationGradient(p, t, x);
        const double own = (F.col(0) * p.fibreDirections[t][2 * k] + F.col(1) * p.fibreDirections[t][2 * k + 1]).norm();
        EXPECT_NEAR(own, tube, 2e-3 * tube);
        EXPECT_NEAR(sim::FibreVector(p, t, k, x).norm(), tube, 2e-3 * tube);
        EXPECT_EQ(sim::FibreVector(p, t, k, x), sim::FibreVector(p, cell.triangles[1], k, x));
    }
    // The two families' cells are mirror images: +40 and -40 deg read the same stretch in every
    // triangle (read on one parallelogram for both, the braid turned its top).
    for (size_t t = 0; t < p.wall.size(); ++t)
        EXPECT_NEAR(sim::FibreVector(p, static_cast<int>(t), 0, x).norm(), sim::FibreVector(p, static_cast<int>(t), 1, x).norm(), 1e-12);
    // Bands at 20 and 60 degrees: no cell straddles the border.
    def.fibres.bands = {{0, 0.5, 20}, {0.5, 1, 60}};
    const sim::ShellProblem banded = sim::BuildTubeProblem(def, sim::CylinderShape{}, false, &error);
    ASSERT_TRUE(error.empty()) << error;
    int alone = 0;
    for (size_t t = 0; t < banded.wall.size(); ++t) alone += banded.fibreCellOf[t][0] < 0;
    EXPECT_LE(alone, 2 * def.geometry.ringVertices) << "one strip at the border at most";
    EXPECT_LT(alone, static_cast<int>(banded.wall.size()) / 4);
    auto upperBand = [&](int t) {
        double z = 0;
        for (int v : banded.wall[t]) z += banded.rest.z[v] / 3;
        return z > 0.5 * def.geometry.lengthMm;
    };
    for (const sim::FibreCell& cell : banded.fibreCells) EXPECT_EQ(upperBand(cell.triangles[0]), upperBand(cell.triangles[1]));
}
