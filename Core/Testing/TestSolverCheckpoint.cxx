// Solver checkpoints (docs/solver.md §14): a run stopped after a checkpoint and resumed from the
// file ends bit for bit like the uninterrupted run (open cube with drag and curvature; periodic
// cell with radius growth), the resumed run really starts at the saved step, and a file that does
// not belong to the run (other options, other input, an older version, damaged, not a checkpoint,
// missing) is an error naming the file and what differs.
#include "Checkpoint/SolverCheckpoint.h"
#include "PeriodicReference.h"
#include "SolverTestModels.h"
#include "ThreadComm.h"
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fstream>
#include <functional>
#include <future>
#include <iterator>
#include <memory>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

using namespace fiberpli;

namespace
{
struct TempFile
{
  std::string dir;
  std::string path;
  TempFile()
  {
    char tmpl[] = "/tmp/fiberpli-checkpoint-XXXXXX";
    dir = ::mkdtemp(tmpl);
    path = dir + "/solve.ckpt";
  }
  ~TempFile() // the checkpoints, their previous generations, the ranks' files
  {
    if (DIR* d = ::opendir(dir.c_str()))
    {
      while (const dirent* e = ::readdir(d))
      {
        if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, ".."))
          std::remove((dir + "/" + e->d_name).c_str());
      }
      ::closedir(d);
    }
    ::rmdir(dir.c_str());
  }
};

using fiberpli_test::bitwiseEqual;

FiberModel denseOpenCube()
{
  CubeOptions o;
  o.populations = 2;
  o.numberOfFibers = 100;
  o.edgeLength = std::sqrt(3.0) * 30.0 * std::sqrt(100 / 1000.0);
  o.seed = 3;
  return generateCube(o);
}

// A finished 30-step solve of the dense open cube that wrote a checkpoint every 10 steps (the
// file then holds step 30, its previous generation step 20): what the tests reading a file start
// from.
struct CheckpointedRun
{
  const FiberModel in = denseOpenCube();
  CollisionSolverOptions options;
  TempFile file;
  std::string error; ///< of the solve, "" when it ran
  CheckpointedRun()
  {
    options.maxSteps = 30;
    FiberModel m = in;
    error = solveWithCheckpoints(m, options, { file.path, 10, false }).error;
  }
};

// Uninterrupted, then: checkpoints every `interval` steps, "killed" (aborted) at step `killAt`,
// resumed from the file; both must end identically, and the resumed run must begin right after
// the last checkpoint before the kill.
void expectResumeEqualsUninterrupted(
  const FiberModel& in, const CollisionSolverOptions& o, int interval, int killAt)
{
  FiberModel reference = in;
  const CollisionSolverResult r1 = solveCollisions(reference, o);
  ASSERT_TRUE(r1.error.empty()) << r1.error;
  ASSERT_GT(r1.steps, killAt) << "the solve must outlast the kill";

  TempFile file;
  CheckpointOptions cp{ file.path, interval, false };
  FiberModel killed = in;
  int lastStep = 0;
  const StepObserver count = [&](int step, const FiberModel&) { lastStep = step; };
  const CollisionSolverResult aborted = solveWithCheckpoints(
    killed, o, cp, [&](double) { return lastStep < killAt; }, count);
  ASSERT_TRUE(aborted.error.empty()) << aborted.error;
  ASSERT_TRUE(aborted.aborted);

  cp.resume = true;
  FiberModel resumed = in; // the input again, as a re-submitted job would build it
  int firstStep = -1;
  const StepObserver first = [&](int step, const FiberModel&)
  {
    if (firstStep < 0)
      firstStep = step;
  };
  const CollisionSolverResult r2 = solveWithCheckpoints(resumed, o, cp, {}, first);
  ASSERT_TRUE(r2.error.empty()) << r2.error;
  EXPECT_EQ(firstStep, killAt / interval * interval + 1)
    << "the resumed run must start after the last checkpoint";
  EXPECT_TRUE(bitwiseEqual(resumed, reference));
  EXPECT_EQ(r2.steps, r1.steps);
  EXPECT_EQ(r2.collisions, r1.collisions);
  EXPECT_EQ(r2.bestCollisions, r1.bestCollisions);
  EXPECT_EQ(r2.bestStep, r1.bestStep);
  EXPECT_EQ(r2.shapeOk, r1.shapeOk);
  EXPECT_EQ(r2.radiusScale, r1.radiusScale);
  EXPECT_EQ(r2.maxOverlap, r1.maxOverlap);
  EXPECT_EQ(r2.minGap, r1.minGap);
  EXPECT_EQ(r2.sourceIndex, r1.sourceIndex);
  EXPECT_EQ(r2.warnings, r1.warnings);
}
// runRanks, but a hang (a rank waiting in a collective the others never make) ends the test
// program with a failure message instead of blocking ctest.
void runRanksWithin(int ranks, int seconds, const std::function<void(Comm&)>& f)
{
  auto done = std::make_shared<std::promise<void>>();
  std::future<void> finished = done->get_future();
  std::thread(
    [ranks, f, done]
    {
      fiberpli_test::runRanks(ranks, f);
      done->set_value();
    })
    .detach();
  if (finished.wait_for(std::chrono::seconds(seconds)) != std::future_status::ready)
  {
    std::fprintf(stderr, "FAILED: the ranks did not finish within %d s (hang)\n", seconds);
    std::_Exit(1);
  }
}

// The two-rank tests: a run long enough (> 45 steps) to be stopped after a checkpoint at step 20.
CollisionSolverOptions twoRankOptions()
{
  CollisionSolverOptions o;
  o.maxSteps = 90;
  o.minCurvatureRadius = 4.0;
  o.numberOfThreads = 1;
  return o;
}

// Rank r's input piece of two: the first or second half of the fibers, in order.
FiberModel halfOf(const FiberModel& whole, int r)
{
  FiberModel m;
  for (std::size_t f = whole.fibers.size() * r / 2; f < whole.fibers.size() * (r + 1) / 2; ++f)
    m.fibers.push_back(whole.fibers[f]);
  return m;
}

} // namespace

TEST(SolverCheckpoint, ResumedOpenCubeEqualsUninterruptedRun)
{
  CollisionSolverOptions o;
  o.maxSteps = 90;
  o.minCurvatureRadius = 4.0;
  o.drag = 0.3; // velocities are part of the state
  o.numberOfThreads = 2;
  expectResumeEqualsUninterrupted(denseOpenCube(), o, 20, 45);
}

TEST(SolverCheckpoint, ResumedBoostedRunEqualsUninterruptedRun)
{
  // Twice the paper cube's fibers in its cube: > 9 colliding pairs per link, so the push boost
  // chosen at the first detection (part of the state) must survive the resume.
  CubeOptions c;
  c.populations = 2;
  c.numberOfFibers = 100;
  c.edgeLength = std::sqrt(3.0) * 30.0 * std::sqrt(50 / 1000.0);
  c.seed = 3;
  CollisionSolverOptions o;
  o.maxSteps = 90;
  o.minCurvatureRadius = 4.0;
  o.pushBoost = 2.0;
  o.numberOfThreads = 2;
  const FiberModel in = generateCube(c);
  FiberModel probe = in;
  CollisionSolverRun run(probe, o);
  ASSERT_TRUE(run.start());
  ASSERT_TRUE(run.step());
  ASSERT_GT(run.state().pushScale, 1.0) << "the input must be crowded enough for the boost";
  expectResumeEqualsUninterrupted(in, o, 20, 45);
}

TEST(SolverCheckpoint, ResumedPeriodicGrowthEqualsUninterruptedRun)
{
  const CubeOptions c = fiberpli_test::periodicCube(2, 20.0, 0.35);
  const FiberModel in = generateCube(c);
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.initialRadiusScale = 0.9; // the radius scale and its counters are part of the state
  o.maxSteps = 150;
  expectResumeEqualsUninterrupted(in, o, 15, 40);
}

TEST(SolverCheckpoint, AFileOfAnotherRunIsAnErrorNamingFileAndDifference)
{
  const CheckpointedRun run;
  ASSERT_EQ(run.error, "");
  const FiberModel& in = run.in;
  const CollisionSolverOptions& o = run.options;
  const TempFile& file = run.file;

  FiberModel model;
  CollisionSolverState state;
  const std::uint64_t fingerprint = modelFingerprint(in);
  EXPECT_EQ(readSolverCheckpoint(file.path, o, fingerprint, model, state), "");
  EXPECT_EQ(state.steps, 30);
  EXPECT_EQ(model.fibers.size(), in.fibers.size());

  CollisionSolverOptions threads = o; // the thread count does not change the result
  threads.numberOfThreads = 3;
  EXPECT_EQ(readSolverCheckpoint(file.path, threads, fingerprint, model, state), "");

  CollisionSolverOptions other = o;
  other.separationSpeed = 0.05;
  std::string e = readSolverCheckpoint(file.path, other, fingerprint, model, state);
  EXPECT_NE(e.find(file.path), std::string::npos) << e;
  EXPECT_NE(e.find("SeparationSpeed is 0.025 there and 0.05 now"), std::string::npos) << e;

  FiberModel moved = in;
  moved.fibers[7].points[2].x += 1e-9;
  e = readSolverCheckpoint(file.path, o, modelFingerprint(moved), model, state);
  EXPECT_NE(e.find("another input"), std::string::npos) << e;
  // Through the solve: the caller's model is left as it was.
  const CollisionSolverResult refused = solveWithCheckpoints(moved, o, { file.path, 10, true });
  EXPECT_NE(refused.error.find("another input"), std::string::npos) << refused.error;
  EXPECT_EQ(moved.fibers[7].points[2].x, in.fibers[7].points[2].x + 1e-9);

  // Damaged: one byte changed, or the end cut off.
  std::string bytes;
  {
    std::ifstream f(file.path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  for (const std::string& bad :
    { bytes.substr(0, bytes.size() / 2), std::string(bytes).replace(bytes.size() / 2, 1, "~") })
  {
    std::ofstream(file.path, std::ios::binary) << bad;
    e = readSolverCheckpoint(file.path, o, fingerprint, model, state);
    EXPECT_NE(e.find("is damaged"), std::string::npos) << e;
  }
  std::ofstream(file.path, std::ios::binary) << "FiberPLI dat 1\n";
  EXPECT_NE(readSolverCheckpoint(file.path, o, fingerprint, model, state)
              .find("is not a FiberPLI solver checkpoint"),
    std::string::npos);
  // Not readable (or gone): the previous generation (step 20) is taken; without it, an error.
  std::remove(file.path.c_str());
  FiberModel fromPrevious = in;
  int firstStep = -1;
  e = solveWithCheckpoints(fromPrevious, o, { file.path, 0, true }, {},
    [&](int step, const FiberModel&)
    {
      if (firstStep < 0)
        firstStep = step;
    }).error;
  EXPECT_EQ(e, "");
  EXPECT_EQ(firstStep, 21);
  std::remove(previousCheckpointPath(file.path).c_str());
  FiberModel noFile = in;
  e = solveWithCheckpoints(noFile, o, { file.path, 0, true }).error;
  EXPECT_NE(e.find(file.path), std::string::npos) << e;
  EXPECT_NE(e.find("cannot be opened"), std::string::npos) << e;
}

// A file of the previous format (version 2: another push rule, so it would not resume bit for
// bit) is refused naming the file and both versions, and the caller's model stays as it was.
TEST(SolverCheckpoint, AVersion2FileIsRefusedNamingFileAndVersions)
{
  const CheckpointedRun run;
  ASSERT_EQ(run.error, "");
  for (const std::string& file : { run.file.path, previousCheckpointPath(run.file.path) })
  {
    std::fstream f(file, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(16); // after the 16-byte magic: the version, a little-endian u64
    const unsigned char two[8] = { 2, 0, 0, 0, 0, 0, 0, 0 };
    f.write(reinterpret_cast<const char*>(two), sizeof two);
    ASSERT_TRUE(f.good()) << file;
  }
  FiberModel model;
  CollisionSolverState state;
  const std::string e =
    readSolverCheckpoint(run.file.path, run.options, modelFingerprint(run.in), model, state);
  EXPECT_NE(e.find(run.file.path), std::string::npos) << e;
  EXPECT_NE(e.find("has version 2, this FiberPLI reads version 5"), std::string::npos) << e;

  FiberModel resumed = run.in;
  const CollisionSolverResult r =
    solveWithCheckpoints(resumed, run.options, { run.file.path, 10, true });
  EXPECT_EQ(r.error, e); // the newest generation's message (the previous one is version 2 too)
  EXPECT_EQ(r.steps, 0);
  EXPECT_TRUE(bitwiseEqual(resumed, run.in)) << "the caller's model must be unchanged";
}

TEST(SolverCheckpoint, AnUnwritableCheckpointStopsTheSolveNamingTheFile)
{
  FiberModel m = denseOpenCube();
  CollisionSolverOptions o;
  o.maxSteps = 30;
  const std::string path = "/nonexistent-fiberpli-dir/solve.ckpt";
  const CollisionSolverResult r = solveWithCheckpoints(m, o, { path, 10, false });
  EXPECT_NE(r.error.find(path), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("at step 10"), std::string::npos) << r.error;
  EXPECT_NE(solveWithCheckpoints(m, o, { "", 10, false }).error.find("CheckpointFile is empty"),
    std::string::npos);
  EXPECT_NE(solveWithCheckpoints(m, o, { path, -1, false }).error.find("CheckpointInterval is -1"),
    std::string::npos);
}

// Distributed (threads as ranks): one file per rank; a run stopped after a checkpoint and resumed
// on 2 ranks gives the serial result; a checkpoint one rank cannot write fails both ranks.
TEST(SolverCheckpoint, DistributedRanksResumeToTheSerialResultAndShareErrors)
{
  const FiberModel whole = denseOpenCube();
  const CollisionSolverOptions o = twoRankOptions();
  FiberModel serial = whole;
  const CollisionSolverResult s = solveCollisions(serial, o);
  ASSERT_TRUE(s.error.empty()) << s.error;
  ASSERT_GT(s.steps, 45);

  TempFile file;
  const auto piece = [&](int r) { return halfOf(whole, r); };
  std::vector<FiberModel> out(2);
  std::vector<CollisionSolverResult> results(2);
  fiberpli_test::runRanks(2,
    [&](Comm& comm)
    {
      FiberModel m = piece(comm.rank());
      int last = 0;
      solveWithCheckpoints(
        m, o, { file.path, 20, false }, [&](double) { return last < 45; },
        [&](int step, const FiberModel&) { last = step; }, &comm);
      FiberModel again = piece(comm.rank());
      results[static_cast<std::size_t>(comm.rank())] =
        solveWithCheckpoints(again, o, { file.path, 20, true }, {}, {}, &comm);
      out[static_cast<std::size_t>(comm.rank())] = std::move(again);
    });
  for (int r = 0; r < 2; ++r)
  {
    const std::string own = checkpointPath(file.path, nullptr) + "." + std::to_string(r) + "-of-2";
    EXPECT_EQ(checkpointPath(file.path, nullptr), file.path);
    EXPECT_EQ(std::remove(own.c_str()), 0) << "no file " << own;
    ASSERT_EQ(results[r].error, "");
    EXPECT_EQ(results[r].steps, s.steps);
  }
  FiberModel joined = out[0];
  joined.fibers.insert(joined.fibers.end(), out[1].fibers.begin(), out[1].fibers.end());
  EXPECT_TRUE(bitwiseEqual(joined, serial));

  // Rank 1's file cannot be written (a directory is in its place): both ranks fail at step 20.
  const std::string blocked = file.path + ".1-of-2";
  ASSERT_EQ(::mkdir(blocked.c_str(), 0700), 0);
  fiberpli_test::runRanks(2,
    [&](Comm& comm)
    {
      FiberModel m = piece(comm.rank());
      results[static_cast<std::size_t>(comm.rank())] =
        solveWithCheckpoints(m, o, { file.path, 20, false }, {}, {}, &comm);
    });
  ::rmdir(blocked.c_str());
  std::remove((file.path + ".0-of-2").c_str());
  EXPECT_NE(results[1].error.find(blocked), std::string::npos) << results[1].error;
  EXPECT_NE(results[0].error.find("rank 1 failed"), std::string::npos) << results[0].error;
  EXPECT_NE(results[0].error.find("at step 20"), std::string::npos) << results[0].error;
}

// Rank 1's files are one generation older than rank 0's (it could not write its last checkpoint,
// or the job died between the ranks' writes): both resume from the newest step both hold and end
// like the serial run; with no common step both fail naming the files and steps — no hang.
TEST(SolverCheckpoint, RanksWithCheckpointsOfDifferentStepsAgreeOrAllFail)
{
  const FiberModel whole = denseOpenCube();
  const CollisionSolverOptions o = twoRankOptions();
  FiberModel serial = whole;
  const CollisionSolverResult s = solveCollisions(serial, o);
  ASSERT_TRUE(s.error.empty()) << s.error;
  ASSERT_GT(s.steps, 45);
  const auto piece = [&](int r) { return halfOf(whole, r); };
  TempFile file;
  const std::string own0 = file.path + ".0-of-2", own1 = file.path + ".1-of-2";
  const auto stopAt45 = [&]
  {
    runRanksWithin(2, 120,
      [&](Comm& comm)
      {
        FiberModel m = piece(comm.rank());
        int last = 0;
        solveWithCheckpoints(
          m, o, { file.path, 20, false }, [&](double) { return last < 45; },
          [&](int step, const FiberModel&) { last = step; }, &comm);
      });
  };
  std::vector<FiberModel> out(2);
  std::vector<CollisionSolverResult> results(2);
  std::vector<int> firstSteps(2, -1);
  const auto resume = [&]
  {
    runRanksWithin(2, 120,
      [&](Comm& comm)
      {
        const std::size_t r = static_cast<std::size_t>(comm.rank());
        out[r] = piece(comm.rank());
        results[r] = solveWithCheckpoints(
          out[r], o, { file.path, 20, true }, {},
          [&](int step, const FiberModel&)
          {
            if (firstSteps[r] < 0)
              firstSteps[r] = step;
          },
          &comm);
      });
  };

  // Steps 40 (and 20 kept) on both ranks; rank 1 is put back to step 20 alone.
  stopAt45();
  ASSERT_EQ(std::rename(previousCheckpointPath(own1).c_str(), own1.c_str()), 0);
  resume();
  for (int r = 0; r < 2; ++r)
  {
    ASSERT_EQ(results[r].error, "") << "rank " << r;
    EXPECT_EQ(firstSteps[r], 21) << "rank " << r << " must resume from the common step 20";
    EXPECT_EQ(results[r].steps, s.steps);
  }
  FiberModel joined = out[0];
  joined.fibers.insert(joined.fibers.end(), out[1].fibers.begin(), out[1].fibers.end());
  EXPECT_TRUE(bitwiseEqual(joined, serial));

  // No step on both: rank 0 holds only step 40, rank 1 only step 20.
  stopAt45();
  ASSERT_EQ(std::remove(previousCheckpointPath(own0).c_str()), 0);
  ASSERT_EQ(std::rename(previousCheckpointPath(own1).c_str(), own1.c_str()), 0);
  const std::vector<FiberModel> before{ piece(0), piece(1) };
  resume();
  for (int r = 0; r < 2; ++r)
  {
    const std::string& e = results[r].error;
    EXPECT_NE(e.find("different steps"), std::string::npos) << e;
    EXPECT_NE(e.find("'" + own0 + "' at step 40"), std::string::npos) << e;
    EXPECT_NE(e.find("'" + own1 + "' at step 20"), std::string::npos) << e;
    EXPECT_TRUE(bitwiseEqual(out[r], before[r])) << "rank " << r << " must keep its own piece";
  }

  // A common step, but rank 1's file holds rank 0's fibers (a file of the wrong rank): the
  // fiber set check fails both ranks, naming the file.
  stopAt45();
  ASSERT_EQ(std::remove(previousCheckpointPath(own0).c_str()), 0);
  ASSERT_EQ(std::remove(previousCheckpointPath(own1).c_str()), 0);
  {
    std::ifstream src(own0, std::ios::binary);
    std::ofstream dst(own1, std::ios::binary | std::ios::trunc);
    dst << src.rdbuf();
  }
  // The copy was written for rank 0's input: resume rank 1 from rank 0's piece too, so only the
  // fiber set (not the input fingerprint) is wrong.
  runRanksWithin(2, 120,
    [&](Comm& comm)
    {
      const std::size_t r = static_cast<std::size_t>(comm.rank());
      out[r] = piece(0);
      results[r] = solveWithCheckpoints(out[r], o, { file.path, 20, true }, {}, {}, &comm);
    });
  EXPECT_NE(results[1].error.find("exactly once"), std::string::npos) << results[1].error;
  EXPECT_NE(results[0].error.find("exactly once"), std::string::npos) << results[0].error;
}

// Rank 1's checkpoint reads (checksum, options and input fingerprint fine) but its state does not
// fit its model: the refusal is agreed on before any other collective, so both ranks fail, naming
// rank 1's file, and nobody waits for the other in the distribution (under a timeout).
TEST(SolverCheckpoint, AStateThatFitsOnlyOneRankFailsEveryRankNamingTheFile)
{
  const FiberModel whole = denseOpenCube();
  const CollisionSolverOptions o = twoRankOptions();
  const auto piece = [&](int r) { return halfOf(whole, r); };
  TempFile file;
  const std::string own1 = file.path + ".1-of-2";
  runRanksWithin(2, 120,
    [&](Comm& comm)
    {
      FiberModel m = piece(comm.rank());
      int last = 0;
      solveWithCheckpoints(
        m, o, { file.path, 20, false }, [&](double) { return last < 25; },
        [&](int step, const FiberModel&) { last = step; }, &comm);
    });
  FiberModel saved;
  CollisionSolverState state;
  const std::uint64_t fingerprint = modelFingerprint(piece(1));
  ASSERT_EQ(readSolverCheckpoint(own1, o, fingerprint, saved, state), "");
  ASSERT_FALSE(saved.fibers.empty());
  saved.fibers[0].radii[0] = -1.0; // a radius the solver refuses (file and state still consistent)
  ASSERT_EQ(writeSolverCheckpoint(own1, saved, state, o, fingerprint), "");
  std::vector<CollisionSolverResult> results(2);
  std::vector<FiberModel> out{ piece(0), piece(1) };
  runRanksWithin(2, 120,
    [&](Comm& comm)
    {
      const std::size_t r = static_cast<std::size_t>(comm.rank());
      results[r] = solveWithCheckpoints(out[r], o, { file.path, 20, true }, {}, {}, &comm);
    });
  for (int r = 0; r < 2; ++r)
  {
    const std::string& e = results[r].error;
    EXPECT_NE(e.find("'" + own1 + "': does not fit"), std::string::npos)
      << "rank " << r << ": " << e;
    EXPECT_NE(e.find("fiber " + std::to_string(state.global[0])), std::string::npos)
      << "rank " << r << ": " << e;
    EXPECT_TRUE(bitwiseEqual(out[r], piece(r))) << "rank " << r << " must keep its own piece";
  }
  EXPECT_NE(results[0].error.find("rank 1 failed"), std::string::npos) << results[0].error;
}

// A resumed run that fails (here: its next checkpoint cannot be written, a directory stands where
// the file was; the run resumed from the previous generation) leaves the caller's model as it was.
TEST(SolverCheckpoint, AFailedResumedRunLeavesTheCallersModel)
{
  const CheckpointedRun run;
  ASSERT_EQ(run.error, "");
  const FiberModel& in = run.in;
  const CollisionSolverOptions& o = run.options;
  const TempFile& file = run.file;
  ASSERT_EQ(std::remove(file.path.c_str()), 0); // steps 30 gone, 20 kept as .prev
  ASSERT_EQ(::mkdir(file.path.c_str(), 0700), 0);
  FiberModel resumed = in;
  int firstStep = -1;
  const CollisionSolverResult r = solveWithCheckpoints(resumed, o, { file.path, 5, true }, {},
    [&](int step, const FiberModel&)
    {
      if (firstStep < 0)
        firstStep = step;
    });
  ::rmdir(file.path.c_str());
  EXPECT_EQ(firstStep, 21) << "resumed from the previous generation";
  EXPECT_NE(r.error.find(file.path), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("at step 25"), std::string::npos) << r.error;
  EXPECT_TRUE(bitwiseEqual(resumed, in)) << "the caller's model must be unchanged";
}

TEST(SolverCheckpoint, ASoundFileWithAnUnsoundStateIsRefusedNamingFileAndField)
{
  // A checkpoint with a valid checksum but one edited value (rewritten with its checksum) used to
  // be trusted: a NaN radius scale aborted, a tiny segment length split the model until memory ran
  // out, a point at 1e300 hung, a NaN closure gave NaN output, all fibers flagged inactive gave
  // "collisions 0". Each must be refused before the run goes on, naming the file and the field.
  CheckpointedRun run;
  ASSERT_EQ(run.error, "");
  FiberModel savedModel;
  CollisionSolverState savedState;
  ASSERT_EQ(readSolverCheckpoint(
              run.file.path, run.options, modelFingerprint(run.in), savedModel, savedState),
    "");
  std::remove(previousCheckpointPath(run.file.path).c_str()); // nothing older to fall back to
  struct Edit
  {
    const char* expected;
    std::function<void(FiberModel&, CollisionSolverState&)> apply;
  };
  const std::vector<Edit> edits = {
    { "radius scale is nan", [](FiberModel&, CollisionSolverState& s) { s.scale = std::nan(""); } },
    { "radius scale is 1.5", [](FiberModel&, CollisionSolverState& s) { s.scale = 1.5; } },
    { "segment length is 1e-09",
      [](FiberModel&, CollisionSolverState& s) { s.segmentLength = 1e-9; } },
    { "coordinate 1e+300",
      [](FiberModel& m, CollisionSolverState&) { m.fibers[3].points[1].x = 1e300; } },
    { "closure vector of fiber 2",
      [](FiberModel&, CollisionSolverState& s) { s.closure[2].y = std::nan(""); } },
    { "flags fiber 0 (fiber_id 0) inactive",
      [](FiberModel&, CollisionSolverState& s)
      { std::fill(s.active.begin(), s.active.end(), 0); } },
    { "move cap is 1e+09", [](FiberModel&, CollisionSolverState& s) { s.vMax = 1e9; } },
    { "step count is -4", [](FiberModel&, CollisionSolverState& s) { s.steps = -4; } },
    { "push scale is inf", [](FiberModel&, CollisionSolverState& s) { s.pushScale = HUGE_VAL; } },
    { "velocity of fiber 1 (fiber_id 1) point 0",
      [](FiberModel&, CollisionSolverState& s) { s.points[1].velocity[0].z = std::nan(""); } },
  };
  for (const Edit& edit : edits)
  {
    FiberModel m = savedModel;
    CollisionSolverState st = savedState;
    edit.apply(m, st);
    ASSERT_EQ(
      writeSolverCheckpoint(run.file.path, m, st, run.options, modelFingerprint(run.in)), "");
    FiberModel resumed = run.in;
    const CollisionSolverResult r =
      solveWithCheckpoints(resumed, run.options, { run.file.path, 0, true });
    EXPECT_NE(r.error.find("checkpoint file '" + run.file.path + "'"), std::string::npos)
      << r.error;
    EXPECT_NE(r.error.find(edit.expected), std::string::npos) << r.error;
    EXPECT_TRUE(bitwiseEqual(resumed, run.in)) << "a refused resume must leave the caller's model";
  }
  // The state as written resumes.
  ASSERT_EQ(writeSolverCheckpoint(
              run.file.path, savedModel, savedState, run.options, modelFingerprint(run.in)),
    "");
  FiberModel resumed = run.in;
  EXPECT_EQ(solveWithCheckpoints(resumed, run.options, { run.file.path, 0, true }).error, "");
}

TEST(SolverCheckpoint, AFallBackToThePreviousGenerationIsAWarning)
{
  // A damaged newest file used to be skipped silently for its previous generation.
  CheckpointedRun run;
  ASSERT_EQ(run.error, "");
  {
    std::ofstream damaged(run.file.path, std::ios::binary | std::ios::trunc);
    damaged << "FiberPLI? no";
  }
  FiberModel m = run.in;
  const CollisionSolverResult r = solveWithCheckpoints(m, run.options, { run.file.path, 0, true });
  ASSERT_EQ(r.error, "");
  bool warned = false;
  for (const std::string& w : r.warnings)
  {
    warned = warned ||
      (w.find("'" + run.file.path + "'") != std::string::npos &&
        w.find("resumed from the previous generation '" + previousCheckpointPath(run.file.path) +
          "' at step 20") != std::string::npos);
  }
  EXPECT_TRUE(warned) << (r.warnings.empty() ? std::string("no warning") : r.warnings.back());
}

TEST(SolverCheckpoint, ResumingOnAnotherRankCountSaysWhichFilesExist)
{
  // Files of a 2-rank run, resumed on 3 ranks (and serially): every rank says that files for 2
  // ranks exist, instead of only that its own file cannot be opened.
  TempFile file;
  for (int r = 0; r < 2; ++r)
  {
    std::ofstream(file.path + "." + std::to_string(r) + "-of-2") << "x";
  }
  const FiberModel whole = denseOpenCube();
  std::vector<std::string> errors(3);
  runRanksWithin(3, 60,
    [&](Comm& comm)
    {
      FiberModel piece;
      for (std::size_t f = whole.fibers.size() * comm.rank() / 3;
           f < whole.fibers.size() * (comm.rank() + 1) / 3; ++f)
        piece.fibers.push_back(whole.fibers[f]);
      errors[static_cast<std::size_t>(comm.rank())] =
        solveWithCheckpoints(piece, twoRankOptions(), { file.path, 0, true }, {}, {}, &comm).error;
    });
  for (const std::string& e : errors)
  {
    EXPECT_NE(e.find("files for 2 ranks exist ('solve.ckpt.0-of-2', 'solve.ckpt.1-of-2')"),
      std::string::npos)
      << e;
  }
  FiberModel serial = whole;
  const std::string e =
    solveWithCheckpoints(serial, twoRankOptions(), { file.path, 0, true }).error;
  EXPECT_NE(e.find("files for 2 ranks exist"), std::string::npos) << e;
}

TEST(SolverCheckpoint, AFifoAsCheckpointFileIsRefusedWithoutBlocking)
{
  TempFile file;
  ASSERT_EQ(::mkfifo(file.path.c_str(), 0600), 0);
  std::string error;
  runRanksWithin(1, 30,
    [&](Comm&)
    {
      FiberModel m = denseOpenCube();
      error = solveWithCheckpoints(m, twoRankOptions(), { file.path, 0, true }).error;
    });
  EXPECT_NE(error.find("'" + file.path + "'"), std::string::npos) << error;
  EXPECT_NE(error.find("FIFO"), std::string::npos) << error;
}
