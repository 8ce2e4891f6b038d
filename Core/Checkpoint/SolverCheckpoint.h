/// SolverCheckpoint: a collision solve that survives being killed (docs/solver.md §14). Every N
/// steps the complete state of the run — the model as it is, CollisionSolverState, the options
/// and a fingerprint of the input — goes to one file, replaced atomically; a run resumed from it
/// ends bit for bit where the uninterrupted run ends.
#pragma once

#include "Model/FiberModel.h"
#include "Parallel/Comm.h"
#include "Solver/CollisionSolver.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

/// FNV-1a over every fiber's id, bundle, points and radii: the input a checkpoint belongs to.
std::uint64_t modelFingerprint(const FiberModel& model);

/// Writes model + state (after state.steps steps), the options and the input's fingerprint to
/// path atomically (IO/AtomicFile.h): a failed or killed write leaves the previous file. Returns
/// "" or a message naming the file.
std::string writeSolverCheckpoint(const std::string& path, const FiberModel& model,
  const CollisionSolverState& state, const CollisionSolverOptions& options,
  std::uint64_t inputFingerprint);

/// Reads a checkpoint written for `options` (all but numberOfThreads, which does not change the
/// result) and the input of fingerprint `inputFingerprint`. Returns "" and fills model and
/// state, or a message naming the file and what is wrong: not a checkpoint, damaged (checksum),
/// another version, an option that differs (name, saved and given value), another input.
std::string readSolverCheckpoint(const std::string& path, const CollisionSolverOptions& options,
  std::uint64_t inputFingerprint, FiberModel& model, CollisionSolverState& state);

/// How solveWithCheckpoints saves and resumes.
struct CheckpointOptions
{
  std::string path;    ///< the checkpoint file
  int interval = 0;    ///< write after every interval-th move step; 0 = never
  bool resume = false; ///< start from the file (it must exist) instead of from the model
};

/// The file a rank writes: `path` itself without comm (or with one rank), else
/// "<path>.<rank>-of-<ranks>", one file per rank (its owned fibers and their state).
std::string checkpointPath(const std::string& path, const Comm* comm);

/// "<file>.prev": the generation before `file` (solveWithCheckpoints keeps it when it writes).
std::string previousCheckpointPath(const std::string& file);

/// solveCollisions with checkpoints: with resume the model is replaced by the file's (checked
/// against options and the given model's fingerprint) and the run continues from its state.
/// Every write first keeps the file as previousCheckpointPath; resume reads both and takes the
/// newest that reads. A checkpoint that cannot be read or written is result.error (naming the
/// file); the model is then unchanged (read, or any error of a resumed run) or in the state of
/// the failed write's step (write, not resumed). With comm (distributed, collective) every rank
/// writes and reads its own files (checkpointPath) and the ranks agree after every read and
/// write: an error on one rank is an error on all. Resume takes the newest step every rank
/// holds and checks that the pieces hold each fiber of the model exactly once; else every rank
/// fails, naming the files and their steps.
CollisionSolverResult solveWithCheckpoints(FiberModel& model, const CollisionSolverOptions& options,
  const CheckpointOptions& checkpoint, const ProgressFn& progress = {},
  const StepObserver& observer = {}, Comm* comm = nullptr);

} // namespace fiberpli
