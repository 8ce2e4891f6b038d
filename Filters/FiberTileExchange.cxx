#include "FiberTileExchange.h"

#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberPolyData.h"
#include "FiberSolverComm.h"
#include "Model/InnerRadii.h"
#include "Model/PeriodicCellRule.h"
#include "Util/MemoryBudget.h"

#include <vtkAlgorithm.h>
#include <vtkAlgorithmOutput.h>
#include <vtkCommunicator.h>
#include <vtkExecutive.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiProcessController.h>
#include <vtkMultiProcessStream.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace fiberpli
{

namespace
{
// Per fiber: global index, fiber id, bundle id, number of points; per point x, y, z, radius.
constexpr int kHeader = 4;
constexpr int kPoint = 5; // x, y, z, radius, inner radius (0 = none: a valid one is > 0)
// A TileReach as doubles: box, radius scale, periodic flag, cell lo/hi, tiling box.
constexpr int kReachDoubles = 20;

vtkMultiProcessController* ParallelController()
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  return c && c->GetNumberOfProcesses() > 1 ? c : nullptr;
}

void Pack(const TileReach& r, double* out)
{
  std::copy(r.box, r.box + 6, out);
  out[6] = r.radiusScale;
  out[7] = r.periodic ? 1.0 : 0.0;
  for (int d = 0; d < 3; ++d)
  {
    out[8 + d] = r.cell.lo[d];
    out[11 + d] = r.cell.hi[d];
  }
  std::copy(r.tiling, r.tiling + 6, out + 14);
}

TileReach Unpack(const double* in)
{
  TileReach r;
  std::copy(in, in + 6, r.box);
  r.radiusScale = in[6];
  r.periodic = in[7] != 0.0;
  for (int d = 0; d < 3; ++d)
  {
    r.cell.lo[d] = in[8 + d];
    r.cell.hi[d] = in[11 + d];
  }
  std::copy(in + 14, in + 20, r.tiling);
  return r;
}

/// The fibers `which` of `model` (global index offset + local index) in the message layout.
void Serialise(const FiberModel& model, const std::vector<std::size_t>& which, long long offset,
  std::vector<long long>& header, std::vector<double>& points)
{
  header.clear();
  points.clear();
  for (std::size_t f : which)
  {
    const Fiber& fib = model.fibers[f];
    header.insert(header.end(),
      { offset + static_cast<long long>(f), static_cast<long long>(fib.id), fib.bundle, static_cast<long long>(fib.size()) });
    for (std::size_t i = 0; i < fib.size(); ++i)
    {
      const double inner = fib.innerRadii.empty() ? 0.0 : fib.innerRadii[i];
      points.insert(points.end(), { fib.points[i].x, fib.points[i].y, fib.points[i].z, fib.radii[i], inner });
    }
  }
}

/// Appends the fibers of a message to `out` with their global indices.
void Deserialise(const std::vector<long long>& header, const std::vector<double>& points,
  std::vector<std::pair<long long, Fiber>>& out)
{
  std::size_t p = 0;
  for (std::size_t h = 0; h + kHeader <= header.size(); h += kHeader)
  {
    Fiber fib;
    fib.id = header[h + 1];
    fib.bundle = static_cast<int>(header[h + 2]);
    const std::size_t n = static_cast<std::size_t>(header[h + 3]);
    fib.points.resize(n);
    fib.radii.resize(n);
    fib.innerRadii.resize(n);
    for (std::size_t i = 0; i < n; ++i, p += kPoint)
    {
      fib.points[i] = Vec3{ points[p], points[p + 1], points[p + 2] };
      fib.radii[i] = points[p + 3];
      fib.innerRadii[i] = points[p + 4];
    }
    if (n == 0 || fib.innerRadii[0] <= 0.0) // a fiber has inner radii at every point or none
    {
      fib.innerRadii.clear();
    }
    out.emplace_back(header[h], std::move(fib));
  }
}

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

vtkMultiProcessStream& operator<<(vtkMultiProcessStream& s, const PieceSummary& p)
{
  s << p.piece << p.empty << static_cast<vtkTypeInt64>(p.fibers) << p.hasCell << p.myelinated
    << static_cast<int>(p.cell.size());
  for (double v : p.cell)
  {
    s << v;
  }
  s << static_cast<int>(p.bundles.size());
  for (int b : p.bundles)
  {
    s << b;
  }
  return s;
}

vtkMultiProcessStream& operator>>(vtkMultiProcessStream& s, PieceSummary& p)
{
  vtkTypeInt64 fibers = 0;
  int n = 0;
  s >> p.piece >> p.empty >> fibers >> p.hasCell >> p.myelinated >> n;
  p.fibers = fibers;
  p.cell.resize(static_cast<std::size_t>(n));
  for (double& v : p.cell)
  {
    s >> v;
  }
  s >> n;
  p.bundles.resize(static_cast<std::size_t>(n));
  for (int& b : p.bundles)
  {
    s >> b;
  }
  return s;
}

/// The summary of the whole model in `out` (bundle ids, periodic cell, fiber count) and this
/// rank's global index offset: the fibers of the pieces numbered below its own.
long long Summarise(const std::vector<PieceSummary>& all, int myPiece, TileFibers& out)
{
  std::set<int> bundles;
  long long offset = 0;
  const PieceSummary* cellFrom = nullptr;
  out.emptyInput = true;
  std::vector<RankCell> cells; // every rank's periodic_cell, for the one rule across the ranks
  for (const PieceSummary& p : all)
  {
    cells.push_back(RankCell{ p.hasCell != 0, p.cell.size(), p.cell });
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
    out.cellError = CompareRankCells(cells);
    if (out.cellError.empty())
    {
      out.cellError = periodicCellFromBounds(cellFrom->cell.data(), cellFrom->cell.size(), out.cell);
    }
  }
  return offset;
}

/// The fibers `which` as one message: the header's bytes, then the points' bytes.
std::vector<char> Message(const FiberModel& model, const std::vector<std::size_t>& which, long long offset)
{
  std::vector<long long> header;
  std::vector<double> points;
  Serialise(model, which, offset, header, points);
  const std::size_t headerBytes = header.size() * sizeof(long long);
  std::vector<char> message(headerBytes + points.size() * sizeof(double));
  std::copy_n(reinterpret_cast<const char*>(header.data()), headerBytes, message.data());
  std::copy_n(reinterpret_cast<const char*>(points.data()), message.size() - headerBytes, message.data() + headerBytes);
  return message;
}

/// Appends the `fibers` fibers of a message to `out`.
void UnpackFibers(const std::vector<char>& message, long long fibers, std::vector<std::pair<long long, Fiber>>& out)
{
  const std::size_t headerBytes = static_cast<std::size_t>(fibers * kHeader) * sizeof(long long);
  std::vector<long long> header(static_cast<std::size_t>(fibers * kHeader));
  std::vector<double> points((message.size() - headerBytes) / sizeof(double));
  std::copy_n(message.data(), headerBytes, reinterpret_cast<char*>(header.data()));
  std::copy_n(message.data() + headerBytes, message.size() - headerBytes, reinterpret_cast<char*>(points.data()));
  Deserialise(header, points, out);
}
} // namespace

void FiberTileExchange::RequestPiece(vtkInformation* request, vtkInformationVector* outputVector, vtkInformation* inInfo)
{
  int port = request && request->Has(vtkExecutive::FROM_OUTPUT_PORT()) ? request->Get(vtkExecutive::FROM_OUTPUT_PORT()) : 0;
  port = port >= 0 && port < outputVector->GetNumberOfInformationObjects() ? port : 0;
  vtkInformation* outInfo = outputVector->GetInformationObject(port);
  if (!FiberCollective::ControllerFor(outInfo))
  {
    FiberPolyData::RequestAllFibers(inInfo);
    return;
  }
  using SDDP = vtkStreamingDemandDrivenPipeline;
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()));
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()));
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
}

std::string FiberTileExchange::UpdateBounds(vtkAlgorithm* algorithm, vtkInformation* inInfo, const std::string& who,
  double bounds[6], FiberModelCache* cache)
{
  vtkMultiProcessController* c = ParallelController();
  auto* exec = vtkStreamingDemandDrivenPipeline::SafeDownCast(algorithm->GetInputExecutive(0, 0));
  if (inInfo && exec && algorithm->GetNumberOfInputConnections(0) > 0)
  {
    if (c)
    {
      // The piece a parallel update asks for (ParaView: piece = rank of every rank).
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), c->GetLocalProcessId());
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), c->GetNumberOfProcesses());
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
    else
    {
      FiberPolyData::RequestAllFibers(inInfo);
    }
    exec->Update(algorithm->GetInputConnection(0, 0)->GetIndex());
  }
  vtkPolyData* input = inInfo ? vtkPolyData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())) : nullptr;
  std::string error;
  // MIN over (lo, −hi): one reduction gives both corners.
  double local[6] = { HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL };
  if (!FiberPolyData::IsEmpty(input))
  {
    FiberConversion uncached;
    const FiberConversion& in = cache ? cache->Get(input, who) : (uncached = FiberPolyData::ToModel(input, who));
    Vec3 lo, hi;
    error = in.error;
    if (in.ok() && modelBounds(in.model, true, lo, hi))
    {
      const double v[6] = { lo.x, lo.y, lo.z, -hi.x, -hi.y, -hi.z };
      std::copy(v, v + 6, local);
    }
  }
  double global[6];
  std::copy(local, local + 6, global);
  if (c)
  {
    c->AllReduce(local, global, 6, vtkCommunicator::MIN_OP);
  }
  for (int d = 0; d < 3; ++d)
  {
    const bool none = global[d] == HUGE_VAL;
    bounds[2 * d] = none ? 1.0 : global[d];
    bounds[2 * d + 1] = none ? -1.0 : -global[3 + d];
  }
  return error;
}

TileFibers FiberTileExchange::Receive(vtkInformation* outInfo, vtkPolyData* input, const std::string& who,
  const std::string& localError, const ReachFunction& reachOf, FiberModelCache* cache)
{
  TileFibers result;
  std::string error = localError;
  FiberConversion local; // this rank's piece when there is no cache
  const FiberConversion* conversion = &local;
  if (error.empty() && !FiberPolyData::IsEmpty(input))
  {
    conversion = cache ? &cache->Get(input, who) : &(local = FiberPolyData::ToModel(input, who));
    error = conversion->error;
    result.warning = conversion->warning;
  }
  const FiberConversion& in = *conversion;
  std::vector<double> cellValues;
  const bool hasCell = PeriodicCellValues(input, cellValues);
  result.pieceFibers = static_cast<long long>(in.model.fibers.size());

  vtkMultiProcessController* c = FiberCollective::ControllerFor(outInfo);
  if (!c)
  {
    result.error = error;
    result.emptyInput = FiberPolyData::IsEmpty(input);
    result.periodic = hasCell;
    if (hasCell)
    {
      result.cellError = periodicCellFromBounds(cellValues.data(), cellValues.size(), result.cell);
    }
    std::set<int> bundles;
    for (const Fiber& f : in.model.fibers)
    {
      bundles.insert(f.bundle);
    }
    result.bundleIds.assign(bundles.begin(), bundles.end());
    result.myelinated = hasInnerRadii(in.model);
    result.modelFibers = result.pieceFibers;
    result.model = cache ? in.model : std::move(local.model);
    return result;
  }

  // 1. Agree on the errors of the pieces, then tell every rank what the whole model is.
  result.distributed = true;
  result.error = FiberCollective::AgreeOnError(outInfo, who, error);
  if (!result.ok())
  {
    return result;
  }
  const int ranks = c->GetNumberOfProcesses();
  const int me = c->GetLocalProcessId();
  PieceSummary mine;
  mine.piece = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  mine.fibers = result.pieceFibers;
  mine.empty = FiberPolyData::IsEmpty(input);
  mine.hasCell = hasCell;
  mine.myelinated = hasInnerRadii(in.model);
  mine.cell = cellValues;
  std::set<int> localBundles;
  for (const Fiber& f : in.model.fibers)
  {
    localBundles.insert(f.bundle);
  }
  mine.bundles.assign(localBundles.begin(), localBundles.end());
  vtkMultiProcessStream sent;
  sent << mine;
  std::vector<vtkMultiProcessStream> streams;
  c->AllGather(sent, streams);
  std::vector<PieceSummary> all(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r)
  {
    streams[static_cast<std::size_t>(r)] >> all[static_cast<std::size_t>(r)];
  }
  const long long offset = Summarise(all, mine.piece, result);

  // 2. Every rank's box (agreed errors first: a rank that cannot say what it reads fails all).
  TileReach reach;
  result.error = FiberCollective::AgreeOnError(outInfo, who, reachOf(result, reach));
  if (!result.ok())
  {
    return result;
  }
  double packed[kReachDoubles];
  Pack(reach, packed);
  std::vector<double> reaches(static_cast<std::size_t>(kReachDoubles * ranks));
  c->AllGather(packed, reaches.data(), kReachDoubles);

  // 3. Where each local fiber goes, and how much every rank receives from every rank.
  std::vector<std::vector<std::size_t>> to(static_cast<std::size_t>(ranks));
  std::vector<long long> counts(static_cast<std::size_t>(2 * ranks), 0); // fibers, points per destination
  for (int r = 0; r < ranks; ++r)
  {
    const TileReach theirs = Unpack(&reaches[static_cast<std::size_t>(kReachDoubles * r)]);
    for (std::size_t f = 0; f < in.model.fibers.size(); ++f)
    {
      if (fiberReaches(in.model.fibers[f], theirs))
      {
        to[static_cast<std::size_t>(r)].push_back(f);
        counts[static_cast<std::size_t>(2 * r)] += 1;
        counts[static_cast<std::size_t>(2 * r + 1)] += static_cast<long long>(in.model.fibers[f].size());
      }
    }
  }
  // What every rank sends to this one (fibers, points per sender): O(R) numbers per rank.
  FiberSolverComm comm(c);
  const std::vector<long long> incoming = comm.allToAll(counts, 2);
  double incomingPoints = 0.0, incomingFibers = 0.0, messagePoints = 0.0, messageFibers = 0.0;
  for (int r = 0; r < ranks; ++r)
  {
    incomingFibers += static_cast<double>(incoming[static_cast<std::size_t>(2 * r)]);
    incomingPoints += static_cast<double>(incoming[static_cast<std::size_t>(2 * r + 1)]);
    const bool other = r != me; // messages in and out, all alive during the exchange
    messageFibers += other ? static_cast<double>(incoming[static_cast<std::size_t>(2 * r)] + counts[static_cast<std::size_t>(2 * r)]) : 0.0;
    messagePoints += other ? static_cast<double>(incoming[static_cast<std::size_t>(2 * r + 1)] + counts[static_cast<std::size_t>(2 * r + 1)]) : 0.0;
  }
  // The received model, plus the messages in and out, must fit before anything is sent.
  const double bytes = fiberModelBytes(incomingFibers, incomingPoints) +
    messageFibers * kHeader * sizeof(long long) + messagePoints * kPoint * sizeof(double);
  result.error = FiberCollective::AgreeOnError(outInfo, who,
    checkMemoryBudget(bytes, who + ": the " + std::to_string(static_cast<long long>(incomingFibers)) +
        " fibers that reach rank " + std::to_string(me) + "'s tile"));
  if (!result.ok())
  {
    return result;
  }

  // 4. The exchange (FiberSolverComm: non-blocking, partners only); the order of arrival does
  //    not matter, step 5 sorts by global index.
  std::vector<std::pair<long long, Fiber>> received;
  for (std::size_t f : to[static_cast<std::size_t>(me)])
  {
    received.emplace_back(offset + static_cast<long long>(f), in.model.fibers[f]);
  }
  {
    std::vector<std::vector<char>> messages(static_cast<std::size_t>(ranks));
    for (int r = 0; r < ranks; ++r)
    {
      if (r != me)
      {
        messages[static_cast<std::size_t>(r)] = Message(in.model, to[static_cast<std::size_t>(r)], offset);
      }
    }
    const std::vector<std::vector<char>> arrived = comm.exchange(messages);
    messages.clear();
    for (int r = 0; r < ranks; ++r)
    {
      if (r != me)
      {
        UnpackFibers(arrived[static_cast<std::size_t>(r)], incoming[static_cast<std::size_t>(2 * r)], received);
      }
    }
  }
  local.model = FiberModel(); // this rank's piece is no longer needed (a cache keeps its own)

  // 5. The model order: by global index.
  std::sort(received.begin(), received.end(),
    [](const std::pair<long long, Fiber>& x, const std::pair<long long, Fiber>& y) { return x.first < y.first; });
  result.model.fibers.reserve(received.size());
  for (auto& item : received)
  {
    result.model.fibers.push_back(std::move(item.second));
  }
  return result;
}

} // namespace fiberpli
