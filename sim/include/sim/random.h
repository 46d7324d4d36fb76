// A small, fully specified random number generator (xoshiro256**, seeded through SplitMix64) with
// its own distributions, so that a seed gives the same numbers on every compiler and standard
// library, and the whole state fits in a checkpoint.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace sim {

inline std::uint64_t SplitMix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Seed of run `run` of an experiment with seed `seed`: independent streams, written into outputs.
inline std::uint64_t DeriveSeed(std::uint64_t seed, std::uint64_t run) {
    std::uint64_t state = seed ^ (0xA0761D6478BD642Full * (run + 1));
    return SplitMix64(state);
}

class Random {
public:
    explicit Random(std::uint64_t seed = 1) {
        std::uint64_t s = seed;
        for (auto& word : state_) word = SplitMix64(s);
    }

    std::uint64_t Next() {
        const std::uint64_t result = Rotl(state_[1] * 5, 7) * 9;
        const std::uint64_t t = state_[1] << 17;
        state_[2] ^= state_[0];
        state_[3] ^= state_[1];
        state_[1] ^= state_[2];
        state_[0] ^= state_[3];
        state_[2] ^= t;
        state_[3] = Rotl(state_[3], 45);
        return result;
    }

    // Uniform in [0, 1) with 53 random bits.
    double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

    // Uniform integer in [low, high], unbiased (rejection).
    long long Integer(long long low, long long high) {
        const std::uint64_t span = static_cast<std::uint64_t>(high - low) + 1;
        if (span == 0) return static_cast<long long>(Next());
        const std::uint64_t limit = ~std::uint64_t(0) - (~std::uint64_t(0) % span);
        std::uint64_t draw;
        do draw = Next();
        while (draw >= limit);
        return low + static_cast<long long>(draw % span);
    }

    bool Chance(double probability) { return Uniform() < probability; }

    // Standard normal by Box-Muller (one of the pair; no hidden cached state).
    double Normal() {
        double u = Uniform();
        while (u <= 0) u = Uniform();
        return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * Uniform());
    }

    const std::array<std::uint64_t, 4>& State() const { return state_; }
    void SetState(const std::array<std::uint64_t, 4>& state) { state_ = state; }

private:
    static std::uint64_t Rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::array<std::uint64_t, 4> state_{};
};

}  // namespace sim
