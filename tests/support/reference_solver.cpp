#include "reference_solver.h"

#include <cmath>
#include <vector>

namespace reference {

struct Vertex {
    double x, y, z, forceX, forceY, forceZ;
};
struct Edge {
    int a, b;
    double rest;
};

sim::Positions Relax(const sim::Positions& initial, const sim::MeshDef& def, const sim::SimParams& params) {
    const int R = def.resolution, N = R * def.turns;
    std::vector<Vertex> v(N);
    for (int i = 0; i < N; ++i) v[i] = {initial.x[i], initial.y[i], initial.z[i], 0, 0, 0};
    std::vector<Edge> edges;
    for (int i = 0; i < N; ++i)
        for (int o : {1, R, R - 1, R + 1})
            if (i + o < N) {
                const double dx = v[i + o].x - v[i].x, dy = v[i + o].y - v[i].y, dz = v[i + o].z - v[i].z;
                edges.push_back({i, i + o, std::sqrt(dx * dx + dy * dy + dz * dz)});
            }
    auto clamped = [&](int i) { return i < 2 * R || i >= N - 2 * R; };
    for (int it = 0; it < params.iterations; ++it) {
        for (auto& p : v) p.forceX = p.forceY = p.forceZ = 0;
        for (const Edge& e : edges) {
            const double dx = v[e.b].x - v[e.a].x, dy = v[e.b].y - v[e.a].y, dz = v[e.b].z - v[e.a].z;
            const double l = std::sqrt(dx * dx + dy * dy + dz * dz);
            if (l == 0) continue;
            const double f = params.springConstant * (l - e.rest) / l;
            v[e.a].forceX += f * dx; v[e.a].forceY += f * dy; v[e.a].forceZ += f * dz;
            v[e.b].forceX -= f * dx; v[e.b].forceY -= f * dy; v[e.b].forceZ -= f * dz;
        }
        for (int i = 0; i < N; ++i)
            if (clamped(i)) v[i].forceX = v[i].forceY = 0;
        if (params.load == sim::Load::Inflate) {
            for (int i = 0; i < N; ++i) {
                if (clamped(i)) continue;
                const double ax = v[i + R].x - v[i].x, ay = v[i + R].y - v[i].y, az = v[i + R].z - v[i].z;
                const double bx = v[i + 1].x - v[i].x, by = v[i + 1].y - v[i].y, bz = v[i + 1].z - v[i].z;
                v[i].forceX += params.pressureScale * (ay * bz - az * by);
                v[i].forceY += params.pressureScale * (az * bx - ax * bz);
                v[i].forceZ += params.pressureScale * (ax * by - ay * bx);
            }
        } else if (params.load == sim::Load::Stretch) {
            for (int i = 0; i < R; ++i) v[i].forceZ -= params.pullForce;
            for (int i = N - R; i < N; ++i) v[i].forceZ += params.pullForce;
        }
        for (auto& p : v) {
            p.x += params.stepScale * p.forceX;
            p.y += params.stepScale * p.forceY;
            p.z += params.stepScale * p.forceZ;
        }
    }
    sim::Positions out;
    out.Resize(N);
    for (int i = 0; i < N; ++i) {
        out.x[i] = v[i].x;
        out.y[i] = v[i].y;
        out.z[i] = v[i].z;
    }
    return out;
}

}  // namespace reference
