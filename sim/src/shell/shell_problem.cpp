// Shell problems: the tube of a design (staggered rings, caps, clamps), the verification sphere and
// patch, their hinges and unknowns.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "sim/search.h"
#include "shell/shell_problem.h"

namespace sim {
namespace {

Eigen::Vector3d At(const Positions& p, int v) { return {p.x[v], p.y[v], p.z[v]}; }

// Whether every coordinate of vertex v is held by a clamp (fixed, or riding on the top clamp).
bool OnRigidClamp(const ShellProblem& p, int v) {
    if (p.dofOf.empty()) return false;
    for (int c = 0; c < 3; ++c)
        if (p.dofOf[3 * v + c] >= 0) return false;
    return true;
}

// Rest data of every wall triangle, the rest volume and the mean edge.
void FinishRest(ShellProblem& p) {
    p.membrane.clear();
    double edges = 0;
    for (const auto& t : p.wall) {
        p.membrane.push_back(MakeMembraneRest(At(p.rest, t[0]), At(p.rest, t[1]), At(p.rest, t[2])));
        for (int k = 0; k < 3; ++k) edges += (At(p.rest, t[k]) - At(p.rest, t[(k + 1) % 3])).norm();
    }
    p.meanEdgeMm = p.wall.empty() ? 1 : edges / (3.0 * p.wall.size());
    p.restVolume = EnclosedVolume(p, p.rest);
    if (p.bending) SetHingeRest(p);
    p.held = p.rest;
}

// Numbers the unknowns: every coordinate not fixed, axial or twisted, then u and theta last (when
// they are unknowns).
void NumberUnknowns(ShellProblem& p, bool axialUnknown, bool twistUnknown = false) {
    int next = 0;
    for (int& d : p.dofOf)
        if (d >= 0 || d == -3) d = next++;
    for (int k = 0; k < 2; ++k) p.lateral[k] = p.rigidTop ? next++ : -1;
    p.axial = axialUnknown ? next++ : -1;
    for (int k = 0; k < 2; ++k) p.tilt[k] = p.rigidTop ? next++ : -1;
    p.twist = twistUnknown ? next++ : -1;
    p.unknowns = next;
}
constexpr int kFree = -3;  // marks a free coordinate before numbering

}  // namespace

void TubeTriangles(int R, int H, std::vector<std::array<int, 3>>& wall, std::vector<std::array<int, 3>>& caps) {
    // Per strip: (j,i) (j,i+1) (j+1,i) and (j,i+1) (j+1,i+1) (j+1,i), outward (docs/models/shell.md section 2).
    for (int j = 0; j + 1 < H; ++j)
        for (int i = 0; i < R; ++i) {
            const int a = j * R + i, b = j * R + (i + 1) % R, c = (j + 1) * R + i, d = (j + 1) * R + (i + 1) % R;
            wall.push_back({a, b, c});
            wall.push_back({b, d, c});
        }
    // Fans to one vertex per end on the axis (bottom cap R*H, top cap R*H + 1), facing out.
    const int bottomCap = R * H, topCap = R * H + 1;
    for (int i = 0; i < R; ++i) {
        caps.push_back({bottomCap, (i + 1) % R, i});
        caps.push_back({topCap, (H - 1) * R + i, (H - 1) * R + (i + 1) % R});
    }
}

MembraneMaterial MembraneMaterialOf(const ShellDef& def) {
    MembraneMaterial m;
    m.law = def.material.law;
    m.thicknessMm = def.geometry.thicknessMm;
    m.mu = def.material.muKpa * 1e-3;
    m.c10 = def.material.c10Kpa * 1e-3;
    m.c01 = def.material.c01Kpa * 1e-3;
    m.c20 = def.material.c20Kpa * 1e-3;
    m.c30 = def.material.c30Kpa * 1e-3;
    return m;
}

std::vector<std::array<int, 4>> HingesOf(const std::vector<std::array<int, 3>>& triangles) {
    // Each directed edge (a, b) of a triangle with its opposite vertex; a hinge pairs (a, b) with (b, a).
    std::map<std::pair<int, int>, int> opposite;
    for (const auto& t : triangles)
        for (int k = 0; k < 3; ++k) opposite[{t[k], t[(k + 1) % 3]}] = t[(k + 2) % 3];
    std::vector<std::array<int, 4>> hinges;
    for (const auto& [edge, q] : opposite) {
        const auto [a, b] = edge;
        if (a > b) continue;
        const auto other = opposite.find({b, a});
        if (other != opposite.end()) hinges.push_back({a, b, q, other->second});
    }
    return hinges;
}

void SetHingeRest(ShellProblem& p) {
    // D = E h^3 / (12 (1 - nu^2)) with E = 3 mu, nu = 1/2: mu h^3 / 3.
    const double D = MembraneMaterialShearModulus(p.material) * std::pow(p.material.thicknessMm, 3) / 3;
    p.hingeRestAngle.clear();
    p.hingeStiffness.clear();
    for (const auto& h : p.hinges) {
        Eigen::Matrix<double, 12, 1> x;
        for (int k = 0; k < 4; ++k) x.segment<3>(3 * k) = At(p.rest, h[k]);
        p.hingeRestAngle.push_back(HingeAngle(x, nullptr, nullptr));
        const Eigen::Vector3d e = At(p.rest, h[1]) - At(p.rest, h[0]);
        const double a1 = 0.5 * e.cross(At(p.rest, h[2]) - At(p.rest, h[0])).norm();
        const double a2 = 0.5 * e.cross(At(p.rest, h[3]) - At(p.rest, h[0])).norm();
        // k_e = (D/2) |e|^2 / (A1 + A2): Sum theta^2 |e|^2 / (A1 + A2) tends to A / r^2 on a strip bent
        // onto a cylinder, in either direction (tests/sim/shell/shell_verification_test.cpp,
        // BendingCalibration); the shared spec's extra 3 would store 2.95 times that.
        // On a clamp's edge (one triangle on the clamp, one free) the wall leaves the clamp along the
        // clamp's tangent, so the curvature over the hinge's half on the clamp is the mirror image of
        // the free half's (the ghost point of a clamped boundary): the angle is weighed over the free
        // triangle alone. Over both, the edge's bending moment is halved in a strip one ring wide and
        // the tube converges at first order instead of second (docs/models/shell.md section 4).
        const bool onClampA = OnRigidClamp(p, h[0]) && OnRigidClamp(p, h[1]) && OnRigidClamp(p, h[2]);
        const bool onClampB = OnRigidClamp(p, h[0]) && OnRigidClamp(p, h[1]) && OnRigidClamp(p, h[3]);
        const double weighedArea = onClampA == onClampB ? a1 + a2 : onClampA ? a2 : a1;
        p.hingeStiffness.push_back(0.5 * D * e.squaredNorm() / weighedArea);
    }
}

double MembraneMaterialShearModulus(const MembraneMaterial& m) {
    switch (m.law) {
        case MaterialLaw::NeoHookean: return m.mu;
        case MaterialLaw::MooneyRivlin: return 2 * (m.c10 + m.c01);
        case MaterialLaw::Yeoh: return 2 * m.c10;
    }
    return m.mu;
}

namespace {
// The fewest rings a clamped tube can have: a clamp interval at each end and three free ones.
constexpr int kMinimumRings = 6;
// Rings for near-equilateral triangles (ring spacing sqrt(3)/2 of the edge along the ring), as a real
// number: it may be far beyond what an int holds for a long thin tube.
double EquilateralRings(const GeometryDef& g) {
    const double edge = 2 * std::numbers::pi * g.radiusMm / g.ringVertices;
    return std::max<double>(kMinimumRings, std::round(g.lengthMm / (0.5 * std::sqrt(3.0) * edge)) + 1);
}

// Where the rings go, counted without placing them (a long thin tube may have more than memory holds).
struct RingPlan {
    double count = 0;          // rings in all, a real number until checked (Rings caps it)
    int clampIntervals = 1;    // in each clamp
    int sideIntervals = 0;     // graded: intervals growing from each clamp's edge toward the middle
    double sideMm = 0;         // graded: their length (equal intervals fill the middle between them)
};

RingPlan PlanOf(const GeometryDef& g) {
    RingPlan plan;
    const double evenRings = g.rings > 0 ? g.rings : EquilateralRings(g);
    plan.count = evenRings;
    if (evenRings < 2 || !(g.lengthMm > 0) || !(g.clampMm > 0)) return plan;
    const double evenSpacing = g.lengthMm / (evenRings - 1);
    const double freeMm = g.lengthMm - 2 * g.clampMm;
    const bool graded = g.edgeSpacingMm > 0 && g.edgeSpacingMm < evenSpacing && g.ends == EndCondition::Clamped && freeMm > 0;
    if (!graded) {
        plan.clampIntervals = static_cast<int>(std::clamp(std::round(g.clampMm / evenSpacing), 1.0, evenRings));
        return plan;
    }
    // Spacings edge q^d up to the even spacing, as many as the free length has room for on both sides
    // with at least one even interval between.
    for (double spacing = g.edgeSpacingMm; spacing < evenSpacing && 2 * (plan.sideMm + spacing) < freeMm; spacing *= kRingGrowth) {
        plan.sideMm += spacing;
        ++plan.sideIntervals;
    }
    const double middleIntervals = std::max(1.0, std::round((freeMm - 2 * plan.sideMm) / evenSpacing));
    plan.clampIntervals = g.clampMm >= 2 * g.edgeSpacingMm ? 2 : 1;
    plan.count = 1 + 2 * plan.clampIntervals + 2 * plan.sideIntervals + middleIntervals;
    return plan;
}

int Rings(const RingPlan& plan) { return static_cast<int>(std::min(plan.count, 1e9)); }
}  // namespace

int RingCount(const GeometryDef& g) { return Rings(PlanOf(g)); }

bool RingsGraded(const GeometryDef& g) { return PlanOf(g).sideIntervals > 0; }

int ClampIntervals(const GeometryDef& g) { return PlanOf(g).clampIntervals; }

int ClampRingCount(const GeometryDef& g) { return ClampIntervals(g) + 1; }

std::vector<double> RingHeightsMm(const GeometryDef& g) {
    const RingPlan plan = PlanOf(g);
    const int H = Rings(plan), k = plan.clampIntervals, m = H - 1 - 2 * k;
    std::vector<double> z(std::max(H, 0));
    const double uniform = g.lengthMm / (H - 1);
    // The clamp on a ring of the uniform mesh (the default tube at 30, 59, 117 rings): the uniform
    // heights, bit for bit.
    if (g.ends != EndCondition::Clamped || m < 1 || (plan.sideIntervals == 0 && std::fabs(g.clampMm - k * uniform) <= 1e-12 * g.lengthMm)) {
        for (int j = 0; j < H; ++j) z[j] = g.lengthMm * j / (H - 1);
        return z;
    }
    // The free length's intervals: graded sides around an even middle, or all even.
    const double freeMm = g.lengthMm - 2 * g.clampMm;
    std::vector<double> free(m, freeMm / m);
    if (plan.sideIntervals > 0) {
        const int n = plan.sideIntervals;
        const double middle = (freeMm - 2 * plan.sideMm) / (m - 2 * n);
        for (int i = 0; i < m; ++i) {
            const int d = std::min(i, m - 1 - i);
            free[i] = d < n ? g.edgeSpacingMm * std::pow(kRingGrowth, d) : middle;
        }
    }
    // Each clamp: graded, its edge interval as long as the first free one, the rest of it before.
    std::vector<double> clamp(k, g.clampMm / k);
    if (plan.sideIntervals > 0 && k == 2) clamp = {g.clampMm - free.front(), free.front()};
    for (int j = 1; j <= k; ++j) z[j] = z[j - 1] + clamp[j - 1];
    z[k] = g.clampMm;
    for (int i = 0; i < m; ++i) z[k + 1 + i] = z[k + i] + free[i];
    z[H - 1 - k] = g.lengthMm - g.clampMm;
    for (int j = 1; j <= k; ++j) z[H - 1 - k + j] = z[H - 2 - k + j] + clamp[k - j];
    z[H - 1] = g.lengthMm;
    return z;
}

double EvaluationBytesEstimate(const ShellDef& def) {
    const GeometryDef& g = def.geometry;
    const double vertices = double(std::max(1, g.ringVertices)) * PlanOf(g).count + 2;
    const double positionsPerStep = 24 * vertices;
    return 40e6 + 1750 * vertices * std::log2(std::max(2.0, vertices)) + positionsPerStep * (std::max(1, def.load.steps) + 2);
}

ShellProblem BuildTubeProblem(const ShellDef& def, const Shape& shape, bool bending, std::string* error) {
    const GeometryDef& g = def.geometry;
    const int R = g.ringVertices, H = RingCount(g), c = ClampRingCount(g);
    const int ringCount = R * H;
    ShellProblem p;
    p.material = MembraneMaterialOf(def);
    p.bending = bending;
    p.rest.Resize(ringCount + 2);
    const double clampFraction = g.clampMm / g.lengthMm;
    auto fail = [&](const std::string& why) {
        if (error) *error = why;
        return ShellProblem{};
    };
    if (g.ends == EndCondition::Clamped && (H - 1 - 2 * ClampIntervals(g) < 1 || !(g.clampMm > 0)))
        return fail("the clamps leave no free ring between them (ShellDefError says why)");
    const auto* freeXY = std::get_if<FreeXYShape>(&shape);
    const auto* mesh = std::get_if<MeshShape>(&shape);
    if (freeXY && (static_cast<int>(freeXY->dx.size()) != ringCount || static_cast<int>(freeXY->dy.size()) != ringCount))
        return fail("free-xy needs one (dx, dy) per vertex of the " + std::to_string(R) + " x " + std::to_string(H) + " ring mesh: " +
                    std::to_string(ringCount) + " pairs");
    if (mesh && mesh->positions.Size() != ringCount)
        return fail("the mesh has " + std::to_string(mesh->positions.Size()) + " vertices; the ring mesh needs " + std::to_string(ringCount) + " (" +
                    std::to_string(R) + " per ring x " + std::to_string(H) + " rings)");
    const std::vector<double> heights = RingHeightsMm(g);
    for (int j = 0; j < H; ++j) {
        const double z = heights[j];
        for (int i = 0; i < R; ++i) {
            const int v = j * R + i;
            const double angle = 2 * std::numbers::pi * (i + 0.5 * j) / R;
            if (mesh) {
                p.rest.x[v] = mesh->positions.x[v];
                p.rest.y[v] = mesh->positions.y[v];
                p.rest.z[v] = mesh->positions.z[v];
                continue;
            }
            double rho = freeXY ? 1.0 : DesignRadius(shape, z / g.lengthMm, angle, clampFraction);
            if (!(rho > 0))
                return fail("the radius is " + std::to_string(rho * g.radiusMm) + " mm at height " + std::to_string(z) +
                            " mm: the shell models need a positive radius everywhere");
            p.rest.x[v] = g.radiusMm * rho * std::cos(angle);
            p.rest.y[v] = g.radiusMm * rho * std::sin(angle);
            p.rest.z[v] = z;
            if (freeXY) {
                p.rest.x[v] += g.radiusMm * freeXY->dx[v];
                p.rest.y[v] += g.radiusMm * freeXY->dy[v];
            }
        }
    }
    const int bottomCap = ringCount, topCap = ringCount + 1;
    p.rest.x[bottomCap] = p.rest.y[bottomCap] = 0;
    p.rest.z[bottomCap] = p.rest.z[0];
    p.rest.x[topCap] = p.rest.y[topCap] = 0;
    p.rest.z[topCap] = p.rest.z[(H - 1) * R];
    TubeTriangles(R, H, p.wall, p.caps);
    if (p.bending) p.hinges = HingesOf(p.wall);

    // Unknowns: clamped rings and caps ride on the clamps (bottom fixed, top by u along the axis);
    // sliding ends hold only the end rings' heights, with an anchor against rigid motion.
    p.dofOf.assign(3 * p.rest.Size(), kFree);
    auto hold = [&](int v, int coordinate, int how) { p.dofOf[3 * v + coordinate] = how; };
    const bool clamped = g.ends == EndCondition::Clamped;
    p.rigidTop = clamped && def.ends.tip == TipEnd::Free;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < R; ++i) {
            const int v = j * R + i;
            const bool bottom = clamped ? j < c : j == 0, top = clamped ? j >= H - c : j == H - 1;
            if (!bottom && !top) continue;
            if (clamped) {
                // The top clamp's rings turn with it (held or not, the torque is measured through them);
                // with the tip free they move with it in every direction.
                hold(v, 0, bottom ? kFixed : p.rigidTop ? kRigid : kTwist);
                hold(v, 1, bottom ? kFixed : p.rigidTop ? kRigid : kTwist);
            }
            hold(v, 2, bottom ? kFixed : p.rigidTop ? kRigid : kAxial);
        }
    for (int coordinate = 0; coordinate < 3; ++coordinate) {
        hold(bottomCap, coordinate, kFixed);
        hold(topCap, coordinate, p.rigidTop ? kRigid : coordinate == 2 ? kAxial : kFixed);
    }
    if (clamped) {
        p.onTop.assign(p.rest.Size(), 0);
        for (int v = (H - c) * R; v < H * R; ++v) p.onTop[v] = 1;
        p.onTop[topCap] = 1;
        p.topCap = topCap;
    }
    if (!clamped) {
        for (int i = 0; i < R; ++i) p.anchor.vertices.push_back(i);
        p.anchor.translation[0] = p.anchor.translation[1] = true;
        p.anchor.rotation[2] = true;
    }
    // u is an unknown (held by the solver under the blocked test, which steps it to its stroke); theta
    // is one unless the twist is held.
    const bool twistUnknown = clamped && def.ends.twist != TwistEnd::Held;
    NumberUnknowns(p, true, twistUnknown);
    if (clamped) {
        p.twistReference = (H - 1) * R;
        p.tiltReference = (H - 1) * R + R / 4;
        p.twistLeverMm = std::hypot(p.rest.x[p.twistReference], p.rest.y[p.twistReference]);
        if (!(p.twistLeverMm > 0)) return fail("the top clamp's ring lies on the axis");
    }
    FinishRest(p);
    p.anchor.stiffness = MembraneMaterialShearModulus(p.material) * p.material.thicknessMm / std::max(1, R);
    for (const auto& rest : p.membrane)
        if (!(rest.area > 1e-12 * p.meanEdgeMm * p.meanEdgeMm)) return fail("the rest shape has a degenerate triangle (two vertices in one place)");
    if (SelfIntersects(p, p.rest)) return fail("the rest shape passes through itself");
    std::string fibreError;
    SetFibres(p, def.fibres, g.lengthMm, &fibreError);
    if (!fibreError.empty()) return fail(fibreError);
    if (def.contact.mode == ContactMode::On) {
        std::string contactError;
        SetContact(p, def.contact, &contactError);
        if (!contactError.empty()) return fail(contactError);
    }
    if (error) error->clear();
    return p;
}

void SetContact(ShellProblem& p, const ContactDef& def, std::string* error) {
    const double h = p.material.thicknessMm;
    p.barrier.thicknessMm = h;
    p.barrier.activationMm = def.gapFraction * h;
    p.barrier.stiffness = def.stiffness * MembraneMaterialShearModulus(p.material) * h;
    // Rigid bodies: what is held in place (the bottom clamp), and the top clamp.
    std::vector<int> body(p.rest.Size(), -1);
    for (int v = 0; v < p.rest.Size(); ++v) {
        if (p.dofOf[3 * v] == kFixed && p.dofOf[3 * v + 1] == kFixed && p.dofOf[3 * v + 2] == kFixed) body[v] = 0;
        else if (!p.onTop.empty() && p.onTop[v]) body[v] = 1;
    }
    std::vector<std::array<int, 3>> triangles = p.wall;
    triangles.insert(triangles.end(), p.caps.begin(), p.caps.end());
    // Neighbours: closer than twice the reach at rest, and near along the wall. Two points of one
    // wall that far apart come within the barrier's reach only if the wall between them is squeezed
    // to half its length, which a wall does by wrinkling, not by compressing.
    p.contact = std::make_shared<const ContactSurface>(MakeContactSurface(p.rest, triangles, body, 2 * ContactReachMm(p.barrier)));
    // Walls that already touch at rest cannot be pushed apart by a barrier that starts at contact.
    if (p.contact->restClearanceMm <= h) {
        char text[160];
        std::snprintf(text, sizeof text, "the rest shape's walls are %.3g mm apart near z = %.1f mm, closer than the wall's thickness (%g mm)",
                      p.contact->restClearanceMm, p.rest.z[p.contact->restNearest.vertices[0]], h);
        if (error) *error = text;
        return;
    }
    if (error) error->clear();
}

ShellProblem BuildSphereProblem(const MembraneMaterial& material, double radius, int subdivisions, bool bending) {
    // An icosahedron, each triangle split in four `subdivisions` times, projected onto the sphere.
    const double t = (1 + std::sqrt(5.0)) / 2;
    std::vector<Eigen::Vector3d> v{{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    std::vector<std::array<int, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<int, int>, int> middle;
        auto mid = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            if (auto it = middle.find(key); it != middle.end()) return it->second;
            v.push_back(0.5 * (v[a] + v[b]));
            return middle[key] = static_cast<int>(v.size()) - 1;
        };
        std::vector<std::array<int, 3>> next;
        for (const auto& tri : f) {
            const int ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
            next.insert(next.end(), {{tri[0], ab, ca}, {tri[1], bc, ab}, {tri[2], ca, bc}, {ab, bc, ca}});
        }
        f = std::move(next);
    }
    ShellProblem p;
    p.material = material;
    p.bending = bending;
    p.rest.Resize(static_cast<int>(v.size()));
    for (size_t k = 0; k < v.size(); ++k) {
        const Eigen::Vector3d x = radius * v[k].normalized();
        p.rest.x[k] = x.x();
        p.rest.y[k] = x.y();
        p.rest.z[k] = x.z();
    }
    p.wall = f;
    if (bending) p.hinges = HingesOf(p.wall);
    p.dofOf.assign(3 * v.size(), kFree);
    // The icosahedron's twelve corners: symmetric about the centre, few enough to keep the anchor sparse.
    for (int k = 0; k < 12; ++k) p.anchor.vertices.push_back(k);
    for (int c = 0; c < 3; ++c) p.anchor.translation[c] = p.anchor.rotation[c] = true;
    NumberUnknowns(p, false);
    FinishRest(p);
    p.anchor.stiffness = MembraneMaterialShearModulus(material) * material.thicknessMm;
    return p;
}

ShellProblem BuildPatchProblem(const MembraneMaterial& material, double size, int n, const Eigen::Matrix<double, 3, 2>& boundaryF) {
    ShellProblem p;
    p.material = material;
    p.bending = false;
    p.rest.Resize(n * n);
    auto index = [n](int i, int j) { return j * n + i; };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            // A slightly irregular grid: the patch test must hold for any mesh.
            const double jitter = (i > 0 && i < n - 1 && j > 0 && j < n - 1) ? 0.15 * std::sin(3.7 * i + 1.3 * j) : 0;
            p.rest.x[index(i, j)] = size * (i + jitter) / (n - 1);
            p.rest.y[index(i, j)] = size * (j - jitter) / (n - 1);
            p.rest.z[index(i, j)] = 0;
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            p.wall.push_back({index(i, j), index(i + 1, j), index(i, j + 1)});
            p.wall.push_back({index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)});
        }
    p.dofOf.assign(3 * n * n, kFree);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            if (i == 0 || j == 0 || i == n - 1 || j == n - 1)
                for (int c = 0; c < 3; ++c) p.dofOf[3 * index(i, j) + c] = kFixed;
    NumberUnknowns(p, false);
    FinishRest(p);
    // The boundary is held where F puts it.
    for (int v = 0; v < n * n; ++v) {
        const Eigen::Vector3d x = boundaryF * Eigen::Vector2d(p.rest.x[v], p.rest.y[v]);
        p.held.x[v] = x.x();
        p.held.y[v] = x.y();
        p.held.z[v] = x.z();
    }
    return p;
}

std::array<int, kTopParameters> TopUnknowns(const ShellProblem& p) {
    return {p.lateral[0], p.lateral[1], p.axial, p.tilt[0], p.tilt[1], p.twist};
}

std::array<double, kTopParameters> TopParameters(const ShellProblem& p, const Eigen::VectorXd& q) {
    const std::array<int, kTopParameters> unknown = TopUnknowns(p);
    std::array<double, kTopParameters> value{0, 0, p.heldAxial, 0, 0, p.heldTwist};
    for (int k = 0; k < kTopParameters; ++k)
        if (unknown[k] >= 0) value[k] = q[unknown[k]];
    return value;
}

Eigen::Matrix3d TopRotation(const double angles[3], int i, int j, int k) {
    // A rotation about axis `axis` by `angle`, differentiated `order` times: cos and sin, and the
    // axis's own row and column (constant, so gone once differentiated).
    auto turn = [](int axis, double angle, int order) {
        const double c = std::cos(angle), s = std::sin(angle);
        // d^n/da^n of (cos a, sin a): (cos, sin), (-sin, cos), (-cos, -sin).
        const double dc = order == 0 ? c : order == 1 ? -s : -c;
        const double ds = order == 0 ? s : order == 1 ? c : -s;
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
        if (order == 0) m(axis, axis) = 1;
        m(a, a) = dc;
        m(a, b) = -ds;
        m(b, a) = ds;
        m(b, b) = dc;
        return m;
    };
    return turn(0, angles[0], i) * turn(1, angles[1], j) * turn(2, angles[2], k);
}

Eigen::VectorXd UnknownsOf(const ShellProblem& p, const Positions& x) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(p.unknowns);
    if (p.rigidTop) {
        // t from the cap centre (at c0 + t); R from the frames of two ring vertices, at rest and now.
        const int cap = p.topCap;
        const Eigen::Vector3d c0(p.rest.x[cap], p.rest.y[cap], p.rest.z[cap]), c(x.x[cap], x.y[cap], x.z[cap]);
        auto frame = [&](const Positions& at, const Eigen::Vector3d& centre) {
            const Eigen::Vector3d a = Eigen::Vector3d(at.x[p.twistReference], at.y[p.twistReference], at.z[p.twistReference]) - centre;
            const Eigen::Vector3d b = Eigen::Vector3d(at.x[p.tiltReference], at.y[p.tiltReference], at.z[p.tiltReference]) - centre;
            Eigen::Matrix3d e;
            e.col(0) = a.normalized();
            e.col(2) = a.cross(b).normalized();
            e.col(1) = e.col(2).cross(e.col(0));
            return e;
        };
        const Eigen::Matrix3d R = frame(x, c) * frame(p.rest, c0).transpose();
        const std::array<int, kTopParameters> unknown = TopUnknowns(p);
        // R = Rx(a) Ry(b) Rz(theta): R e_z = (sin b, -sin a cos b, cos a cos b), first row (cos b cos theta, -cos b sin theta, sin b).
        const double value[kTopParameters] = {c.x() - c0.x(), c.y() - c0.y(), c.z() - c0.z(), std::atan2(-R(1, 2), R(2, 2)),
                                              std::asin(std::clamp(R(0, 2), -1.0, 1.0)), std::atan2(-R(0, 1), R(0, 0))};
        for (int k = 0; k < kTopParameters; ++k)
            if (unknown[k] >= 0) q[unknown[k]] = value[k];
    }
    if (p.twist >= 0 && !p.rigidTop) {
        const int v = p.twistReference;
        const double X = p.rest.x[v], Y = p.rest.y[v];
        q[p.twist] = std::atan2(X * x.y[v] - Y * x.x[v], X * x.x[v] + Y * x.y[v]);
    }
    bool axialRead = false;
    for (int v = 0; v < x.Size(); ++v)
        for (int c = 0; c < 3; ++c) {
            const int d = p.dofOf[3 * v + c];
            const double value = c == 0 ? x.x[v] : c == 1 ? x.y[v] : x.z[v];
            if (d >= 0) q[d] = value;
            else if (d == kAxial && !axialRead && p.axial >= 0) {
                q[p.axial] = value - p.rest.z[v];
                axialRead = true;
            }
        }
    return q;
}

void PositionsOf(const ShellProblem& p, const Eigen::VectorXd& q, Positions& x) {
    const int n = p.rest.Size();
    if (x.Size() != n) x.Resize(n);
    const double u = p.axial >= 0 ? q[p.axial] : p.heldAxial;
    const double theta = p.twist >= 0 ? q[p.twist] : p.heldTwist;
    const double cosine = std::cos(theta), sine = std::sin(theta);
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d c0 = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
    if (p.rigidTop) {
        const std::array<double, kTopParameters> top = TopParameters(p, q);
        R = TopRotation(&top[kTopTiltX], 0, 0, 0);
        c0 = Eigen::Vector3d(p.rest.x[p.topCap], p.rest.y[p.topCap], p.rest.z[p.topCap]);
        c = c0 + Eigen::Vector3d(top[kTopX], top[kTopY], top[kTopAxial]);
    }
    for (int v = 0; v < n; ++v) {
        const int* d = &p.dofOf[3 * v];
        if (d[0] == kRigid) {  // the clamp as a rigid body
            const Eigen::Vector3d at = c + R * (Eigen::Vector3d(p.rest.x[v], p.rest.y[v], p.rest.z[v]) - c0);
            x.x[v] = at.x();
            x.y[v] = at.y();
            x.z[v] = at.z();
            continue;
        }
        if (d[0] == kTwist) {  // x and y turn together
            x.x[v] = cosine * p.rest.x[v] - sine * p.rest.y[v];
            x.y[v] = sine * p.rest.x[v] + cosine * p.rest.y[v];
        } else {
            x.x[v] = d[0] >= 0 ? q[d[0]] : p.held.x[v];
            x.y[v] = d[1] >= 0 ? q[d[1]] : p.held.y[v];
        }
        x.z[v] = d[2] >= 0 ? q[d[2]] : d[2] == kAxial ? p.rest.z[v] + u : p.held.z[v];
    }
}

Matrix32 DeformationGradient(const ShellProblem& p, int t, const Positions& x) {
    const auto& tri = p.wall[t];
    const MembraneRest& r = p.membrane[t];
    Matrix32 F = Matrix32::Zero();
    for (int a = 0; a < 3; ++a) F += At(x, tri[a]) * Eigen::RowVector2d(r.g[a][0], r.g[a][1]);
    return F;
}

std::vector<int> VertexBlockPlaces(const ShellProblem& p) {
    std::vector<int> places(p.unknowns, -1);
    int blocks = 0;
    for (int v = 0; v < p.vertexCount(); ++v) {
        bool free = false;
        for (int c = 0; c < 3; ++c)
            if (const int d = p.dofOf[3 * v + c]; d >= 0) {
                places[d] = 3 * blocks + c;
                free = true;
            }
        blocks += free;
    }
    int shared = 0;  // the top's parameters (u and theta; all six with the tip free): blocks of their own
    for (int d : TopUnknowns(p))
        if (d >= 0) places[d] = 3 * blocks + shared++;
    return places;
}

}  // namespace sim
