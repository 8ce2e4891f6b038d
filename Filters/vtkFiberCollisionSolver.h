/**
 * @class   vtkFiberCollisionSolver
 * @brief   moves fibers until no two capsules overlap, keeping segment lengths and curvature in
 * limits
 *
 * Input and output: fiber polydata (docs/data-contract.md §1). Every link (p_i, p_i+1) is a capsule
 * of radius max(r_i, r_i+1); the solver repeats detection (uniform grid), separation of colliding
 * links and shape control (links kept in [2/3, 4/3] · SegmentLength by splitting and merging,
 * points whose circumradius is below MinCurvatureRadius flattened) until no pair overlaps or
 * MaxSteps is reached (docs/solver.md §6). The output has the same fibers in the same order with
 * their fiber_id, bundle_id and other cell arrays; other point arrays follow inserted points
 * (floating-point arrays interpolated, integer arrays copied from the point before). Field data:
 * `steps`, `collisions` (pairs still overlapping), `solved` (1/0), `max_overlap` (µm),
 * `shape_ok`, `segment_length`, `min_gap` (smallest surface gap in µm, at most the median radius),
 * `radius_scale` (size reached by radius growth, 1 = full). If MaxSteps is reached the output
 * still comes, with a warning naming the collisions left.
 * Periodic input (field data `periodic_cell`, e.g. from FiberCubeSource with Periodic on):
 * distances by the minimum-image convention, fibers closed through the cell stay closed, and the
 * output carries `periodic_cell`. `volume_fraction` is nominal: the links' cylinder volume
 * Σ π ρ² · link length (overlaps not subtracted) over the periodic cell's volume, or without a cell
 * over the model's bounding box; FiberMetrics measures the covered fraction (docs/metrics.md §3).
 * The result is identical for any NumberOfThreads. With IterationsAsTime on, the steps are exposed
 * as time steps (0, TimeStepInterval, …, and the step the solve ended at, at most MaximumSnapshots
 * of them) so that ParaView's animation shows the fibers separating; the solve runs once, when the
 * pipeline information is updated, and is cached.
 */
#ifndef vtkFiberCollisionSolver_h
#define vtkFiberCollisionSolver_h

#include "FiberPLIFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory>

class vtkMultiProcessController;
namespace fiberpli
{
class Comm;
struct CollisionSolverOptions;
}
#include <string>

class FIBERPLIFILTERS_EXPORT vtkFiberCollisionSolver : public vtkPolyDataAlgorithm
{
public:
  static vtkFiberCollisionSolver* New();
  vtkTypeMacro(vtkFiberCollisionSolver, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Mean segment length in µm; link lengths are kept in [2/3, 4/3] of it by splitting and
   * merging. 0 = automatic (2 × median radius), negative = off (no splitting or merging).
   * Default is 2.
   */
  vtkSetMacro(SegmentLength, double);
  vtkGetMacro(SegmentLength, double);
  ///@}

  ///@{
  /**
   * Minimum radius of curvature in µm (circumradius of three consecutive points); 0 = off.
   * Default is 0.
   */
  vtkSetMacro(MinCurvatureRadius, double);
  vtkGetMacro(MinCurvatureRadius, double);
  ///@}

  ///@{
  /**
   * Maximum number of steps; the solver never runs longer. Default is 10000.
   */
  vtkSetMacro(MaxSteps, int);
  vtkGetMacro(MaxSteps, int);
  ///@}

  ///@{
  /**
   * Smallest push of a colliding pair per step, relative to the smallest radius of its points
   * (the paper's value at r = 0.8 µm, docs/solver.md §4.1), 0 to 1. Default is 0.025.
   */
  vtkSetMacro(SeparationSpeed, double);
  vtkGetMacro(SeparationSpeed, double);
  ///@}

  ///@{
  /**
   * Extra clearance in µm between capsules: a pair collides when its axis distance is below
   * ρa + ρb + MinimumGap. Default is 0 (the paper).
   */
  vtkSetMacro(MinimumGap, double);
  vtkGetMacro(MinimumGap, double);
  ///@}

  ///@{
  /**
   * Number of threads, 0 = all cores. The result does not depend on it. Default is 0.
   */
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Radius growth: capsules start at this fraction of their radii and grow to full size while
   * solving (dense targets); 1 = off; 0 = automatic, which is off for now (measured slower and
   * looser than plain pushing, bench/README.md). The output always has the input radii. Default 0.
   */
  vtkSetMacro(InitialRadiusScale, double);
  vtkGetMacro(InitialRadiusScale, double);
  ///@}

  ///@{
  /**
   * Push boost for heavily overlapping input, 1 to 4 (1 = off): when the first detection finds
   * more than 6 colliding pairs per link, pushes and the move cap grow for the whole run, a
   * pair's push up to half its overlap (docs/solver.md §4.1). About half the steps on such input
   * at the same density; input like the paper's cube is solved exactly as without it.
   * Default is 3.
   */
  vtkSetMacro(PushBoost, double);
  vtkGetMacro(PushBoost, double);
  ///@}

  ///@{
  /**
   * Momentum: the fraction of a point's last move it keeps, in [0, 1) (0 = none, as in the
   * paper), during the first DragSteps steps (0 = every step), after which the moves have no
   * memory and what momentum carried past contact settles (docs/solver.md §4.2). Large dense
   * beaded cells solve in a fraction of the steps with Drag 0.8 for 500 steps, at a slightly lower
   * volume fraction (momentum squeezes more beads). Defaults are 0 and 0.
   */
  vtkSetMacro(Drag, double);
  vtkGetMacro(Drag, double);
  vtkSetMacro(DragSteps, int);
  vtkGetMacro(DragSteps, int);
  ///@}

  ///@{
  /**
   * Largest move of a point per step, as a fraction of the smallest fiber radius of the input,
   * > 0 (docs/solver.md §4.2). Polydisperse radii with a small minimum (Gamma radii reach a
   * quarter of their mean) move by very little per step with the default; 0.4 solves the dense
   * periodic Gamma cells of docs/periodic-cells.md, "Polydisperse seeding". Default is 0.125.
   */
  vtkSetMacro(MaxDisplacement, double);
  vtkGetMacro(MaxDisplacement, double);
  ///@}

  ///@{
  /**
   * Tortuosity to keep (path length / end-to-end distance; over the lattice vector in a periodic
   * cell), 0 = off, else in (1, 3] (docs/solver.md §5.3). Pushes flatten undulating fibers; with a
   * target, shape control scales a fiber's deviations from its axis back up whenever its
   * tortuosity falls 5 % of the excess below the target, so the solved model keeps the requested
   * undulation. Straight fibers stay straight. Default is 0 (off).
   */
  vtkSetMacro(Tortuosity, double);
  vtkGetMacro(Tortuosity, double);
  ///@}

  ///@{
  /**
   * With Tortuosity: the longest wavelength (µm) of a fiber's deviation that the tortuosity rule
   * scales back up (docs/solver.md §5.3), >= 0. The rule then restores the undulation without
   * amplifying the long sweeps pushes leave across a long fiber, which its neighbours would have
   * to follow: large dense cells solve in fewer steps and pack denser. About 1.5 × the source's
   * UndulationWavelength. Default is 0 (every wavelength).
   */
  vtkSetMacro(TortuosityWavelength, double);
  vtkGetMacro(TortuosityWavelength, double);
  ///@}

  ///@{
  /**
   * With Tortuosity: hold each population's mean solved tortuosity at it, from above too
   * (docs/solver.md §5.5). The weave of a dense interwoven crossing adds 0.1–0.15 to the
   * undulation its fibers were made with; while a population is more than 5 % of the excess off
   * after a solve, the solve is repeated from the input with that population's undulation scaled
   * by what was measured (at most four solves, field data tortuosity_solves). Not with
   * IterationsAsTime or checkpoints. Default is off (one solve; the rule only lengthens).
   */
  vtkSetMacro(HoldTortuosity, bool);
  vtkGetMacro(HoldTortuosity, bool);
  vtkBooleanMacro(HoldTortuosity, bool);
  ///@}

  ///@{
  /**
   * Beaded fibers closed through a periodic cell keep their radius profile along their arc length
   * (docs/solver.md §5.4): every step a point takes the input profile at its arc fraction plus one
   * phase per fiber, so pushes slide a fiber's beads along it as a whole instead of squeezing them
   * into shorter links. Open fibers and constant radii are unaffected. Default is off.
   */
  vtkSetMacro(KeepBeads, bool);
  vtkGetMacro(KeepBeads, bool);
  vtkBooleanMacro(KeepBeads, bool);
  ///@}

  ///@{
  /**
   * Expose the solver's steps as time steps: 0, TimeStepInterval, 2 × TimeStepInterval, … and the
   * step the solve ended at, which is the last time step (the solve runs when the pipeline
   * information is updated, once, and is cached). Default is off.
   */
  vtkSetMacro(IterationsAsTime, bool);
  vtkGetMacro(IterationsAsTime, bool);
  vtkBooleanMacro(IterationsAsTime, bool);
  ///@}

  ///@{
  /**
   * Steps between two time steps when IterationsAsTime is on, >= 1. Default is 50.
   */
  vtkSetMacro(TimeStepInterval, int);
  vtkGetMacro(TimeStepInterval, int);
  ///@}

  ///@{
  /**
   * Most states kept for IterationsAsTime, >= 2 (memory: each is a copy of the fibers). When a
   * solve takes more, every second one is dropped and the interval doubles, so the time steps
   * still cover the whole solve. Default is 100.
   */
  vtkSetMacro(MaximumSnapshots, int);
  vtkGetMacro(MaximumSnapshots, int);
  ///@}

  ///@{
  /**
   * Checkpoint file of the solve (docs/solver.md §14): the complete state of the run, written
   * atomically every CheckpointInterval steps, read by ResumeFromCheckpoint. A distributed solve
   * (MPI) writes one file per rank, CheckpointFile.<rank>-of-<ranks>, and an error on one rank
   * fails all. Default empty.
   */
  vtkSetStdStringFromCharMacro(CheckpointFile);
  vtkGetCharFromStdStringMacro(CheckpointFile);
  ///@}

  ///@{
  /**
   * Write the checkpoint after every CheckpointInterval-th step, >= 0; 0 = never (default). A job
   * killed then loses at most this many steps.
   */
  vtkSetMacro(CheckpointInterval, int);
  vtkGetMacro(CheckpointInterval, int);
  ///@}

  ///@{
  /**
   * Continue from CheckpointFile (which must exist) instead of solving from the input: the result
   * is bit for bit the one of an uninterrupted run. The file must have been written for the same
   * input and the same options (NumberOfThreads may differ); else an error names the file and
   * what differs. Default off.
   */
  vtkSetMacro(ResumeFromCheckpoint, bool);
  vtkGetMacro(ResumeFromCheckpoint, bool);
  vtkBooleanMacro(ResumeFromCheckpoint, bool);
  ///@}

protected:
  vtkFiberCollisionSolver();
  ~vtkFiberCollisionSolver() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// Solves `input` unless the cache holds its solve or its failure: 1 solved, 0 error
  /// (reported on every call, computed once), -1 aborted (never cached). comm: `input` is this
  /// rank's piece of a distributed solve (collective; docs/solver.md §13).
  int Solve(vtkPolyData* input, fiberpli::Comm* comm = nullptr);

private:
  vtkFiberCollisionSolver(const vtkFiberCollisionSolver&) = delete;
  void operator=(const vtkFiberCollisionSolver&) = delete;

  double SegmentLength = 2.0;
  double MinCurvatureRadius = 0.0;
  int MaxSteps = 10000;
  double SeparationSpeed = 0.025;
  double MinimumGap = 0.0;
  int NumberOfThreads = 0;
  double InitialRadiusScale = 0.0;
  double PushBoost = 3.0;
  double Drag = 0.0;
  int DragSteps = 0;
  double MaxDisplacement = 0.125;
  double Tortuosity = 0.0;
  double TortuosityWavelength = 0.0;
  bool HoldTortuosity = false;
  bool KeepBeads = false;
  bool IterationsAsTime = false;
  int TimeStepInterval = 50;
  int MaximumSnapshots = 100;
  std::string CheckpointFile;
  int CheckpointInterval = 0;
  bool ResumeFromCheckpoint = false;

  struct Snapshots; // solved states per time step, cached for IterationsAsTime
  /// One solve into `cache`: "" or the error message (cache.result.aborted on an abort).
  std::string SolveInto(vtkPolyData* input, Snapshots& cache, fiberpli::Comm* comm);
  /// The checks of this rank's input and properties: "" or the error; fills cache.input and
  /// options.
  std::string CheckInput(
    vtkPolyData* input, Snapshots& cache, fiberpli::CollisionSolverOptions& options);
  /// The solve itself (after every rank passed CheckInput): "" or the error.
  std::string RunSolve(
    Snapshots& cache, const fiberpli::CollisionSolverOptions& options, fiberpli::Comm* comm);
  /// The controller of a distributed solve of this request (every rank one piece, IterationsAsTime
  /// off), else nullptr.
  vtkMultiProcessController* Distributed(vtkInformation* outInfo) const;
  std::unique_ptr<Snapshots> Cache;
};

#endif
