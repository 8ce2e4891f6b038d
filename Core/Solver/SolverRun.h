/// CollisionSolverRun::Impl: a run's phase, its result and the engine it drives (internal to
/// Core/Solver). SolverStart.cxx starts or resumes a run, SolverStep.cxx steps and finishes it.
#pragma once

#include "Solver/CollisionSolver.h"
#include "Solver/SolverEngine.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

struct CollisionSolverRun::Impl
{
  Impl(FiberModel& m, const CollisionSolverOptions& o, const ProgressFn& p, const StepObserver& ob,
    Comm* c)
    : model(m)
    , options(o)
    , progress(p)
    , observer(ob)
    , s(m, options, 1)
  {
    s.comm_ = c;
  }

  enum class Phase
  {
    Created, ///< start() or resume() not called yet
    Running, ///< step() goes on
    Ended,   ///< the loop stopped: finish() makes the result
    Failed,  ///< result.error is set and final
    Finished ///< finish() made the result
  };

  FiberModel& model;
  const CollisionSolverOptions options;
  ProgressFn progress;
  StepObserver observer;
  SolverEngine s;
  FiberModel
    input; // periodic or distributed runs: the model before preparation, restored on an error
  CollisionSolverResult result;
  Phase phase = Phase::Created;

  // The callback never sees progress go back. A stop on one rank stops all; distributed, the
  // same sum tells (with leaving non-null) whether any rank has fibers to migrate.
  bool report(double fraction, std::int64_t* leaving = nullptr)
  {
    s.st_.reported = std::max(s.st_.reported, fraction);
    const bool go = reportProgress(progress, s.st_.reported);
    if (!s.comm_)
    {
      return go;
    }
    std::vector<std::int64_t> v{ go ? 0 : 1, leaving ? *leaving : 0 };
    s.comm_->sum(v);
    if (leaving)
    {
      *leaving = v[1];
    }
    return v[0] == 0;
  }
  // Errors of one rank reach all (distributed runs restore the input piece).
  bool fail(const std::string& error)
  {
    return failAgreed(s.comm_ ? agreeOnError(*s.comm_, error) : error);
  }
  // The same for an error the ranks have agreed on already.
  bool failAgreed(const std::string& error)
  {
    if (error.empty())
    {
      return false;
    }
    if (s.comm_)
    {
      model = input;
    }
    result = CollisionSolverResult{};
    result.error = error;
    phase = Phase::Failed;
    return true;
  }
  std::string misfit(const CollisionSolverState& saved) const;
  double stepShareAfter(int steps) const
  {
    return options.maxSteps > 0 ? std::min(1.0, static_cast<double>(steps) / options.maxSteps)
                                : 1.0;
  }
  // The pair limit (or a periodic cell too small for the links) met in the middle of a run.
  void failDetection(const std::string& where)
  {
    if (s.periodic() || s.comm_)
    {
      model = input; // the cell is too small for the links, or distributed: keep the input
      result = CollisionSolverResult{};
      result.error = s.detectError_ + (s.periodic() ? std::string() : where); // the serial text
    }
    else // the model is in this step's state
    {
      takeState();
      result.error = s.detectError_ + where;
    }
    phase = Phase::Failed;
  }
  // Distributed: every fiber back to the rank whose input piece held it; this rank's figures.
  void goHome()
  {
    RankFibers fibers = s.rankFibers();
    result.rankFibers = fibers.size();
    redistribute(fibers, s.st_.home, *s.comm_);
    result.migrations =
      static_cast<std::size_t>(sumOverRanks(static_cast<std::int64_t>(s.migrations_)));
    result.haloBytesPerStep =
      s.haloExchanges_ > 0 ? static_cast<double>(s.haloBytes_) / s.haloExchanges_ : 0.0;
    result.peakHaloLinks = s.peakHaloLinks_;
    result.peakRankPoints = s.peakRankPoints_;
    result.peakHeldLinks = s.peakHeldLinks_;
    result.peakPartners = s.peakPartners_;
    result.testerRecuts = s.testerRecuts_;
    result.testerCutMove = s.testerCutMove_;
  }
  std::int64_t sumOverRanks(std::int64_t v)
  {
    std::vector<std::int64_t> x{ v };
    s.comm_->sum(x);
    return x[0];
  }
  // The result fields that are the state's (also on an error in the middle of a run).
  void takeState()
  {
    const CollisionSolverState& st = s.st_;
    result.steps = st.steps;
    result.segmentLength = st.segmentLength;
    result.bestCollisions = st.bestCollisions;
    result.bestStep = st.bestStep;
    result.warnings = st.warnings;
  }
};

} // namespace fiberpli
