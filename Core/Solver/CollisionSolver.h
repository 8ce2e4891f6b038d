/// CollisionSolver: moves fibers until no two capsules overlap, keeping segment lengths and
/// curvature within limits (docs/solver.md §3–§6, paper "Disentangling colliding fibers").
/// Deterministic: the output is bit-identical for any thread count (§4.4).
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"
#include "Parallel/Comm.h"
#include "Solver/ShapeControl.h"
#include "Solver/SolverState.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fiberpli
{

/// Parameters (docs/solver.md §7). Lengths in µm.
struct CollisionSolverOptions
{
  /// Mean segment length L̄ (µm); links are kept in [2/3, 4/3]·L̄ by split/merge (§5.1).
  /// 0 = automatic (2 × median point radius), < 0 = off (no split/merge). Default 2.
  double segmentLength = 2.0;
  /// Minimum circumradius of three consecutive points (µm); also enables the 60° vertex rule
  /// (§5.2). 0 = off. Default 0.
  double minCurvatureRadius = 0.0;
  /// Upper bound of move steps; the solver never runs longer (§6). Default 10000.
  int maxSteps = 10000;
  /// Push of a colliding pair per step, relative to the smallest radius of its four points
  /// (§4.1; split over the link's two points by the closest-point weights). Default 0.025 = the
  /// paper's 0.02 µm at r = 0.8 µm (fastPLI uses 0.05: fewer steps, looser packings, bench/README).
  double separationSpeed = 0.025;
  /// [ours] Push a colliding pair by at least this fraction of its overlap
  /// (ρa + ρb + gap − δ) per step instead of the fixed push alone. Resolves deep overlaps in fewer
  /// steps but packs looser in the cube benchmark (bench/README.md). 0 = off. Default 0.
  double overlapPush = 0.0;
  /// [ours] Fraction of a pair's push on a link end point that is also given to the next point
  /// outwards along the fiber (p_{k−1}, p_{k+2}): the fiber bends as a smooth bump instead of a
  /// kink, which fights the curvature rule much less (cube benchmark: 2–3× fewer steps with
  /// MinCurvatureRadius 4). 0 = only the link's two points (fastPLI). Default 0.5.
  double pushSpread = 0.5;
  /// Largest move of a point per step, relative to the smallest radius of all fibers (§4.2).
  /// Default 0.125 = the paper's 0.1 µm at r = 0.8 µm (fastPLI 0.2).
  double maxDisplacement = 0.125;
  /// [ours] Push boost for heavily overlapping input (docs/solver.md §4.1): when the first
  /// detection finds q > 6 colliding pairs per link (the paper's cube has 4–5; q ≈ 6 × the
  /// fibers' nominal volume fraction), pushes are multiplied by b = 1 + (PushBoost − 1)·min(1,
  /// (q − 6)/3) for the whole run, but a pair's push never exceeds half its overlap (nor falls
  /// below the unboosted push), and the move cap and the curvature steps grow by 1 + 0.6·(b − 1).
  /// On the 400-fiber two-population cube: half the steps at the same density over 20 inputs
  /// (bench/README.md). Input with q <= 6 is solved bit for bit as with 1 = off. Default 3.
  double pushBoost = 3.0;
  /// Velocity retention per step in [0, 1): 0 = no memory (paper, fastPLI default). Default 0.
  double drag = 0.0;
  /// [ours] The moves that keep velocity (drag > 0): the first dragSteps moves, then none, so
  /// that what momentum carried past contact settles (docs/solver.md §4.2); 0 = every move.
  /// Default 0.
  int dragSteps = 0;
  /// Threads for detection, pushes and shape control; 0 = all cores. Default 0.
  int numberOfThreads = 0;
  /// [ours] Extra clearance g >= 0 (µm): a pair collides iff δ < ρa + ρb + g. Default 0.
  double minimumGap = 0.0;
  /// What end points may do (§4.2). Default Perpendicular.
  EndPointRule endPoints = EndPointRule::Perpendicular;
  /// Stop early when the best collision count has not improved for this many steps; 0 = off.
  int stallSteps = 0;
  /// [ours] Periodic cell (off by default): capsule distances by the minimum-image convention;
  /// a fiber whose last point is its first point shifted by a lattice vector is closed (first and
  /// last point are one point, its first and last links are neighbours, closure kept exactly).
  PeriodicCell periodicCell;
  /// [ours] Radius growth (Lubachevsky–Stillinger style): capsules start at this fraction of their
  /// radii and grow by 0.2 % per step while the deepest overlap is below 5 % of the median radius,
  /// until full size; then the ordinary solve finishes. 1 = off; 0 = automatic (off: measured
  /// slower and looser than plain pushing on the periodic benchmarks, bench/README.md). The output
  /// always has the input radii. Default 0.
  double initialRadiusScale = 0.0;
  /// [ours] Keep every fiber's tortuosity (path length / end-to-end distance, over the closure in
  /// a periodic cell) at least at this value (docs/solver.md §5.3): pushes flatten undulating
  /// fibers, so shape control scales a fiber's deviations from its axis back up once its
  /// tortuosity falls 5 % of the excess below it. Straight fibers stay straight. 0 = off (any
  /// value <= 1), else in (1, 3]. Default 0.
  double tortuosity = 0.0;
  /// [ours] With tortuosity: the longest wavelength (µm) of the deviation the rule scales (§5.3),
  /// so that it restores the fibers' undulation without amplifying the long sweeps the pushes
  /// leave across a long fiber, which its neighbours must then follow (large dense cells solve in
  /// fewer steps and pack denser, bench/README.md "Realistic substrates"); about 1.5 × the
  /// source's UndulationWavelength. 0 = every mode (any fiber length). Default 0.
  double tortuosityWavelength = 0.0;
  /// [ours] With tortuosity: hold each bundle's mean solved tortuosity at it, from above too
  /// (docs/solver.md §5.5): the solve is repeated from the input with the bundle's undulation
  /// scaled by what the weave of a dense crossing added. Honoured by solveHoldingTortuosity
  /// (Solver/TortuosityHold.h); solveCollisions solves once. Default false.
  bool holdTortuosity = false;
  /// [ours] Beaded closed fibers keep their radius profile along their arc length (docs/solver.md
  /// §5.4, Solver/BeadProfile.h): every step each point takes the input profile at its arc
  /// fraction plus one phase per fiber, so pushes slide a fiber's beads along it as a whole
  /// instead of squeezing them into shorter links. Open fibers and constant radii are unaffected.
  /// Default false (points carry their radii).
  bool keepBeads = false;
  /// [ours] Skip the pairs of two links that are unchanged and collision-free since the last
  /// detection (docs/solver.md §3.4): detection then costs about the links still moving. Never
  /// changes the result (tests compare it on and off, serial and distributed). Core only.
  /// Default true.
  bool quietLinks = true;
};

/// Outcome of solveCollisions (field data of §9). error non-empty: nothing was done and the model
/// is unchanged; or, only when the colliding pairs outgrew their limit in the middle of a run (the
/// message says at which step), the model is in that step's state and must not be used. warnings:
/// recoverable oddities, one message each, with counts.
struct CollisionSolverResult : Status
{
  int steps = 0;              ///< move phases run
  std::size_t collisions = 0; ///< colliding capsule pairs in the output geometry
  bool solved = false;        ///< collisions == 0
  bool shapeOk = true;        ///< lengths and curvature within limits (last pass changed nothing)
  double maxOverlap = 0.0;    ///< max over colliding pairs of ρa + ρb + g − δ (µm), 0 if none
  double segmentLength = 0.0; ///< L̄ used (< 0 = off)
  std::size_t bestCollisions = 0; ///< smallest collision count seen ...
  int bestStep = 0;               ///< ... and the step it occurred
  /// Per output fiber, per output point: its position along the input fiber as a fractional input
  /// point index (3.5 = midpoint of input points 3 and 4), for interpolating other point arrays
  /// (floats: linear; integers: take floor). Points are moved, so this is the origin, not the
  /// place.
  std::vector<std::vector<double>> sourceIndex;
  double radiusScale = 1.0; ///< capsule size reached by radius growth (1 = full size)
  /// Fiber volume Σ π ρ² · link length over the periodic cell's volume (-1 without a cell).
  double volumeFraction = -1.0;
  /// Smallest surface gap δ − ρa − ρb over all pairs of capsules, at most minGapProbe (µm).
  double minGap = 0.0;
  double minGapProbe = 0.0; ///< pairs farther apart than this are not examined for minGap
  // Distributed runs (docs/solver.md §13; 0 otherwise): this rank's share and traffic.
  std::size_t rankFibers = 0; ///< fibers this rank owned at the end (before they went home)
  std::size_t peakRankPoints =
    0; ///< most it held in a step: owned points + halo links (one point each)
  std::size_t peakHaloLinks = 0; ///< most halo links (of other ranks' fibers) it held in a step
  std::size_t peakHeldLinks = 0; ///< most links (own or halo) it held for its pair tests in a step
  std::size_t peakPartners = 0;  ///< most ranks it exchanged links and pushes with in a step
  double haloBytesPerStep = 0.0; ///< bytes it sent per step, mean: links out and pushes back
  std::size_t migrations = 0;    ///< fibers that changed rank during the solve (all ranks)
  std::size_t testerRecuts =
    0; ///< re-cuts at equal pair work that moved a tester box cut (same on all ranks) ...
  double testerCutMove =
    0.0; ///< ... and the largest move of a cut, as a fraction of its axis' span
  /// [ours] Links of all detections of the run (this rank's held links) and, of them, the loud
  /// ones whose pairs were tested (docs/solver.md §3.4; all of them with quietLinks off).
  std::uint64_t detectedLinks = 0;
  std::uint64_t loudLinks = 0;
  /// [ours] Solves a tortuosity hold ran (solveHoldingTortuosity; 0: no hold).
  int tortuositySolves = 0;
};

/// Called after every move step with the step number (1, 2, …) and the current model (in a
/// distributed run the fibers this rank owns now), from the calling thread (e.g. to expose
/// iterations as time steps).
using StepObserver = std::function<void(int step, const FiberModel& model)>;

/// One solve driven step by step (solveCollisions is start, step until false, finish). Between
/// steps the caller may save state() with the model (checkpoint) and later resume() from them.
class CollisionSolverRun
{
public:
  /// The run works on `model` in place; progress and observer as for solveCollisions.
  /// comm (optional): distributed over its ranks (docs/solver.md §13), model = this rank's piece.
  CollisionSolverRun(FiberModel& model, const CollisionSolverOptions& options,
    const ProgressFn& progress = {}, const StepObserver& observer = {}, Comm* comm = nullptr);
  ~CollisionSolverRun();
  CollisionSolverRun(const CollisionSolverRun&) = delete;
  CollisionSolverRun& operator=(const CollisionSolverRun&) = delete;

  /// Checks options and model and prepares the fibers. False: finish() returns the error, the
  /// model is unchanged.
  bool start();
  /// How the ranks agree on a refused state (collective): given this rank's refusal ("" = its
  /// state fits), returns what this rank reports ("" = no rank refused).
  using ResumeAgreement = std::function<std::string(const std::string& localMisfit)>;
  /// Instead of start(): continue from a state saved with the model now in the run (same
  /// options). Returns "" or an error naming what does not match (then finish() returns it).
  /// Distributed, the ranks agree on it before any other collective: by default every rank
  /// reports the lowest refusing rank's message; `agree` lets a caller name its file first.
  std::string resume(const CollisionSolverState& saved, const ResumeAgreement& agree = {});
  /// One iteration (§6): shape control, detection, the stop rules, one move. False when the run
  /// has ended (solved, MaxSteps, StallSteps, abort or error): then call finish().
  bool step();
  /// The result (§9): final detection at full size, min gap, warnings. Called before step()
  /// returned false, it ends the run where it is (like an abort, without setting `aborted`).
  CollisionSolverResult finish();
  /// The state after the last step (valid after start() or resume()).
  const CollisionSolverState& state() const;
  /// Links of the last detection, and of them the loud ones whose pairs it tested (§3.4).
  std::size_t detectedLinks() const;
  std::size_t loudLinks() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Solves the model in place (docs/solver.md §6): fibers keep count, order, id and bundle;
/// first and last points stay first and last. Fibers with fewer than 2 points (after removing
/// repeated consecutive points) are left unchanged and excluded (warning). Errors (bad options,
/// mismatched radii, non-finite coordinates, radius <= 0) leave the model unchanged and name the
/// option or the fiber and point. Memory is bounded: the points the split can make must fit the
/// memory budget (Util/MemoryBudget.h), and the colliding pairs stored per step at most
/// packingPairBound (Solver/PairBound.h) and what the budget allows; stacks of identical fibers
/// and gaps that make every link collide are refused with a message saying so (counting the exact
/// copies). Never throws, never prints.
///
/// Distributed (comm non-null, collective, docs/solver.md §13): `model` is this rank's piece of
/// the whole model (the pieces in rank order are the whole model in its order). Every rank
/// returns its piece's fibers solved, and the same result fields (sourceIndex: of its piece) and
/// the same error; together the pieces are bit for bit what the serial solve of the whole model
/// gives, for any rank count and thread count. A stop requested on one rank stops all. The memory
/// guards are each rank's own (its budget against what it holds, never more than the serial run
/// holds): a distributed run may solve a model too large for one process, and refuses only what
/// the serial run would refuse too; the packing bound is the whole model's (§13).
CollisionSolverResult solveCollisions(FiberModel& model, const CollisionSolverOptions& options,
  const ProgressFn& progress = {}, const StepObserver& observer = {}, Comm* comm = nullptr);

/// Number of colliding capsule pairs (δ < ρa + ρb + minimumGap, same-fiber skip rule of §3.1) of
/// all fibers with >= 2 points; threads 0 = all cores. Same count the solver reports. Above the
/// solver's pair limit it stops counting and returns a number larger than that limit; in a
/// periodic cell too small for its links (PeriodicPairs refuses it) it returns SIZE_MAX, never 0.
std::size_t countCollisions(const FiberModel& model, double minimumGap = 0.0,
  int numberOfThreads = 0, const PeriodicCell& periodicCell = PeriodicCell{});

/// Σ π ρ_k² · |link k| over all links (ρ = capsule radius) divided by the cell volume, or without
/// a cell by the volume of the model's bounding box (points grown by their radii); 0 if empty.
/// Summed exactly (the same bits for any order or split); comm: over all ranks' fibers
/// (collective).
double cellVolumeFraction(const FiberModel& model, const PeriodicCell& cell, Comm* comm = nullptr);

/// Empty when the options are usable, else a message naming the option and its value.
std::string validateCollisionSolverOptions(const CollisionSolverOptions& options);

} // namespace fiberpli
