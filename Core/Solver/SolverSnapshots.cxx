#include "Solver/SolverSnapshots.h"

#include <algorithm>
#include <utility>

namespace fiberpli
{

void SolverSnapshots::start(const FiberModel& input, int interval, std::size_t capacity)
{
  models.assign(1, input);
  steps.assign(1, 0);
  interval_ = interval;
  capacity_ = capacity;
}

void SolverSnapshots::observe(int step, const FiberModel& current)
{
  if (step % interval_ != 0)
  {
    return;
  }
  if (models.size() >= capacity_) // full: keep steps 0, 2Δ, 4Δ, … and double Δ
  {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < models.size(); i += 2, ++kept)
    {
      if (kept != i) // a vector moved onto itself is left empty
      {
        models[kept] = std::move(models[i]);
        steps[kept] = steps[i];
      }
    }
    models.resize(kept);
    steps.resize(kept);
    interval_ *= 2;
    if (step % interval_ != 0)
    {
      return;
    }
  }
  models.push_back(current);
  steps.push_back(step);
}

void SolverSnapshots::finish(FiberModel&& final, int step)
{
  // A snapshot of the final step was taken before that step's last shape control: replace it.
  if (!steps.empty() && steps.back() == step)
  {
    models.pop_back();
    steps.pop_back();
  }
  models.push_back(std::move(final));
  steps.push_back(step);
}

std::size_t SolverSnapshots::atTime(double t) const
{
  const auto after = std::upper_bound(steps.begin(), steps.end(), t + 1e-9,
    [](double time, int step) { return time < static_cast<double>(step); });
  return after == steps.begin() ? 0 : static_cast<std::size_t>(after - steps.begin()) - 1;
}

} // namespace fiberpli
