#include "Parallel/TileExchange.h"

#include "Model/FiberWire.h"
#include "Model/InnerRadii.h"
#include "Model/PeriodicCellRule.h"
#include "Util/ByteBuffer.h"
#include "Util/MemoryBudget.h"
#include "Util/NumberFormat.h"

#include <algorithm>
#include <cstdint>
#include <set>
#include <utility>

namespace fiberpli
{
namespace
{
/// What every rank tells the others before the exchange.
struct PieceSummary
{
  int piece = 0;
  bool empty = true;
  long long fibers = 0;
  bool hasCell = false;
  bool myelinated = false;
  std::vector<double> cell;
  std::vector<int> bundles;
};

std::vector<char> encode(const PieceSummary& p)
{
  std::vector<char> bytes;
  ByteWriter w(bytes);
  w.put<std::int32_t>(p.piece);
  w.put<std::uint8_t>(p.empty ? 1 : 0);
  w.put<std::int64_t>(p.fibers);
  w.put<std::uint8_t>(p.hasCell ? 1 : 0);
  w.put<std::uint8_t>(p.myelinated ? 1 : 0);
  w.putVector(p.cell);
  w.putVector(p.bundles);
  return bytes;
}

PieceSummary decode(const std::vector<char>& bytes)
{
  PieceSummary p;
  ByteReader r(bytes);
  p.piece = r.get<std::int32_t>();
  p.empty = r.get<std::uint8_t>() != 0;
  p.fibers = r.get<std::int64_t>();
  p.hasCell = r.get<std::uint8_t>() != 0;
  p.myelinated = r.get<std::uint8_t>() != 0;
  r.getVector(p.cell);
  r.getVector(p.bundles);
  return p;
}

/// Every rank's `mine`, by rank. Collective.
std::vector<std::vector<char>> allGather(const std::vector<char>& mine, Comm& comm)
{
  return comm.exchange(std::vector<std::vector<char>>(static_cast<std::size_t>(comm.size()), mine));
}

std::vector<int> bundlesOf(const FiberModel& model)
{
  std::set<int> bundles;
  for (const Fiber& f : model.fibers)
  {
    bundles.insert(f.bundle);
  }
  return { bundles.begin(), bundles.end() };
}

/// The summary of the whole model in `out` (bundle ids, periodic cell, fiber count) and this
/// rank's global index offset: the fibers of the pieces numbered below its own.
long long summarise(const std::vector<PieceSummary>& all, int myPiece, TileFibers& out)
{
  std::set<int> bundles;
  long long offset = 0;
  const PieceSummary* cellFrom = nullptr;
  out.emptyInput = true;
  for (const PieceSummary& p : all)
  {
    out.emptyInput = out.emptyInput && p.empty;
    bundles.insert(p.bundles.begin(), p.bundles.end());
    out.myelinated = out.myelinated || p.myelinated;
    out.modelFibers += p.fibers;
    offset += p.piece < myPiece ? p.fibers : 0;
    cellFrom = !cellFrom && p.hasCell ? &p : cellFrom; // the lowest rank that has one
  }
  out.bundleIds.assign(bundles.begin(), bundles.end());
  out.periodic = cellFrom != nullptr;
  if (cellFrom)
  {
    // Not only the lowest rank's: a malformed or different cell on any rank fails every rank
    // (the same message everywhere, naming that rank), as the solver refuses it.
    std::vector<RankCell> cells; // every rank's periodic_cell, for the one rule across the ranks
    for (const PieceSummary& p : all)
    {
      cells.push_back(RankCell{ p.hasCell, p.cell.size(), p.cell });
    }
    out.cellError = compareRankCells(cells);
    if (out.cellError.empty())
    {
      out.cellError =
        periodicCellFromBounds(cellFrom->cell.data(), cellFrom->cell.size(), out.cell);
    }
  }
  return offset;
}

// A TileReach as doubles: box, radius scale, periodic flag, cell lo/hi, tiling box.
constexpr std::size_t kReachDoubles = 20;

std::vector<char> encode(const TileReach& r)
{
  double v[kReachDoubles];
  std::copy(r.box, r.box + 6, v);
  v[6] = r.radiusScale;
  v[7] = r.periodic ? 1.0 : 0.0;
  for (int d = 0; d < 3; ++d)
  {
    v[8 + d] = r.cell.lo[d];
    v[11 + d] = r.cell.hi[d];
  }
  std::copy(r.tiling, r.tiling + 6, v + 14);
  std::vector<char> bytes;
  appendBytes(bytes, v, kReachDoubles);
  return bytes;
}

TileReach decodeReach(const std::vector<char>& bytes)
{
  double v[kReachDoubles];
  ByteReader(bytes).get(v, kReachDoubles);
  TileReach r;
  std::copy(v, v + 6, r.box);
  r.radiusScale = v[6];
  r.periodic = v[7] != 0.0;
  for (int d = 0; d < 3; ++d)
  {
    r.cell.lo[d] = v[8 + d];
    r.cell.hi[d] = v[11 + d];
  }
  std::copy(v + 14, v + 20, r.tiling);
  return r;
}

} // namespace

TileFibers wholeModelTile(const TilePiece& piece, const std::string& localError)
{
  TileFibers result;
  static const FiberModel none;
  const FiberModel& model = piece.model ? *piece.model : none;
  result.error = localError;
  result.emptyInput = piece.empty;
  result.periodic = piece.hasCell;
  if (piece.hasCell)
  {
    result.cellError = periodicCellFromBounds(piece.cell.data(), piece.cell.size(), result.cell);
  }
  result.bundleIds = bundlesOf(model);
  result.myelinated = hasInnerRadii(model);
  result.pieceFibers = static_cast<long long>(model.fibers.size());
  result.modelFibers = result.pieceFibers;
  result.model = model;
  return result;
}

TileFibers exchangeTileFibers(const TilePiece& piece, const std::string& localError,
  const std::string& who, const ReachFunction& reachOf, const AgreeFunction& agree, Comm& comm)
{
  static const FiberModel none;
  const FiberModel& model = piece.model ? *piece.model : none;
  TileFibers result;
  result.pieceFibers = static_cast<long long>(model.fibers.size());

  // 1. Agree on the errors of the pieces, then tell every rank what the whole model is.
  result.distributed = true;
  result.error = agree(localError);
  if (!result.ok())
  {
    return result;
  }
  const int ranks = comm.size();
  const int me = comm.rank();
  PieceSummary mine;
  mine.piece = piece.piece;
  mine.fibers = result.pieceFibers;
  mine.empty = piece.empty;
  mine.hasCell = piece.hasCell;
  mine.myelinated = hasInnerRadii(model);
  mine.cell = piece.cell;
  mine.bundles = bundlesOf(model);
  std::vector<PieceSummary> all;
  for (const std::vector<char>& bytes : allGather(encode(mine), comm))
  {
    all.push_back(decode(bytes));
  }
  const long long offset = summarise(all, mine.piece, result);

  // 2. Every rank's box (agreed errors first: a rank that cannot say what it reads fails all).
  TileReach reach;
  result.error = agree(reachOf(result, reach));
  if (!result.ok())
  {
    return result;
  }
  const std::vector<std::vector<char>> reaches = allGather(encode(reach), comm);

  // 3. Where each local fiber goes, and how much every rank receives from every rank.
  std::vector<std::vector<std::size_t>> to(static_cast<std::size_t>(ranks));
  std::vector<std::vector<char>> counts(
    static_cast<std::size_t>(ranks)); // fibers, points per destination
  for (int r = 0; r < ranks; ++r)
  {
    const TileReach theirs = decodeReach(reaches[static_cast<std::size_t>(r)]);
    long long sent[2] = { 0, 0 };
    for (std::size_t f = 0; f < model.fibers.size(); ++f)
    {
      if (fiberReaches(model.fibers[f], theirs))
      {
        to[static_cast<std::size_t>(r)].push_back(f);
        sent[0] += 1;
        sent[1] += static_cast<long long>(model.fibers[f].size());
      }
    }
    appendBytes(counts[static_cast<std::size_t>(r)], sent, 2);
  }
  const std::vector<std::vector<char>> incoming = comm.exchange(counts);
  double incomingFibers = 0.0, incomingPoints = 0.0, messageBytes = 0.0;
  for (int r = 0; r < ranks; ++r)
  {
    long long in[2], out[2];
    ByteReader(incoming[static_cast<std::size_t>(r)]).get(in, 2);
    ByteReader(counts[static_cast<std::size_t>(r)]).get(out, 2);
    incomingFibers += static_cast<double>(in[0]);
    incomingPoints += static_cast<double>(in[1]);
    if (r != me) // messages in and out, all alive during the exchange
    {
      messageBytes += static_cast<double>(fiberWireBytes(0)) * static_cast<double>(in[0] + out[0]) +
        static_cast<double>(fiberWireBytes(1) - fiberWireBytes(0)) *
          static_cast<double>(in[1] + out[1]);
    }
  }
  // The received model, plus the messages in and out, must fit before anything is sent.
  const double bytes = fiberModelBytes(incomingFibers, incomingPoints) + messageBytes;
  result.error = agree(checkMemoryBudget(bytes,
    who + ": the " + formatNumber(static_cast<long long>(incomingFibers)) +
      " fibers that reach rank " + formatNumber(me) + "'s tile"));
  if (!result.ok())
  {
    return result;
  }

  // 4. The exchange; the order of arrival does not matter, step 5 sorts by global index.
  std::vector<std::pair<long long, Fiber>> received;
  for (std::size_t f : to[static_cast<std::size_t>(me)])
  {
    received.emplace_back(offset + static_cast<long long>(f), model.fibers[f]);
  }
  {
    std::vector<std::vector<char>> messages(static_cast<std::size_t>(ranks));
    for (int r = 0; r < ranks; ++r)
    {
      if (r != me)
      {
        writeFibers(
          model, to[static_cast<std::size_t>(r)], offset, messages[static_cast<std::size_t>(r)]);
      }
    }
    const std::vector<std::vector<char>> arrived = comm.exchange(messages);
    messages.clear();
    for (int r = 0; r < ranks; ++r)
    {
      if (r != me)
      {
        readFibers(arrived[static_cast<std::size_t>(r)], received);
      }
    }
  }

  // 5. The model order: by global index.
  std::sort(received.begin(), received.end(),
    [](const std::pair<long long, Fiber>& x, const std::pair<long long, Fiber>& y)
    { return x.first < y.first; });
  result.model.fibers.reserve(received.size());
  for (auto& item : received)
  {
    result.model.fibers.push_back(std::move(item.second));
  }
  return result;
}

} // namespace fiberpli
