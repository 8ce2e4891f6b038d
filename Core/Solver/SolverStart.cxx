// CollisionSolverRun: construction, start and resume (docs/solver.md §6, §14).
#include "Solver/SolverRun.h"

#include "Solver/SolverChecks.h"
#include "Util/NumberFormat.h"
#include "Util/Threads.h"

#include <numeric>

namespace fiberpli
{

CollisionSolverRun::CollisionSolverRun(FiberModel& model, const CollisionSolverOptions& options,
  const ProgressFn& progress, const StepObserver& observer, Comm* comm)
  : impl_(std::make_unique<Impl>(model, options, progress, observer, comm))
{
}

CollisionSolverRun::~CollisionSolverRun() = default;

const CollisionSolverState& CollisionSolverRun::state() const
{
  return impl_->s.st_;
}

std::size_t CollisionSolverRun::detectedLinks() const
{
  return impl_->s.lastDetectedLinks_;
}

std::size_t CollisionSolverRun::loudLinks() const
{
  return impl_->s.lastLoudLinks_;
}

bool CollisionSolverRun::start()
{
  Impl& r = *impl_;
  SolverEngine& s = r.s;
  const CollisionSolverOptions& o = r.options;
  FiberModel& model = r.model;
  CollisionSolverState& st = s.st_;
  const std::size_t nf = model.fibers.size();
  std::int64_t first = 0; // global index of this piece's first fiber: pieces in rank order
  if (s.comm_)
  {
    r.input = model; // before any failure path: fail() restores it
    std::vector<std::int64_t> counts(static_cast<std::size_t>(s.comm_->size()), 0);
    counts[static_cast<std::size_t>(s.comm_->rank())] = static_cast<std::int64_t>(nf);
    s.comm_->sum(counts);
    first = std::accumulate(counts.begin(), counts.begin() + s.comm_->rank(), std::int64_t{ 0 });
  }
  st.global.resize(nf);
  std::iota(st.global.begin(), st.global.end(), first);
  std::string error = validateCollisionSolverOptions(o);
  if (error.empty())
  {
    error = validatePiece(model, st.global);
  }
  if (r.fail(error))
  {
    return false;
  }
  s.threads_ = resolveThreadCount(o.numberOfThreads);
  st.points.assign(nf, FiberPointState{});
  st.active.assign(nf, 1);
  st.closed.assign(nf, 0);
  st.closure.assign(nf, Vec3{});
  st.home.assign(nf, s.comm_ ? s.comm_->rank() : 0);
  if (s.comm_)
  {
    s.startDistribution();
  }
  // Before anything touches the model: a refused run leaves it unchanged.
  st.segmentLength = resolveSegmentLength(s, o);
  error = checkMemory(s);
  if (error.empty())
  {
    error = checkStacksAndGap(model, o, s.comm_);
  }
  if (error.empty())
  {
    error = checkCoordinateResolution(model, st.segmentLength); // Solver/ShapeControl.h
  }
  if (r.fail(error))
  {
    return false;
  }
  if (!s.periodic())
  {
    // Stacks of nearly identical fibers are refused on the input as it came, before the model
    // changes (the limit is checked again at every step; periodic runs restore the input).
    const bool found = s.detect(nullptr, false, true);
    if (r.failAgreed(
          found ? std::string() : s.detectError_)) // detect() agrees on it over the ranks
    {
      return false;
    }
  }
  // A periodic cell too small for the links is only known once they are built: keep the input.
  if (s.periodic() && !s.comm_)
  {
    r.input = model;
  }
  prepareFibers(s, st.warnings);
  prepareClosures(s);
  configure(s, st.warnings);
  st.scale = initialScale(o);
  st.growthTolerance = 0.05 * s.median();
  s.resetTraffic();
  r.phase = Impl::Phase::Running;
  return true;
}

// What resume(saved) refuses, on this rank alone (not collective).
std::string CollisionSolverRun::Impl::misfit(const CollisionSolverState& saved) const
{
  const Impl& r = *this;
  std::string error = validateCollisionSolverOptions(r.options);
  const std::size_t nf = r.model.fibers.size();
  const bool serialState = saved.global.size() != nf || saved.home.size() != nf;
  if (error.empty() && serialState && r.s.comm_ && r.s.comm_->size() > 1)
  {
    // Every rank would number its fibers 0..n-1: the global indices would collide.
    error = "the saved solver state has no global fiber indices (a serial state): it cannot "
            "resume a run over " +
      formatNumber(r.s.comm_->size()) + " ranks";
  }
  if (error.empty() &&
    (saved.points.size() != nf || saved.active.size() != nf || saved.closed.size() != nf ||
      saved.closure.size() != nf))
  {
    error = "the saved solver state is for " + formatNumber(saved.points.size()) +
      " fibers, the model has " + formatNumber(nf);
  }
  for (std::size_t f = 0; error.empty() && f < nf; ++f)
  {
    const std::size_t n = r.model.fibers[f].size();
    if (saved.points[f].velocity.size() != n || saved.points[f].source.size() != n)
    {
      error = "the saved solver state of fiber " + formatNumber(f) + " has " +
        formatNumber(saved.points[f].velocity.size()) + " points, the model " + formatNumber(n);
    }
  }
  if (error.empty())
  {
    error = validatePiece(r.model, serialState ? std::vector<std::int64_t>{} : saved.global);
  }
  return error;
}

std::string CollisionSolverRun::resume(
  const CollisionSolverState& saved, const ResumeAgreement& agree)
{
  Impl& r = *impl_;
  r.phase = Impl::Phase::Failed;
  if (r.s.periodic() || r.s.comm_)
  {
    r.input = r.model; // before any failure path: fail() restores it
  }
  // Agreed over the ranks before any other collective: a rank refusing its state alone must not
  // leave the others waiting in the distribution below.
  const std::string misfit = r.misfit(saved);
  if (agree ? r.failAgreed(agree(misfit)) : r.fail(misfit))
  {
    return r.result.error;
  }
  const std::size_t nf = r.model.fibers.size();
  const bool serialState = saved.global.size() != nf || saved.home.size() != nf;
  r.s.threads_ = resolveThreadCount(r.options.numberOfThreads);
  r.s.st_ = saved;
  if (serialState) // one rank only (refused above otherwise)
  {
    r.s.st_.global.resize(nf);
    std::iota(r.s.st_.global.begin(), r.s.st_.global.end(), std::int64_t{ 0 });
    r.s.st_.home.assign(nf, 0);
  }
  if (r.s.comm_)
  {
    r.s.startDistribution(); // any boxes do: the result does not depend on who owns what
  }
  r.phase = Impl::Phase::Running;
  return {};
}

} // namespace fiberpli
