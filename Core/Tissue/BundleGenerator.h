/// BundleGenerator: FiberBundleSource's Core (docs/tissue-models.md §2, §5, §6.2–§6.5, §7, §8).
/// Builds bundles of fibers along trajectories: a straight cylinder, a user polyline, or the
/// paper's crossing, Y-shaped and chiasm-like models, ready for the collision solver.
#pragma once

#include "Model/FiberModel.h"
#include "Tissue/BundleOptions.h"
#include "Tissue/CrossSection.h"
#include "Tissue/FiberShape.h"
#include "Tissue/Ranvier.h"
#include "Tissue/Trajectory.h"

#include <string>
#include <vector>

namespace fiberpli
{

/// Lays one cross-section fiber along a resampled trajectory (docs/tissue-models.md §2, §5.2,
/// §5.4): x_k = T_k + σ_k·(s.x·u_k + s.y·v_k); then Ranvier profile points (if options.spacing > 0)
/// with radius r_j·factor, else constant r_j; then every point + U[−D, D]³ drawn point by point (x,
/// y, z) from fiber.rng (which is advanced). id and bundle are left 0 for the caller. With
/// dispersion (§10.2) the fiber is first tilted about its middle by a Watson-drawn angle (at most
/// 75°) in a random direction across the path. With undulation (shape.tortuosity > 1, §10.1) the
/// laid polyline is the base path of an undulated fiber of round(τ·L/l) + 1 points (frames u_k, v_k
/// across it), displaced by draws of the fiber's Jitter stream, calibrated with them, and the
/// Ranvier points are inserted on it afterwards; with beading (§10.3) the radii are multiplied by
/// the fiber's profile along its arc length. Shape streams: (seed, crossSection, key) of
/// shapeStream.
Fiber layFiber(const ResampledTrajectory& trajectory, const TrajectoryFrames& frames,
  CrossSectionFiber& fiber, const RanvierOptions& ranvier, double displacement,
  const ShapeOptions& shape = {}, double segmentLength = 0.0, std::uint64_t seed = 0,
  bool* reached = nullptr);

/// The target shape of an undulated bundle fiber (Tissue/FiberShape.h, docs/tissue-models.md
/// §10.8): the base path is the fiber laid along the trajectory at its seed offset (and dispersed),
/// with the transported frames across it; round(τ·L/l) + 1 points; displacements from the fiber's
/// Jitter stream; undulation from its Undulation stream, calibrated with the displacements. Nodes
/// of Ranvier and beading come on top (layFiber).
FiberShape bundleFiberShape(const ResampledTrajectory& trajectory, const TrajectoryFrames& frames,
  const CrossSectionFiber& fiber, double displacement, const ShapeOptions& shape,
  double segmentLength, std::uint64_t seed);

/// FiberBundleSource (docs/tissue-models.md §8). Shapes and bundle ids:
/// - Cylinder: along x from (−Length/2, 0, 0) to (+Length/2, 0, 0); bundle 0.
/// - Trajectory: along *trajectory (optional per-point scale σ_k multiplies the offsets); bundle 0.
/// - Crossing (§6.3): axes (1, 0, 0) and (cos ω, sin ω, 0), each of length Length through the
///   origin; bundles 0, 1 with independent cross-sections 0, 1.
/// - YShape (§6.4): trunk along +y to the fork at the origin, seeds with x < 0 turn to
///   b− = (−sin(ω/2), cos(ω/2), 0) (bundle 0), x >= 0 to b+ (bundle 1); turn radius
///   max(2R, 5r); trunk and branch Length/2 each.
/// - Chiasm (§6.5): H = Length/2; bundles 0 left→right crossing, 1 right→left crossing, 2 left
///   uncrossed, 3 right uncrossed (the ⌈f·N⌉ fibers of each nerve with the largest entry offset
///   along the lateral normal, ties by index); Ranvier on by default. The uncrossed fibers follow
///   their nerve's axis, turn on a circular arc of radius max(2R, 5r) tangent to both nerve axes
///   (chiasmSidePath) and leave along the other nerve's axis, so the innermost of them turn on a
///   radius >= R and never fold over (fastPLI's five-point side curve had a tip radius of 0.144·H,
///   below the default R, and folded 32 of 44 uncrossed fibers). Only when the arc must shrink to
///   fit (H/tan(ω/2) < R, very short nerves or wide angles) does bundleWarnings report folding.
/// All paths are resampled by arc length at SegmentLength (resampleTrajectory). Fiber ids are
/// 0..N−1 in output order (bundle by bundle). Randomness: see makeCrossSection (cross-section
/// index, seed index) — same options → bit-identical model. Returns an empty model when
/// validateBundleOptions(options, trajectory, trajectoryScale, pieces) is not empty (call it first
/// to get the message).
/// Pieces (docs/tissue-models.md §9): only the fibers of pieceRange(N, piece, pieces) of that order
/// are laid, with their global ids; every piece draws all cross-sections (seeds, radii: small), the
/// points only of its own fibers.
FiberModel generateBundle(const BundleOptions& options, const std::vector<Vec3>* trajectory,
  const std::vector<double>* trajectoryScale = nullptr, int piece = 0, int pieces = 1);

/// Non-fatal problems of valid options, docs/tissue-models.md §2 "Corners": a (resampled)
/// trajectory whose smallest radius of curvature is below BundleRadius·max σ, where inner fibers
/// fold over. Empty when none; else one message naming the radius, the point and the fix.
std::string bundleWarnings(const BundleOptions& options, const std::vector<Vec3>* trajectory,
  const std::vector<double>* trajectoryScale = nullptr);

} // namespace fiberpli
