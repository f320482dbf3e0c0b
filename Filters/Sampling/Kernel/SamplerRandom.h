// SPDX-License-Identifier: BSD-3-Clause
// SamplerRandom: the particle sampler's portable random numbers (splitmix64 uniforms and uniform
// barycentric coordinates): the same seed gives the same sites on every platform.
#ifndef av_SamplerRandom_h
#define av_SamplerRandom_h

#include <cstdint>
#include <utility>

namespace av
{
namespace sampling
{

/// Portable uniform double in [0,1) (std distributions differ between standard libraries).
struct Rng
{
  std::uint64_t State;
  explicit Rng(std::uint64_t seed)
    : State(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull)
  {
  }
  std::uint64_t Next() // splitmix64
  {
    std::uint64_t z = (State += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
};

/// Uniform barycentrics on `nv` vertices (gaps of sorted uniforms).
inline void UniformBary(Rng& rng, int nv, double* b)
{
  double cut[5] = { 0.0, 0.0, 0.0, 0.0, 0.0 };
  for (int j = 1; j < nv; ++j)
    cut[j] = rng.Uniform();
  for (int a = 2; a < nv; ++a) // insertion sort of the nv - 1 uniforms
    for (int c = a; c > 1 && cut[c] < cut[c - 1]; --c)
      std::swap(cut[c], cut[c - 1]);
  cut[nv] = 1.0;
  for (int j = 0; j < nv; ++j)
    b[j] = cut[j + 1] - cut[j];
}

} // namespace sampling
} // namespace av

#endif
