/// Optics: the camera side of the polarimeter (docs/pli-simulation.md §5): Gaussian PSF at voxel
/// resolution, binning to CCD pixels, camera noise. Every function works on a piece of the global
/// image and gives exactly the values of the whole-image computation (global mirror edges, global
/// pixel keys for the noise).
#pragma once

#include "PLI/PLITypes.h"

#include <cstdint>
#include <vector>

namespace fiberpli
{
namespace pli
{

/// Kernel radii from here on are refused (a weight vector of gigabytes, or an int overflow).
constexpr std::int64_t kMaxGaussianRadius = std::int64_t{ 1 } << 30;

/// Kernel radius R = int(4σ + 0.5) (§5.1); 0 for σ <= 0, −1 when not finite or >=
/// kMaxGaussianRadius.
std::int64_t gaussianRadius(double sigmaVox);

/// Normalised weights w_m, m = −R..R, R = gaussianRadius(σ) (§5.1). σ <= 0 → {1}; empty when R < 0.
std::vector<double> gaussianWeights(double sigmaVox);

/// Half-sample mirror of index i into [0, n), repeated for long kernels (§5.1).
std::int64_t mirrorIndex(std::int64_t i, std::int64_t n);

/// Blurs `in` (a piece of the global nGlobalX × nGlobalY voxel image) with σ in voxels; out covers
/// `range`. `in` must hold every column the kernel reads (range ± R, mirrored at the global edge).
/// Error when R exceeds twice the larger image side (planPLI refuses such an OpticalSigma first).
Status blurStack(const Stack& in, std::int64_t nGlobalX, std::int64_t nGlobalY, double sigmaVox,
  const GridRange& range, Stack& out);

/// Mean of the voxels of each pixel in `pixels` (§5.2, the mapping of Section/PixelGrid.h); `in`
/// must cover those voxels.
Status binStack(const Stack& in, std::int64_t nVoxX, std::int64_t nVoxY, double scale,
  const GridRange& pixels, Stack& out);

/// Camera counts with mean I and variance g·I (§5.3): Gamma–Poisson mixture for g > 1, Poisson for
/// g = 1, nothing for g = 0. The stream of value (pixel, k) is RandomStream(seed, global pixel
/// index p + q·nPxX, view·2^32 + k), so any split or thread count gives the same numbers.
void addNoise(
  Stack& pixels, double gain, std::uint64_t seed, int view, std::int64_t nPxX, int threads);

/// One noisy sample with mean I (exposed for the statistical tests).
double sampleCounts(
  double I, double gain, std::uint64_t seed, std::uint64_t key1, std::uint64_t key2);

} // namespace pli
} // namespace fiberpli
