// The millimetre section's solve on the Core alone (bench/README.md "A millimetre section"):
// the same field, FiberFieldSource's fibers and FiberCollisionSolver's options as
// bench/section_bench.py, without ParaView, so that the solve can be profiled (perf) and its
// output compared bit for bit between builds (the hash of the solved points and radii).
// --ranks R solves it distributed (docs/solver.md §13) on R thread ranks
// (Core/Testing/ThreadComm.h) and prints each rank's CPU seconds outside the collectives and the
// critical path: the sum over the stretches between two collectives of the slowest rank's CPU (the
// wall time with free, instant communication and a core per rank). Usage:
// fiberpli_section_solve_bench [--size 250] [--thickness 60] [--threads 2] [--ranks 1]
//        [--max-steps N] [--every N] (a line of timings every N steps, 100) [--no-quiet]
//        [--seed-candidates M] (FiberFieldSource's SeedCandidates, 1) [--stretches FILE]
// (--stretches: a line per stretch, each rank's CPU seconds, then the collective that ends it)
// --ranks takes a list (--ranks 1,2,1,2): the traced fibers are solved once per entry, one after
// the other, each from the same traced model, so that the runs to compare are taken in the same
// minutes without tracing again (each distributed run's stretches go to FILE.<i>, i its place in
// the list; the peak RSS printed is the process's, over the runs so far). An entry d1 runs the
// distributed solver on one rank: what its code costs without a halo or a partner.
#include "BenchSolve.h"
#include "Field/FieldFibers.h"
#include "ThreadComm.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <numeric>
#include <string>
#include <vector>

using namespace fiberpli;

namespace
{
// The orientation fields of section_bench.py's make_field: population A along x on sinusoids
// (amplitude 25 µm, wavelength 400 µm), population B along y in a band of band·L across the
// middle; 10 µm grid.
std::vector<OrientationField> sectionFields(double L, double T, double band)
{
  const double h = 10.0;
  const int n = static_cast<int>(std::lround(L / h)) + 1;
  const int nz = std::max(2, static_cast<int>(std::lround(T / h)) + 1);
  OrientationField a;
  a.origin = { 0.0, 0.0, 0.0 };
  a.spacing = { L / (n - 1), L / (n - 1), T / (nz - 1) };
  a.dimensions = { n, n, nz };
  a.vectors.resize(a.size());
  OrientationField b = a;
  const double amplitude = 25.0, k = 2.0 * M_PI / 400.0;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        const double px = L * x / (n - 1); // numpy's linspace(0, L, n)
        a.vectors[a.index(x, y, z)] = { 1.0, amplitude * k * std::cos(k * px), 0.0 };
        b.vectors[b.index(x, y, z)] =
          std::fabs(px - 0.5 * L) < 0.5 * band * L ? Vec3{ 0.0, 1.0, 0.0 } : Vec3{};
      }
  normalizeOrientationField(a);
  normalizeOrientationField(b);
  return { a, b };
}

// CPU seconds of the calling thread.
double threadCpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// A thread rank that notes its CPU seconds between two collective calls (every call is
// collective, so the i-th stretch of every rank ends at the same collective).
class TimedComm final : public Comm
{
public:
  explicit TimedComm(Comm& inner)
    : inner_(inner)
    , last_(threadCpuSeconds())
  {
  }
  int rank() const override { return inner_.rank(); }
  int size() const override { return inner_.size(); }
  void sum(std::vector<std::int64_t>& v) override
  {
    note("sum");
    inner_.sum(v);
    last_ = threadCpuSeconds();
  }
  void max(std::vector<double>& v) override
  {
    note("max");
    inner_.max(v);
    last_ = threadCpuSeconds();
  }
  std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) override
  {
    note("exchange");
    std::vector<std::vector<char>> in = inner_.exchange(send);
    last_ = threadCpuSeconds();
    return in;
  }
  std::vector<std::vector<char>> exchangeWith(
    const std::vector<int>& partners, const std::vector<std::vector<char>>& send) override
  {
    note("exchangeWith");
    std::vector<std::vector<char>> in = inner_.exchangeWith(partners, send);
    last_ = threadCpuSeconds();
    return in;
  }
  // Per stretch, the collective that ends it.
  const std::vector<const char*>& kinds() const { return kinds_; }
  // The stretches, the last one (after the last collective) included.
  std::vector<double> finish()
  {
    note("end");
    return stretches_;
  }

private:
  // kind: the collective that ends the stretch.
  void note(const char* kind)
  {
    stretches_.push_back(threadCpuSeconds() - last_);
    kinds_.push_back(kind);
  }
  Comm& inner_;
  double last_;
  std::vector<double> stretches_;
  std::vector<const char*> kinds_;
};
} // namespace

int main(int argc, char** argv)
{
  double L = 250.0, T = 60.0, fa = 0.57, fb = 0.10, band = 0.3;
  int threads = 2, maxSteps = 20000, every = 100, seedCandidates = 1;
  std::vector<int> rankList{ 1 };
  std::string stretchFile;
  bool quiet = true;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const auto next = [&]() { return i + 1 < argc ? argv[++i] : "0"; };
    if (a == "--size")
      L = std::atof(next());
    else if (a == "--thickness")
      T = std::atof(next());
    else if (a == "--threads")
      threads = std::atoi(next());
    else if (a == "--ranks")
    {
      rankList.clear();
      const std::string list = next();
      for (std::size_t at = 0; at <= list.size();)
      {
        const std::size_t comma = std::min(list.find(',', at), list.size());
        const std::string entry = list.substr(at, comma - at);
        // 0: the distributed solver on one rank (d1)
        rankList.push_back(entry == "d1" ? 0 : std::max(1, std::atoi(entry.c_str())));
        at = comma + 1;
      }
    }
    else if (a == "--stretches")
      stretchFile = next();
    else if (a == "--max-steps")
      maxSteps = std::atoi(next());
    else if (a == "--every")
      every = std::atoi(next());
    else if (a == "--seed-candidates")
      seedCandidates = std::atoi(next());
    else if (a == "--no-quiet")
      quiet = false;
    else
    {
      std::fprintf(stderr, "unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  const std::vector<OrientationField> fields = sectionFields(L, T, band);
  FieldFiberOptions fo;
  fo.volumeFraction = fa + fb * band;
  fo.fiberRadius = 1.0;
  fo.trace.segmentLength = 2.0;
  fo.seed = 1;
  fo.seedCandidates = seedCandidates;
  fo.threads = threads;
  fo.populationShares = { fa, fb * band };
  double t0 = bench::seconds();
  FieldFiberResult traced = generateFieldFibers({ &fields[0], &fields[1] }, fo);
  if (!traced.ok())
  {
    std::fprintf(stderr, "trace: %s\n", traced.error.c_str());
    return 1;
  }
  const FiberModel& tracedModel = traced.model;
  std::printf("trace %.1f s: %zu fibers, %zu points, traced hash %016llx\n", bench::seconds() - t0,
    tracedModel.fibers.size(), tracedModel.numberOfPoints(), bench::modelHash(tracedModel));
  CollisionSolverOptions o;
  o.segmentLength = 2.0;
  o.maxSteps = maxSteps;
  o.numberOfThreads = threads;
  o.separationSpeed = 0.1;
  o.maxDisplacement = 0.4;
  o.quietLinks = quiet;
  // Solves a copy of the traced fibers on `ranks` thread ranks; returns the critical path
  // (seconds), < 0 on an error.
  const auto solveDistributed = [&](int ranks, const std::string& stretchesTo)
  {
    // Pieces of consecutive fibers, as a reader would hand them out; the output pieces in rank
    // order are the solved model.
    std::vector<FiberModel> pieces(static_cast<std::size_t>(ranks));
    const std::size_t nf = tracedModel.fibers.size();
    for (int r = 0; r < ranks; ++r)
      for (std::size_t f = nf * r / ranks; f < nf * (r + 1) / ranks; ++f)
        pieces[static_cast<std::size_t>(r)].fibers.push_back(tracedModel.fibers[f]);
    std::vector<CollisionSolverResult> results(pieces.size());
    std::vector<std::vector<double>> stretches(pieces.size());
    std::vector<const char*> kinds; // rank 0's: every rank calls the same collectives
    t0 = bench::seconds();
    const double c0 = bench::cpuSeconds();
    fiberpli_test::runRanks(ranks,
      [&](Comm& inner)
      {
        TimedComm comm(inner);
        const auto r = static_cast<std::size_t>(comm.rank());
        results[r] = solveCollisions(pieces[r], o, {}, {}, &comm);
        stretches[r] = comm.finish();
        if (r == 0)
          kinds = comm.kinds();
      });
    const double wall = bench::seconds() - t0, cpu = bench::cpuSeconds() - c0;
    if (!stretchesTo.empty())
    {
      if (FILE* f = std::fopen(stretchesTo.c_str(), "w"))
      {
        for (std::size_t i = 0; i < stretches[0].size(); ++i)
        {
          for (const std::vector<double>& s : stretches)
            std::fprintf(f, " %.6f", i < s.size() ? s[i] : 0.0);
          std::fprintf(f, " %s\n", i < kinds.size() ? kinds[i] : "");
        }
        std::fclose(f);
      }
    }
    std::uint64_t h = kFnv1aOffset;
    for (const FiberModel& p : pieces)
      bench::addToHash(h, p);
    double critical = 0.0;
    for (std::size_t i = 0; i < stretches[0].size(); ++i)
    {
      double slowest = 0.0;
      for (const std::vector<double>& s : stretches)
        slowest = std::max(slowest, i < s.size() ? s[i] : 0.0);
      critical += slowest;
    }
    const CollisionSolverResult& r = results[0];
    std::printf("solve on %d ranks %.1f s wall, %.1f s cpu: %d steps, %zu collisions, peak RSS "
                "%.0f MB, solved hash %016llx%s%s\n",
      ranks, wall, cpu, r.steps, r.collisions, bench::peakRssMB(),
      static_cast<unsigned long long>(h), r.error.empty() ? "" : " error: ", r.error.c_str());
    std::printf("cpu outside the collectives per rank:");
    for (std::size_t q = 0; q < stretches.size(); ++q)
    {
      double sum = 0.0;
      for (double x : stretches[q])
        sum += x;
      std::printf(" %.1f", sum);
    }
    std::printf(
      " s; critical path %.1f s over %zu collectives\n", critical, stretches[0].size() - 1);
    for (std::size_t q = 0; q < results.size(); ++q)
      std::printf("rank %zu: %zu held links, %zu halo links, %.0f B sent per step, %zu partners, "
                  "%zu of %zu links loud\n",
        q, results[q].peakHeldLinks, results[q].peakHaloLinks, results[q].haloBytesPerStep,
        results[q].peakPartners, static_cast<std::size_t>(results[q].loudLinks),
        static_cast<std::size_t>(results[q].detectedLinks));
    return r.error.empty() ? critical : -1.0;
  };
  // Solves a copy of the traced fibers on one rank (the serial solver); returns its CPU seconds,
  // < 0 on an error.
  const auto solveSerial = [&]()
  {
    FiberModel model = tracedModel;
    CollisionSolverRun run(model, o);
    t0 = bench::seconds();
    const double c0 = bench::cpuSeconds();
    bench::stepWithTimings(run, every,
      [&](int s, double, double wall, double cpu)
      {
        std::printf("step %5d  %.3f s/step wall  %.3f s/step cpu  loud %zu of %zu links\n", s, wall,
          cpu, run.loudLinks(), run.detectedLinks());
        std::fflush(stdout);
      });
    const CollisionSolverResult r = run.finish();
    const double cpu = bench::cpuSeconds() - c0;
    std::printf("loud links %zu of %zu over all detections\n",
      static_cast<std::size_t>(r.loudLinks), static_cast<std::size_t>(r.detectedLinks));
    std::printf("solve %.1f s wall, %.1f s cpu: %d steps, %zu collisions, peak RSS %.0f MB, "
                "solved hash %016llx%s%s\n",
      bench::seconds() - t0, cpu, r.steps, r.collisions, bench::peakRssMB(),
      bench::modelHash(model), r.error.empty() ? "" : " error: ", r.error.c_str());
    return r.error.empty() ? cpu : -1.0;
  };
  std::vector<double> serialCpu, critical, oneRankDistributed;
  for (std::size_t i = 0; i < rankList.size(); ++i)
  {
    const int ranks = rankList[i];
    const std::string to = stretchFile.empty() || rankList.size() == 1
      ? stretchFile
      : stretchFile + "." + std::to_string(i);
    const double s = ranks != 1 ? solveDistributed(std::max(1, ranks), to) : solveSerial();
    if (s < 0.0)
      return 1;
    (ranks > 1 ? critical : ranks == 1 ? serialCpu : oneRankDistributed).push_back(s);
    std::fflush(stdout);
  }
  if (serialCpu.empty())
    return 0;
  const double one = std::accumulate(serialCpu.begin(), serialCpu.end(), 0.0) /
    static_cast<double>(serialCpu.size()); // the mean one-rank CPU
  if (!critical.empty())
  {
    std::printf("speed-up against the mean one-rank CPU (%.1f s), by critical path:", one);
    for (double c : critical)
      std::printf(" %.3f", one / c);
    std::printf("\n");
  }
  if (!oneRankDistributed.empty())
  {
    std::printf("the distributed solver on one rank against the serial one, CPU:");
    for (double c : oneRankDistributed)
      std::printf(" %.3f", c / one);
    std::printf("\n");
  }
  return 0;
}
