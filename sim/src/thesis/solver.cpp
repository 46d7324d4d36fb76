// The `thesis` model's relaxation loop (docs/models/thesis.md, "One iteration").
//
// [SECTION] World: the solver's state as structure-of-arrays
// [SECTION] Stages of one iteration: springs, then free and clamped vertices gather and move
// [SECTION] Run loop, health checks, public entry points
//
// Speed comes from the mesh's regularity: every spring family is "vertex i to vertex i+offset", so
// each stage is a plain loop over contiguous arrays that the compiler vectorises (build with
// -DACTUATOR_VEC_REPORT=ON to see it). Each spring's force is written once per family into its own
// array; a vertex then gathers "my springs minus the springs whose upper end I am" at fixed offsets,
// which avoids the scattered += of an edge list. The summation order is fixed, so results are
// bit-identical across vector widths and thread counts.
#include "sim/solver.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace sim {
namespace {

// ---------------------------------------------------------------------------------------------
// [SECTION] World
// ---------------------------------------------------------------------------------------------

// Buffers on 64-byte boundaries (a cache line, an AVX-512 vector): the vectorised loops then run
// the same wherever the heap happens to place them, in the command line or inside Python.
template <typename T>
struct CacheLineAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlignment{64};
    CacheLineAllocator() = default;
    template <typename U>
    CacheLineAllocator(const CacheLineAllocator<U>&) {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
    void deallocate(T* p, std::size_t) { ::operator delete(p, kAlignment); }
    template <typename U>
    bool operator==(const CacheLineAllocator<U>&) const { return true; }
};
template <typename Real>
using Buffer = std::vector<Real, CacheLineAllocator<Real>>;

template <typename Real>
struct World {
    int resolution = 0;  // R
    int vertexCount = 0; // N
    int clampBand = 0;   // vertices held at each end: 2R
    std::array<int, 4> offsets{};
    // Leading zeros before each spring-force array, so that "spring ending at i" reads index
    // i - offset without a bounds branch. Trailing entries (springs that do not exist) stay zero.
    int pad = 0;

    Buffer<Real> x, y, z;              // positions at the start of the iteration
    Buffer<Real> nextX, nextY, nextZ;  // positions after it (double buffer, swapped each step)
    std::array<Buffer<Real>, 4> restLength;  // per family, indexed by lower vertex
    std::array<Buffer<Real>, 4> springFx, springFy, springFz;  // force on lower vertex, padded
    Buffer<Real> inflationX, inflationY, inflationZ;           // the inflation force on each free vertex

    Real springConstant{}, pressureScale{}, pullForce{}, stepScale{};
    Load load = Load::Inflate;
};

// One formula for a spring's length, used for rest lengths and in the loop, so that an undeformed
// spring gives exactly zero force (an unloaded mesh must not creep).
template <typename Real>
inline Real SpringLength(Real dx, Real dy, Real dz) {
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

template <typename Real>
World<Real> MakeWorld(const Positions& initial, const MeshDef& def, const SimParams& params) {
    World<Real> w;
    w.resolution = def.resolution;
    w.vertexCount = VertexCount(def);
    w.clampBand = kClampedTurns * def.resolution;
    w.offsets = SpringOffsets(def);
    w.pad = def.resolution + 1;
    const int n = w.vertexCount;

    w.x.resize(n); w.y.resize(n); w.z.resize(n);
    for (int i = 0; i < n; ++i) {
        w.x[i] = static_cast<Real>(initial.x[i]);
        w.y[i] = static_cast<Real>(initial.y[i]);
        w.z[i] = static_cast<Real>(initial.z[i]);
    }
    // Clamped vertices never change x or y, so both buffers keep them without being written.
    w.nextX = w.x; w.nextY = w.y; w.nextZ = w.z;

    for (int f = 0; f < 4; ++f) {
        const int o = w.offsets[f];
        w.restLength[f].assign(n, Real(0));
        for (int i = 0; i + o < n; ++i)
            w.restLength[f][i] = SpringLength(w.x[i + o] - w.x[i], w.y[i + o] - w.y[i], w.z[i + o] - w.z[i]);
        w.springFx[f].assign(w.pad + n, Real(0));
        w.springFy[f].assign(w.pad + n, Real(0));
        w.springFz[f].assign(w.pad + n, Real(0));
    }
    w.inflationX.assign(n, Real(0));
    w.inflationY.assign(n, Real(0));
    w.inflationZ.assign(n, Real(0));
    w.springConstant = static_cast<Real>(params.springConstant);
    w.pressureScale = static_cast<Real>(params.pressureScale);
    w.pullForce = static_cast<Real>(params.pullForce);
    w.stepScale = static_cast<Real>(params.stepScale);
    w.load = params.load;
    return w;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Stages of one iteration
// ---------------------------------------------------------------------------------------------

// Hot kernels are kept out of line: inlined into the run loop, GCC 12 loses track of the restrict
// pointers and stops vectorising them.
#define ACTUATOR_KERNEL __attribute__((noinline))

// Hooke's law for every spring of one family: force on the lower vertex i toward i+offset.
// Raw pointers in the signature: given the World by reference, GCC 12 does not vectorise this loop.
template <typename Real>
ACTUATOR_KERNEL void ComputeSpringFamily(int offset, int count, Real springConstant, const Real* __restrict x,
                                         const Real* __restrict y, const Real* __restrict z,
                                         const Real* __restrict rest, Real* __restrict sfx,
                                         Real* __restrict sfy, Real* __restrict sfz) {
    for (int i = 0; i < count; ++i) {
        const Real dx = x[i + offset] - x[i];
        const Real dy = y[i + offset] - y[i];
        const Real dz = z[i + offset] - z[i];
        const Real length = SpringLength(dx, dy, dz);
        // A spring squeezed to zero length has no direction: it exerts no force this iteration.
        const Real scale = length > Real(0) ? springConstant * (length - rest[i]) / length : Real(0);
        sfx[i] = scale * dx;
        sfy[i] = scale * dy;
        sfz[i] = scale * dz;
    }
}

template <typename Real>
void ComputeSpringForces(World<Real>& w) {
    for (int f = 0; f < 4; ++f) {
        const int o = w.offsets[f];
        ComputeSpringFamily(o, w.vertexCount - o, w.springConstant, w.x.data(), w.y.data(), w.z.data(),
                            w.restLength[f].data(), w.springFx[f].data() + w.pad, w.springFy[f].data() + w.pad,
                            w.springFz[f].data() + w.pad);
    }
}

// The vertex stages below share one idea: a vertex's spring force is + its own springs (it is the
// lower end) - the springs whose upper end it is, read at i - offset. The summation order is fixed,
// so the result does not depend on the vector width.
template <typename Real>
struct SpringForceView {
    const Real* __restrict s0;
    const Real* __restrict s1;
    const Real* __restrict s2;
    const Real* __restrict s3;
};

template <typename Real>
SpringForceView<Real> ViewOf(const World<Real>& w, const std::array<Buffer<Real>, 4>& spring) {
    return {spring[0].data() + w.pad, spring[1].data() + w.pad, spring[2].data() + w.pad, spring[3].data() + w.pad};
}

#define ACTUATOR_GATHER(v, i) \
    (((v).s0[i] - (v).s0[(i) - o0]) + ((v).s1[i] - (v).s1[(i) - o1]) + ((v).s2[i] - (v).s2[(i) - o2]) + \
     ((v).s3[i] - (v).s3[(i) - o3]))

// Free vertices: spring forces, plus inflation when the load is Inflate, then the overdamped move
// (every vertex moves by its force times the step scale; there is no velocity).
//
// Inflation is the cross product of the edges one turn up and one step along the helix: its length
// is the area of the patch the vertex pushes on, and it points outward on the bare cylinder.
//
// One coordinate at a time: a loop over all three would read 24 spring-force streams and 9 position
// streams and write 3, more pointers than there are registers, and spend its time reloading them.
// The inflation force is computed first into its own arrays; each coordinate then gathers its
// springs, adds it and moves. Each vertex's sum keeps the formula's order (springs, then inflation),
// so the split does not change a bit.
template <typename Real>
ACTUATOR_KERNEL void InflationRange(int begin, int end, int resolution, Real pressureScale, const Real* __restrict x,
                                    const Real* __restrict y, const Real* __restrict z, Real* __restrict ix,
                                    Real* __restrict iy, Real* __restrict iz) {
    const int r = resolution;
    const Real c = pressureScale;
    for (int i = begin; i < end; ++i) {
        const Real ax = x[i + r] - x[i], ay = y[i + r] - y[i], az = z[i + r] - z[i];  // one turn up
        const Real bx = x[i + 1] - x[i], by = y[i + 1] - y[i], bz = z[i + 1] - z[i];  // next along helix
        ix[i] = c * (ay * bz - az * by);
        iy[i] = c * (az * bx - ax * bz);
        iz[i] = c * (ax * by - ay * bx);
    }
}

// One coordinate of the free vertices' move: its spring forces, plus the inflation force when given.
template <typename Real, bool kInflate>
ACTUATOR_KERNEL void MoveFreeCoordinate(int begin, int end, std::array<int, 4> offsets, Real stepScale, SpringForceView<Real> s,
                                        const Real* __restrict inflation, const Real* __restrict position,
                                        Real* __restrict next) {
    const int o0 = offsets[0], o1 = offsets[1], o2 = offsets[2], o3 = offsets[3];
    for (int i = begin; i < end; ++i) {
        Real f = ACTUATOR_GATHER(s, i);
        if constexpr (kInflate) f += inflation[i];
        next[i] = position[i] + stepScale * f;
    }
}

// Clamped vertices slide only along z, like the rig's clamps that hold the actuator's ends; they get
// no inflation. `pull` is the stretch test's force on this range (0 when not pulled).
template <typename Real>
ACTUATOR_KERNEL void MoveClampedRange(int begin, int end, std::array<int, 4> offsets, Real pull, Real stepScale,
                                      SpringForceView<Real> sz, const Real* __restrict z, Real* __restrict nextZ) {
    const int o0 = offsets[0], o1 = offsets[1], o2 = offsets[2], o3 = offsets[3];
    for (int i = begin; i < end; ++i) {
        const Real fz = ACTUATOR_GATHER(sz, i) + pull;
        nextZ[i] = z[i] + stepScale * fz;
    }
}

#undef ACTUATOR_GATHER

template <typename Real>
void MoveFreeVertices(World<Real>& w) {
    const int begin = w.clampBand, end = w.vertexCount - w.clampBand;
    const bool inflate = w.load == Load::Inflate;
    if (inflate)
        InflationRange(begin, end, w.resolution, w.pressureScale, w.x.data(), w.y.data(), w.z.data(), w.inflationX.data(),
                       w.inflationY.data(), w.inflationZ.data());
    const auto move = [&](const std::array<Buffer<Real>, 4>& spring, const Buffer<Real>& inflation, const Buffer<Real>& position,
                          Buffer<Real>& next) {
        const auto kernel = inflate ? MoveFreeCoordinate<Real, true> : MoveFreeCoordinate<Real, false>;
        kernel(begin, end, w.offsets, w.stepScale, ViewOf(w, spring), inflation.data(), position.data(), next.data());
    };
    move(w.springFx, w.inflationX, w.x, w.nextX);
    move(w.springFy, w.inflationY, w.y, w.nextY);
    move(w.springFz, w.inflationZ, w.z, w.nextZ);
}

// The two clamped turns at each end. Under the stretch load the outermost turn at each end is pulled
// outward (bottom down, top up); the turn next to it is held but not pulled.
template <typename Real>
void MoveClampedVertices(World<Real>& w) {
    const auto sz = ViewOf(w, w.springFz);
    const int n = w.vertexCount, r = w.resolution;
    const Real pull = w.load == Load::Stretch ? w.pullForce : Real(0);
    auto move = [&](int begin, int end, Real force) {
        MoveClampedRange(begin, end, w.offsets, force, w.stepScale, sz, w.z.data(), w.nextZ.data());
    };
    move(0, r, -pull);
    move(r, w.clampBand, Real(0));
    move(n - w.clampBand, n - r, Real(0));
    move(n - r, n, pull);
}

// One iteration: all forces from the positions at its start, then all vertices move.
template <typename Real>
void Step(World<Real>& w) {
    ComputeSpringForces(w);
    MoveFreeVertices(w);
    MoveClampedVertices(w);
    std::swap(w.x, w.nextX);
    std::swap(w.y, w.nextY);
    std::swap(w.z, w.nextZ);
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Run loop
// ---------------------------------------------------------------------------------------------

// Coordinates that are NaN, infinite or beyond the bound. One compare per coordinate, vectorised, so
// it runs after every iteration: a blow-up goes from 1e3 to NaN in a handful of iterations (the
// inflation force grows with area), and only an every-iteration check can call it `diverged`.
template <typename Real>
ACTUATOR_KERNEL int CountOutside(const Real* __restrict values, int count, Real bound) {
    int outside = 0;
    for (int i = 0; i < count; ++i) outside += !(std::fabs(values[i]) <= bound);
    return outside;
}

template <typename Real>
Status CheckHealth(const World<Real>& w, double divergenceLimit) {
    const Real bound = static_cast<Real>(divergenceLimit);
    const int n = w.vertexCount;
    if (CountOutside(w.x.data(), n, bound) + CountOutside(w.y.data(), n, bound) + CountOutside(w.z.data(), n, bound) == 0)
        return Status::Ok;
    for (const auto* array : {&w.x, &w.y, &w.z})
        for (Real v : *array)
            if (!std::isfinite(v)) return Status::NaN;
    return Status::Diverged;
}

template <typename Real>
Positions ToPositions(const World<Real>& w) {
    Positions p;
    p.Resize(w.vertexCount);
    for (int i = 0; i < w.vertexCount; ++i) {
        p.x[i] = w.x[i];
        p.y[i] = w.y[i];
        p.z[i] = w.z[i];
    }
    return p;
}

template <typename Real>
SimResult Run(const Positions& initial, const MeshDef& def, const SimParams& params, const SimObserver* observer) {
    const auto start = std::chrono::steady_clock::now();
    World<Real> w = MakeWorld<Real>(initial, def, params);
    SimResult result;
    // The mesh actually simulated: for float, the initial positions rounded to float. Measuring the
    // fitness against it keeps an unloaded mesh at exactly zero.
    result.initial = ToPositions(w);

    const bool observing = observer && observer->interval > 0 && observer->onSnapshot;
    if (observing && !observer->onSnapshot(0, result.initial)) {
        result.final = result.initial;
        result.fitness = 0;
        result.elapsedMs = 0;
        return result;
    }
    int iteration = 0;
    Status status = CheckHealth(w, params.divergenceLimit);
    while (status == Status::Ok && iteration < params.iterations) {
        Step(w);
        ++iteration;
        status = CheckHealth(w, params.divergenceLimit);
        if (status != Status::Ok) break;
        if (observing && iteration % observer->interval == 0 && !observer->onSnapshot(iteration, ToPositions(w)))
            break;
    }
    result.status = status;
    result.iterationsRun = iteration;
    result.final = ToPositions(w);
    if (status == Status::Ok) {
        result.fitness = Fitness(result.initial, result.final, def);
        result.contractionPercent = 100.0 * result.fitness / def.turns;
    } else {
        result.fitness = std::nan("");
        result.contractionPercent = std::nan("");
    }
    result.elapsedMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public entry points
// ---------------------------------------------------------------------------------------------

SimParams DefaultSimParams() { return SimParams{}; }

std::string SimParamsError(const SimParams& p) {
    if (p.iterations < 0 || p.iterations > kMaxIterations)
        return "iterations must be between 0 and " + std::to_string(kMaxIterations);
    const std::pair<const char*, double> constants[] = {{"spring constant", p.springConstant},
                                                        {"pressure scale", p.pressureScale},
                                                        {"pull force", p.pullForce},
                                                        {"step scale", p.stepScale}};
    for (const auto& [name, value] : constants)
        if (!std::isfinite(value) || value < 0) return std::string(name) + " must be a finite number, not negative";
    if (!(p.divergenceLimit > 0) || !std::isfinite(p.divergenceLimit)) return "divergence limit must be a positive finite number";
    return "";
}

SimResult Simulate(const Positions& initial, const MeshDef& def, const SimParams& params, const SimObserver* observer) {
    if (params.precision == Precision::Double) return Run<double>(initial, def, params, observer);
    return Run<float>(initial, def, params, observer);
}

SimResult Evaluate(const Shape& shape, const MeshDef& def, const SimParams& params) {
    return Simulate(BuildInitialPositions(shape, def), def, params);
}

double Fitness(const Positions& initial, const Positions& final, const MeshDef& def) {
    const int r = def.resolution;
    const int n = VertexCount(def);
    double bottomRise = 0, topRise = 0;
    for (int i = 0; i < r; ++i) bottomRise += final.z[i] - initial.z[i];
    for (int i = n - r; i < n; ++i) topRise += final.z[i] - initial.z[i];
    return bottomRise / r - topRise / r;
}

std::uint64_t PositionsHash(const Positions& positions) {
    std::uint64_t hash = 1469598103934665603ull;
    auto mix = [&hash](double v) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int b = 0; b < 8; ++b) {
            hash ^= (bits >> (8 * b)) & 0xffu;
            hash *= 1099511628211ull;
        }
    };
    for (int i = 0; i < positions.Size(); ++i) {
        mix(positions.x[i]);
        mix(positions.y[i]);
        mix(positions.z[i]);
    }
    return hash;
}

}  // namespace sim
