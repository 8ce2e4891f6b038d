// Collision solver benchmark (bench/README.md): the workloads of bench/README.md on cubes
// from generateCube (seed 42), timed against the fastPLI reference figures (bench/README.md).
// Usage: fiberpli_solver_bench
// [quick-a|quick-b|quick-c|cube-a|cube-b|cube-c|dense-b|chiasm-fat|quick|cube|dense|all]...
//        [--threads 1,2] [--cap SECONDS] [--max-steps N] [--samples N] (MC samples for phi)
//        [--overlap-push X] [--separation-speed X] [--max-displacement X] [--drag X] [--push-spread
//        X]
//        [--push-boost X] [--end-points perpendicular|free|fixed] (solver knobs)
//        [--seed N] (of the generated cube, 42) [--trace N] (collisions every N steps, to stderr)
#include "BenchUtil.h"
#include "CapsuleCells.h"
#include "PushOverrides.h"
#include "Solver/CollisionSolver.h"
#include "Tissue/BundleGenerator.h"
#include "Tissue/CubeGenerator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace fiberpli;

namespace
{
struct Workload
{
  const char* name;
  int populations;
  int fibers;
  double
    referenceSeconds; // fastPLI, 1 thread (bench/README.md); cube-b hit the 540 s cap; 0 = unknown
  double edge = 0.0;  // cube edge (µm); 0 = √3·30·√(fibers/1000), the paper's fiber density
  double chiasmRadius =
    0.0; // > 0: not a cube but FiberBundleSource's Chiasm with this fiber radius
};

const Workload kWorkloads[] = { { "quick-a", 1, 200, 3.1 }, { "quick-b", 2, 200, 10.6 },
  { "quick-c", 3, 200, 9.0 }, { "cube-a", 1, 1000, 76.9 }, { "cube-b", 2, 1000, 540.0 },
  { "cube-c", 3, 1000, 491.1 },
  // Twice the quick cube's fibers in its cube: heavily overlapping input (fastPLI: 1 756 steps).
  { "dense-b", 2, 400, 0.0, 23.24 },
  // The examples' chiasm (Examples/bundle_chiasm.py: R 10 µm, fiber spacing 2 µm) with its fibers
  // fattened from r 0.8 to 1.2 µm, so that every fiber overlaps its six neighbours by 0.4 µm and
  // the nerves overlap where they cross (fastPLI's 399 steps were measured on its own chiasm
  // model).
  { "chiasm-fat", 0, 0, 0.0, 0.0, 1.2 } };

// The model of a workload, its central cube's edge (for φ) and its shape control.
FiberModel workloadModel(
  const Workload& w, unsigned seed, double& centralEdge, double& minCurvatureRadius)
{
  if (w.chiasmRadius > 0.0)
  {
    BundleOptions b;
    b.shape = BundleShape::Chiasm;
    b.fiberRadius = w.chiasmRadius;
    b.seed = seed;
    centralEdge = b.bundleRadius; // a cube inside both nerves where they cross
    minCurvatureRadius = 0.0;     // as in the examples
    return generateBundle(b, nullptr);
  }
  CubeOptions c;
  c.populations = w.populations;
  c.numberOfFibers = w.fibers;
  c.edgeLength = w.edge > 0.0 ? w.edge : std::sqrt(3.0) * 30.0 * std::sqrt(w.fibers / 1000.0);
  c.fiberRadius = 0.8;
  c.segmentLength = 2.0;
  c.displacement = 0.5;
  c.seed = seed;
  centralEdge = c.edgeLength / std::sqrt(3.0);
  minCurvatureRadius = 4.0;
  return generateCube(c);
}

// 1-minute load average of the machine (includes this process): a rough noise indicator.
double loadAverage()
{
  double l = -1.0;
  if (FILE* f = std::fopen("/proc/loadavg", "r"))
  {
    if (std::fscanf(f, "%lf", &l) != 1)
      l = -1.0;
    std::fclose(f);
  }
  return l;
}

// Volume fraction of the central cube (edge e, centred at 0) covered by capsules of radius
// max(r_i, r_i+1): Monte Carlo with 'samples' uniform points through a coarse cell list.
double volumeFraction(const FiberModel& m, double e, long samples)
{
  const double cell = 2.0;
  bench::CapsuleCells cells(0.5 * e, static_cast<int>(std::ceil(e / cell)), cell);
  for (const Fiber& f : m.fibers)
  {
    for (std::size_t k = 0; k + 1 < f.points.size(); ++k)
    {
      cells.add(
        bench::BenchCapsule{ f.points[k], f.points[k + 1], std::max(f.radii[k], f.radii[k + 1]) });
    }
  }
  return cells.hitFraction(samples);
}
} // namespace

int main(int argc, char** argv)
{
  std::vector<const Workload*> selected;
  std::vector<int> threads{ 1, 2 };
  double cap = 540.0;
  int maxSteps = 100000;
  bench::PushOverrides push;
  int endPoints = -1;
  double pushSpread = -1.0;
  long samples = 1000000;
  int trace = 0;
  unsigned seed = 42;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc)
    {
      threads.clear();
      for (char* t = std::strtok(argv[++i], ","); t; t = std::strtok(nullptr, ","))
        threads.push_back(std::atoi(t));
    }
    else if (a == "--cap" && i + 1 < argc)
      cap = std::atof(argv[++i]);
    else if (a == "--max-steps" && i + 1 < argc)
      maxSteps = std::atoi(argv[++i]);
    else if (a == "--overlap-push" && i + 1 < argc)
      push.overlapPush = std::atof(argv[++i]);
    else if (a == "--separation-speed" && i + 1 < argc)
      push.separationSpeed = std::atof(argv[++i]);
    else if (a == "--max-displacement" && i + 1 < argc)
      push.maxDisplacement = std::atof(argv[++i]);
    else if (a == "--end-points" && i + 1 < argc)
    {
      const std::string e = argv[++i];
      endPoints = e == "free" ? 1 : (e == "fixed" ? 2 : 0);
    }
    else if (a == "--push-spread" && i + 1 < argc)
      pushSpread = std::atof(argv[++i]);
    else if (a == "--push-boost" && i + 1 < argc)
      push.pushBoost = std::atof(argv[++i]);
    else if (a == "--drag" && i + 1 < argc)
      push.drag = std::atof(argv[++i]);
    else if (a == "--seed" && i + 1 < argc)
      seed = static_cast<unsigned>(std::atol(argv[++i]));
    else if (a == "--trace" && i + 1 < argc)
      trace = std::atoi(argv[++i]);
    else if (a == "--samples" && i + 1 < argc)
      samples = std::atol(argv[++i]);
    else
    {
      bool found = false;
      for (const Workload& w : kWorkloads)
      {
        const std::string n = w.name;
        if (a == n || a == "all" || (a == "quick" && n.rfind("quick", 0) == 0) ||
          (a == "cube" && n.rfind("cube", 0) == 0) || (a == "dense" && n.rfind("dense", 0) == 0))
        {
          selected.push_back(&w);
          found = true;
        }
      }
      if (!found)
      {
        std::fprintf(stderr, "unknown argument '%s'\n", a.c_str());
        return 2;
      }
    }
  }
  if (selected.empty())
  {
    for (int k = 0; k < 3; ++k)
      selected.push_back(&kWorkloads[k]);
  }

  std::printf("| workload | fibers | threads | steps | solve [s] | CPU [s] | ref 1-thread [s] | "
              "ratio | load after | peak RSS "
              "[MB] | solved | collisions left | links | phi (MC) | central cube [um] | input "
              "pairs per link |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Workload* w : selected)
  {
    for (int t : threads)
    {
      double edge = 0.0;
      CollisionSolverOptions o;
      FiberModel m = workloadModel(*w, seed, edge, o.minCurvatureRadius);
      // Colliding pairs per link of the input: what PushBoost's gate sees (docs/solver.md §4.1).
      const double q = static_cast<double>(countCollisions(m, 0.0, t)) /
        static_cast<double>(std::max<std::size_t>(1, m.numberOfLinks()));
      o.segmentLength = 2.0;
      o.maxSteps = maxSteps;
      o.numberOfThreads = t;
      push.apply(o);
      if (pushSpread >= 0.0)
        o.pushSpread = pushSpread;
      if (endPoints >= 0)
        o.endPoints = static_cast<EndPointRule>(endPoints);
      const double cpu0 = bench::cpuSeconds();
      const auto t0 = std::chrono::steady_clock::now();
      auto elapsed = [&]()
      { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
      const CollisionSolverResult r = solveCollisions(
        m, o, [&](double) { return elapsed() < cap; },
        [&](int step, const FiberModel& now)
        {
          if (trace > 0 && step % trace == 0)
            std::fprintf(
              stderr, "%s step %d: %zu collisions\n", w->name, step, countCollisions(now, 0.0, t));
        });
      const double seconds = elapsed();
      const double cpu = bench::cpuSeconds() - cpu0;
      const double load = loadAverage();
      if (!r.error.empty())
      {
        std::printf("%s: error %s\n", w->name, r.error.c_str());
        continue;
      }
      const double phi = volumeFraction(m, edge, samples);
      std::printf("| %s | %zu | %d | %d | %.2f | %.2f | %.1f | %.3f | %.1f | %.0f | %d%s | %zu | "
                  "%zu | %.1f %% | %.2f | %.2f |\n",
        w->name, m.fibers.size(), t, r.steps, seconds, cpu, w->referenceSeconds,
        w->referenceSeconds > 0.0 ? seconds / w->referenceSeconds : 0.0, load, bench::peakRssMB(),
        r.solved ? 1 : 0, r.aborted ? " (cap)" : "", r.collisions, m.numberOfLinks(), 100.0 * phi,
        edge, q);
      std::fflush(stdout);
    }
  }
  return 0;
}
