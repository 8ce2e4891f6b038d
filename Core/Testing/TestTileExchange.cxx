// The fiber exchange for image tiles (Parallel/TileExchange.h) with threads as ranks: every rank
// receives exactly the fibers that reach its box, in the order of the whole model, whatever piece
// it held; the summary of the model is the same on every rank; an error on one rank fails all.
#include "Parallel/TileExchange.h"

#include "Parallel/Collectives.h"
#include "ThreadComm.h"

#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

using namespace fiberpli;
using fiberpli_test::runRanks;

namespace
{
constexpr int kFibers = 12;

/// Fiber f: a segment along x from 10·f to 10·f + 2 at y = z = 0, radius 0.5, id 100 + f, bundle
/// f mod 3; every fourth fiber myelinated (inner radius 0.3).
Fiber fiberAt(int f)
{
  Fiber fiber;
  fiber.id = 100 + f;
  fiber.bundle = f % 3;
  fiber.points = { Vec3{ 10.0 * f, 0, 0 }, Vec3{ 10.0 * f + 2, 0, 0 } };
  fiber.radii = { 0.5, 0.5 };
  if (f % 4 == 0)
  {
    fiber.innerRadii = { 0.3, 0.3 };
  }
  return fiber;
}

/// Rank r's box: x in [40·r − 1, 40·r + 35].
TileReach boxOf(int rank)
{
  TileReach reach;
  const double box[6] = { 40.0 * rank - 1, 40.0 * rank + 35, -5, 5, -5, 5 };
  std::copy(box, box + 6, reach.box);
  return reach;
}

/// Independently: the fibers whose x extent, grown by the radius, overlaps rank r's box.
std::vector<std::int64_t> expectedIds(int rank)
{
  std::vector<std::int64_t> ids;
  for (int f = 0; f < kFibers; ++f)
  {
    if (10.0 * f + 2.5 >= 40.0 * rank - 1 && 10.0 * f - 0.5 <= 40.0 * rank + 35)
    {
      ids.push_back(100 + f);
    }
  }
  return ids;
}

/// Rank r holds piece R − 1 − r: the fibers of that piece, a contiguous part of the model in order.
FiberModel pieceOf(int piece, int ranks)
{
  FiberModel model;
  for (int f = kFibers * piece / ranks; f < kFibers * (piece + 1) / ranks; ++f)
  {
    model.fibers.push_back(fiberAt(f));
  }
  return model;
}

struct RankRun
{
  std::string localError;   ///< this rank's error before the exchange
  std::string reachError;   ///< what its reach function says
  std::vector<double> cell; ///< its periodic_cell ("" = none)
};

std::vector<TileFibers> exchange(int ranks, const std::vector<RankRun>& runs = {})
{
  std::vector<TileFibers> results(static_cast<std::size_t>(ranks));
  runRanks(ranks,
    [&](Comm& comm)
    {
      const int r = comm.rank();
      const RankRun run = runs.empty() ? RankRun() : runs[static_cast<std::size_t>(r)];
      const FiberModel model = pieceOf(ranks - 1 - r, ranks);
      TilePiece piece;
      piece.model = &model;
      piece.piece = ranks - 1 - r;
      piece.empty = model.fibers.empty();
      piece.hasCell = !run.cell.empty();
      piece.cell = run.cell;
      results[static_cast<std::size_t>(r)] = exchangeTileFibers(
        piece, run.localError, "Test",
        [&](const TileFibers&, TileReach& reach)
        {
          reach = boxOf(r);
          return run.reachError;
        },
        [&](const std::string& e) { return agreeOnError(comm, e); }, comm);
    });
  return results;
}
} // namespace

TEST(TileExchange, EveryRankGetsTheFibersOfItsBoxInModelOrder)
{
  for (int ranks = 1; ranks <= 3; ++ranks)
  {
    const std::vector<TileFibers> results = exchange(ranks);
    for (int r = 0; r < ranks; ++r)
    {
      const TileFibers& t = results[static_cast<std::size_t>(r)];
      ASSERT_TRUE(t.ok()) << t.error;
      std::vector<std::int64_t> ids;
      for (const Fiber& f : t.model.fibers)
      {
        ids.push_back(f.id);
        const int index = static_cast<int>(f.id - 100);
        EXPECT_EQ(f.bundle, index % 3);
        EXPECT_EQ(f.points, fiberAt(index).points);
        EXPECT_EQ(f.innerRadii, fiberAt(index).innerRadii); // kept, and none where there was none
      }
      EXPECT_EQ(ids, expectedIds(r)) << ranks << " ranks, rank " << r;
      EXPECT_TRUE(t.distributed);
      EXPECT_EQ(t.modelFibers, kFibers);
      EXPECT_EQ(t.pieceFibers, static_cast<long long>(pieceOf(ranks - 1 - r, ranks).fibers.size()));
      EXPECT_EQ(t.bundleIds, (std::vector<int>{ 0, 1, 2 }));
      EXPECT_TRUE(t.myelinated);
      EXPECT_FALSE(t.periodic);
      EXPECT_FALSE(t.emptyInput);
    }
  }
}

TEST(TileExchange, OneRanksErrorFailsEveryRank)
{
  std::vector<RankRun> runs(3);
  runs[1].localError = "bad piece";
  for (const TileFibers& t : exchange(3, runs))
  {
    EXPECT_NE(t.error.find("bad piece"), std::string::npos) << t.error;
    EXPECT_TRUE(t.model.fibers.empty());
  }
  runs.assign(3, RankRun());
  runs[2].reachError = "no box";
  for (const TileFibers& t : exchange(3, runs))
  {
    EXPECT_NE(t.error.find("no box"), std::string::npos) << t.error;
  }
}

TEST(TileExchange, PeriodicCellAgreedOverTheRanks)
{
  std::vector<RankRun> runs(2);
  runs[0].cell = { 0, 120, -5, 5, -5, 5 };
  std::vector<TileFibers> results = exchange(2, runs); // a piece without the field is fine
  for (const TileFibers& t : results)
  {
    ASSERT_TRUE(t.ok()) << t.error;
    EXPECT_TRUE(t.periodic);
    EXPECT_EQ(t.cellError, "");
    EXPECT_EQ(t.cell.hi.x, 120.0);
  }
  runs[1].cell = { 0, 100, -5, 5, -5, 5 }; // another cell on rank 1: the same message everywhere
  results = exchange(2, runs);
  EXPECT_NE(results[0].cellError.find("rank 1"), std::string::npos) << results[0].cellError;
  EXPECT_EQ(results[0].cellError, results[1].cellError);
}

TEST(TileExchange, OneProcessKeepsTheWholePiece)
{
  const FiberModel model = pieceOf(0, 1);
  TilePiece piece;
  piece.model = &model;
  piece.empty = false;
  const TileFibers t = wholeModelTile(piece, "");
  EXPECT_TRUE(t.ok());
  EXPECT_FALSE(t.distributed);
  ASSERT_EQ(t.model.fibers.size(), static_cast<std::size_t>(kFibers));
  EXPECT_EQ(t.model.fibers[5].id, 105);
  EXPECT_EQ(t.modelFibers, kFibers);
  EXPECT_EQ(t.bundleIds, (std::vector<int>{ 0, 1, 2 }));
  EXPECT_EQ(wholeModelTile(piece, "broken").error, "broken");
}
