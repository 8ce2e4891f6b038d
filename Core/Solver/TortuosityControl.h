/// TortuosityControl: the solver's rule that keeps an undulating fiber undulating
/// (docs/solver.md §5.3). Pushes between fibers that undulate independently flatten their
/// undulations (a (40 µm)³ cell at 81 % with tortuosity 1.05 came out of the solve at 1.02); this
/// rule scales a fiber's deviations from its axis back up whenever its tortuosity falls below the
/// target, a little per step, so the solve ends with shapes that fit their neighbours and still
/// have the requested path length. Sequential inside one fiber, independent between fibers.
#pragma once

#include "Geometry/Vec3.h"
#include "Model/FiberModel.h"

#include <vector>

namespace fiberpli
{

/// Path length over end-to-end distance: over |closure| for a fiber closed through a periodic
/// cell (closure non-null), else over |p_{n−1} − p_0|. 1 for a straight fiber; 0 when the fiber
/// has fewer than 2 points or its ends coincide.
double fiberTortuosity(const Fiber& f, const Vec3* closure = nullptr);

/// A fiber's deviation from its axis (docs/solver.md §5.3): the axis is the chord through the end
/// points of an open fiber or the line along the closure through the points' mean of a closed
/// one; per point its position t along the axis (from the first point) and its deviation, the
/// component of its offset from the axis across it. The fiber must have >= 2 points and a chord
/// (or closure) of non-zero length.
struct FiberDeviation
{
  Vec3 axis;         ///< unit vector along the chord or closure
  double span = 0.0; ///< |chord| or |closure|
  std::vector<double> t;
  std::vector<Vec3> deviation;
};
FiberDeviation fiberDeviation(const Fiber& f, const Vec3* closure = nullptr);

/// When the fiber's tortuosity τ is below target − tolerance, scales the smooth part of its
/// deviation from its axis up (docs/solver.md §5.3): the axis is the chord through the end points
/// of an open fiber (they stay) or the line along the closure through the points' mean of a closed
/// one (it stays closed, exactly); the smooth part is the deviation's Fourier series along the axis
/// down to wavelength minWavelength (periodic over the closure, a sine series between open ends;
/// minWavelength <= 0: five mean links); it is added (k − 1) times with k = √((target − 1)/(τ − 1))
/// (small slopes: τ − 1 grows with the square of the deviations), limited so that no point moves
/// more than maxMove. maxWavelength > 0: only the modes of wavelength at most this are scaled
/// (the bends of one undulation, not the long sweeps the pushes leave across the fiber, which its
/// neighbours must follow); 0 = every mode down from the fiber's length. A straight fiber has
/// nothing to scale and stays. target <= 1 disables it. Returns true when it moved points.
bool controlTortuosity(Fiber& f, double target, double tolerance, double maxMove,
  double minWavelength, const Vec3* closure = nullptr, double maxWavelength = 0.0);

} // namespace fiberpli
