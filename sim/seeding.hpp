#pragma once
// Every noise source of the simulator draws from its own generator, seeded from the run's
// seed and a per-source constant, so adding draws to one sensor never changes another's.
#include <cstdint>
#include <random>

namespace slambox {

/// SplitMix64 finalizer (Steele, Lea, Flood 2014): a bijective 64-bit mixer.
inline std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

enum class NoiseSource : std::uint64_t { kOdometry = 1, kLidar = 2, kLandmarks = 3, kGyro = 4 };

inline std::mt19937_64 MakeGenerator(std::uint64_t seed, NoiseSource source) {
  return std::mt19937_64(SplitMix64(SplitMix64(seed) ^ SplitMix64(static_cast<std::uint64_t>(source) << 32)));
}

}  // namespace slambox
