#include "Checkpoint/SolverCheckpoint.h"

#include "Checkpoint/CheckpointState.h"

#include "IO/AtomicFile.h"
#include "IO/RegularFile.h"
#include "Util/BinaryIO.h"
#include "Util/Fnv1a.h"
#include "Util/NumberFormat.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

namespace fiberpli
{

namespace
{
// File layout (all little-endian): magic, version, the options as (name, value) pairs, the
// input's fingerprint and size, the model, the per-fiber state, the scalars of the state, the
// warnings, then the FNV-1a checksum of everything before it.
const char kMagic[16] = { 'F', 'i', 'b', 'e', 'r', 'P', 'L', 'I', ' ', 's', 'o', 'l', 'v', 'e', 'r',
  '\n' };
constexpr std::uint32_t kVersion = 5; // 2: PushBoost and the push scale; 3: its pair cap (another
                                      // push rule); 4: Tortuosity; 5: input radius profiles
// The checksum's start value: one digit short of FNV's offset basis (kFnv1aOffset) since the
// first version; kept, so that the checksum rule stays the one every version has used.
constexpr std::uint64_t kChecksumStart = 1469598103934665603ULL;

std::uint64_t bitsOf(double v)
{
  std::uint64_t u;
  std::memcpy(&u, &v, sizeof u);
  return u;
}

// The options that decide the result, by the name the user knows them (the pvpython property
// where there is one). numberOfThreads is not among them: the result does not depend on it.
std::vector<std::pair<std::string, double>> optionList(const CollisionSolverOptions& o)
{
  const PeriodicCell& c = o.periodicCell;
  return { { "SegmentLength", o.segmentLength }, { "MinCurvatureRadius", o.minCurvatureRadius },
    { "MaxSteps", o.maxSteps }, { "SeparationSpeed", o.separationSpeed },
    { "overlapPush", o.overlapPush }, { "pushSpread", o.pushSpread },
    { "maxDisplacement", o.maxDisplacement }, { "pushBoost", o.pushBoost }, { "drag", o.drag },
    { "MinimumGap", o.minimumGap }, { "endPoints", static_cast<double>(o.endPoints) },
    { "stallSteps", o.stallSteps }, { "periodic_cell xmin", c.lo.x },
    { "periodic_cell xmax", c.hi.x }, { "periodic_cell ymin", c.lo.y },
    { "periodic_cell ymax", c.hi.y }, { "periodic_cell zmin", c.lo.z },
    { "periodic_cell zmax", c.hi.z }, { "InitialRadiusScale", o.initialRadiusScale },
    { "Tortuosity", o.tortuosity }, { "TortuosityWavelength", o.tortuosityWavelength },
    { "DragSteps", o.dragSteps } };
}

// Options added after the format, with their defaults: a file without one was written at that.
constexpr std::pair<const char*, double> kLaterOptions[] = { { "TortuosityWavelength", 0.0 },
  { "DragSteps", 0.0 } };

bool laterOptionAtDefault(const std::string& name, double value)
{
  return std::any_of(std::begin(kLaterOptions), std::end(kLaterOptions),
    [&](const auto& o) { return name == o.first && bitsOf(o.second) == bitsOf(value); });
}

class Writer
{
public:
  explicit Writer(std::ostream& out)
    : out_(out)
  {
  }
  void bytes(const void* p, std::size_t n)
  {
    fnv1aAdd(hash_, p, n);
    out_.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
  }
  void u64(std::uint64_t v)
  {
    unsigned char b[8];
    binary::store64LE(b, v);
    bytes(b, 8);
  }
  void f64(double v)
  {
    unsigned char b[8];
    binary::storeFloat64LE(b, v);
    bytes(b, 8);
  }
  void vec(const Vec3& v)
  {
    f64(v.x);
    f64(v.y);
    f64(v.z);
  }
  void text(const std::string& s)
  {
    u64(s.size());
    bytes(s.data(), s.size());
  }
  void checksum()
  {
    u64(hash_);
  } // the checksum itself is not hashed: the reader compares before it
  std::uint64_t hash() const { return hash_; }

private:
  std::ostream& out_;
  std::uint64_t hash_ = kChecksumStart;
};

// Reads with the bytes left in the file known, so that a damaged count never allocates more than
// the file could hold.
class Reader
{
public:
  Reader(std::istream& in, std::uint64_t size)
    : in_(in)
    , left_(size)
  {
  }
  bool ok() const { return ok_; }
  std::uint64_t left() const { return left_; }
  void bytes(void* p, std::size_t n)
  {
    if (!ok_ || n > left_ || !in_.read(static_cast<char*>(p), static_cast<std::streamsize>(n)))
    {
      ok_ = false;
      std::memset(p, 0, n);
      return;
    }
    left_ -= n;
    fnv1aAdd(hash_, p, n);
  }
  std::uint64_t u64()
  {
    unsigned char b[8];
    bytes(b, 8);
    return binary::load64(b, true);
  }
  double f64()
  {
    unsigned char b[8];
    bytes(b, 8);
    return binary::loadFloat64(b, true);
  }
  Vec3 vec()
  {
    const double x = f64();
    const double y = f64();
    return Vec3{ x, y, f64() };
  }
  /// A count of items of at least `itemBytes` bytes each that the rest of the file can hold.
  std::size_t count(std::uint64_t itemBytes)
  {
    const std::uint64_t n = u64();
    if (ok_ && itemBytes > 0 && n > left_ / itemBytes)
    {
      ok_ = false;
    }
    return ok_ ? static_cast<std::size_t>(n) : 0;
  }
  std::string text()
  {
    std::string s(count(1), '\0');
    bytes(&s[0], s.size());
    return s;
  }
  std::uint64_t hash() const { return hash_; }

private:
  std::istream& in_;
  std::uint64_t left_;
  std::uint64_t hash_ = kChecksumStart;
  bool ok_ = true;
};

std::string named(const std::string& path, const std::string& what)
{
  return "checkpoint file '" + path + "': " + what;
}
} // namespace

std::uint64_t modelFingerprint(const FiberModel& model)
{
  std::ostringstream sink; // Writer hashes while it writes; a null stream keeps nothing
  sink.setstate(std::ios::badbit);
  Writer w(sink);
  w.u64(model.fibers.size());
  for (const Fiber& f : model.fibers)
  {
    w.u64(static_cast<std::uint64_t>(f.id));
    w.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(f.bundle)));
    w.u64(f.points.size());
    for (const Vec3& p : f.points)
      w.vec(p);
    for (double r : f.radii)
      w.f64(r);
  }
  return w.hash();
}

std::string writeSolverCheckpoint(const std::string& path, const FiberModel& model,
  const CollisionSolverState& st, const CollisionSolverOptions& options,
  std::uint64_t inputFingerprint)
{
  const std::size_t nf = model.fibers.size();
  if (st.points.size() != nf || st.active.size() != nf || st.closed.size() != nf ||
    st.closure.size() != nf)
  {
    return named(path,
      "the solver state has " + formatNumber(st.points.size()) + " fibers, the model " +
        formatNumber(nf));
  }
  const std::string error = writeFileAtomically(path,
    [&](std::ostream& out) -> std::string
    {
      Writer w(out);
      w.bytes(kMagic, sizeof kMagic);
      w.u64(kVersion);
      const auto list = optionList(options);
      w.u64(list.size());
      for (const auto& [name, value] : list)
      {
        w.text(name);
        w.f64(value);
      }
      w.u64(inputFingerprint);
      w.u64(nf);
      for (std::size_t f = 0; f < nf; ++f)
      {
        const Fiber& fib = model.fibers[f];
        const FiberPointState& ps = st.points[f];
        if (fib.radii.size() != fib.points.size() || ps.velocity.size() != fib.points.size() ||
          ps.source.size() != fib.points.size())
        {
          return "fiber " + formatNumber(f) + " has points, radii and state of different sizes";
        }
        w.u64(static_cast<std::uint64_t>(fib.id));
        w.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(fib.bundle)));
        w.u64(fib.points.size());
        for (std::size_t i = 0; i < fib.points.size(); ++i)
        {
          w.vec(fib.points[i]);
          w.f64(fib.radii[i]);
          w.vec(ps.velocity[i]);
          w.f64(ps.source[i]);
        }
        w.u64(ps.inputRadii.size());
        for (double r : ps.inputRadii)
          w.f64(r);
        w.u64(static_cast<std::uint64_t>(st.active[f] ? 1 : 0) |
          (static_cast<std::uint64_t>(st.closed[f] ? 1 : 0) << 1));
        w.vec(st.closure[f]);
        // Global index and home rank (distributed runs; a serial state may leave them empty).
        w.u64(static_cast<std::uint64_t>(
          f < st.global.size() ? st.global[f] : static_cast<std::int64_t>(f)));
        w.u64(static_cast<std::uint64_t>(
          static_cast<std::int64_t>(f < st.home.size() ? st.home[f] : 0)));
      }
      for (double v : { st.segmentLength, st.vMax, st.growthTolerance, st.pushScale, st.scale,
             st.done, st.reported })
      {
        w.f64(v);
      }
      for (long long v : { static_cast<long long>(st.steps), static_cast<long long>(st.sinceGrowth),
             static_cast<long long>(st.sinceImprovement), static_cast<long long>(st.first),
             static_cast<long long>(st.warnedStall), static_cast<long long>(st.firstCount),
             static_cast<long long>(st.bestCollisions), static_cast<long long>(st.bestStep),
             static_cast<long long>(st.changed) })
      {
        w.u64(static_cast<std::uint64_t>(v));
      }
      w.u64(st.warnings.size());
      for (const std::string& text : st.warnings)
      {
        w.text(text);
      }
      w.checksum();
      return out ? std::string() : std::string("the write failed");
    });
  // writeFileAtomically's message names the file and the system error.
  return error.empty() ? error : "cannot write the solver checkpoint: " + error;
}

std::string readSolverCheckpoint(const std::string& path, const CollisionSolverOptions& options,
  std::uint64_t inputFingerprint, FiberModel& model, CollisionSolverState& state)
{
  const std::string special = checkRegularFile(path); // a FIFO would block the read forever
  if (!special.empty())
  {
    return named(path, "cannot be read: " + special);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return named(path, "cannot be opened (" + std::string(std::strerror(errno)) + ")");
  }
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0)
  {
    return named(path, "cannot be read");
  }
  Reader r(in, static_cast<std::uint64_t>(size));
  char magic[sizeof kMagic];
  r.bytes(magic, sizeof magic);
  if (!r.ok() || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
  {
    return named(path, "is not a FiberPLI solver checkpoint");
  }
  const std::uint64_t version = r.u64();
  if (version != kVersion)
  {
    return named(path,
      "has version " + formatNumber(version) + ", this FiberPLI reads version " +
        formatNumber(kVersion));
  }
  const auto given = optionList(options);
  const std::size_t nOptions = r.count(16);
  std::vector<std::pair<std::string, double>> saved;
  for (std::size_t i = 0; i < nOptions && r.ok(); ++i)
  {
    std::string name = r.text();
    saved.emplace_back(std::move(name), r.f64());
  }
  const std::uint64_t fingerprint = r.u64();
  FiberModel m;
  CollisionSolverState st;
  const std::size_t nf = r.count(8 * 6 + 8 * 3); // id, bundle, count, flags, global, home, closure
  m.fibers.resize(nf);
  st.points.resize(nf);
  st.active.resize(nf);
  st.closed.resize(nf);
  st.closure.resize(nf);
  st.global.resize(nf);
  st.home.resize(nf);
  for (std::size_t f = 0; f < nf && r.ok(); ++f)
  {
    Fiber& fib = m.fibers[f];
    FiberPointState& ps = st.points[f];
    fib.id = static_cast<std::int64_t>(r.u64());
    fib.bundle = static_cast<int>(static_cast<std::int64_t>(r.u64()));
    const std::size_t n = r.count(8 * 8);
    fib.points.resize(n);
    fib.radii.resize(n);
    ps.velocity.resize(n);
    ps.source.resize(n);
    for (std::size_t i = 0; i < n && r.ok(); ++i)
    {
      fib.points[i] = r.vec();
      fib.radii[i] = r.f64();
      ps.velocity[i] = r.vec();
      ps.source[i] = r.f64();
    }
    ps.inputRadii.resize(r.count(8));
    for (double& radius : ps.inputRadii)
      radius = r.f64();
    const std::uint64_t flags = r.u64();
    st.active[f] = (flags & 1) ? 1 : 0;
    st.closed[f] = (flags & 2) ? 1 : 0;
    st.closure[f] = r.vec();
    st.global[f] = static_cast<std::int64_t>(r.u64());
    st.home[f] = static_cast<int>(static_cast<std::int64_t>(r.u64()));
  }
  for (double* v : { &st.segmentLength, &st.vMax, &st.growthTolerance, &st.pushScale, &st.scale,
         &st.done, &st.reported })
  {
    *v = r.f64();
  }
  st.steps = static_cast<int>(r.u64());
  st.sinceGrowth = static_cast<int>(r.u64());
  st.sinceImprovement = static_cast<int>(r.u64());
  st.first = r.u64() != 0;
  st.warnedStall = r.u64() != 0;
  st.firstCount = static_cast<std::size_t>(r.u64());
  st.bestCollisions = static_cast<std::size_t>(r.u64());
  st.bestStep = static_cast<int>(r.u64());
  st.changed = r.u64() != 0;
  const std::size_t nWarnings = r.count(8);
  for (std::size_t i = 0; i < nWarnings && r.ok(); ++i)
  {
    st.warnings.push_back(r.text());
  }
  const std::uint64_t computed = r.hash();
  const std::uint64_t stored = r.u64();
  if (!r.ok() || stored != computed || r.left() != 0)
  {
    return named(path, "is damaged (truncated or changed: its checksum does not match)");
  }
  // The file is sound: now whether it belongs to this run.
  for (const auto& [name, value] : given)
  {
    const auto it =
      std::find_if(saved.begin(), saved.end(), [&](const auto& s) { return s.first == name; });
    if (it == saved.end() && laterOptionAtDefault(name, value))
    {
      continue;
    }
    if (it == saved.end() || bitsOf(it->second) != bitsOf(value))
    {
      std::ostringstream msg;
      msg << "was written with other options: " << name << " is ";
      if (it == saved.end())
        msg << "missing";
      else
        msg << it->second;
      msg << " there and " << value << " now; resume with the options it was written with";
      return named(path, msg.str());
    }
  }
  if (fingerprint != inputFingerprint)
  {
    return named(path,
      "was written for another input (fingerprint " + formatNumber(fingerprint) +
        ", this input has " + formatNumber(inputFingerprint) +
        "); resume with the input it was written for");
  }
  model = std::move(m);
  state = std::move(st);
  return {};
}

std::string checkpointPath(const std::string& path, const Comm* comm)
{
  if (!comm || comm->size() < 2)
  {
    return path;
  }
  return path + "." + formatNumber(comm->rank()) + "-of-" + formatNumber(comm->size());
}

std::string previousCheckpointPath(const std::string& path)
{
  return path + ".prev";
}

namespace
{
// Collective: "" when no rank failed, else (on every rank) its own error, or the lowest failing
// rank's error named as such.
std::string agree(Comm* comm, const std::string& local)
{
  if (!comm || comm->size() < 2)
  {
    return local;
  }
  std::vector<std::vector<char>> send(
    static_cast<std::size_t>(comm->size()), std::vector<char>(local.begin(), local.end()));
  const std::vector<std::vector<char>> got = comm->exchange(send);
  if (!local.empty())
  {
    return local;
  }
  for (std::size_t r = 0; r < got.size(); ++r)
  {
    if (!got[r].empty())
    {
      return "rank " + formatNumber(r) + " failed: " + std::string(got[r].begin(), got[r].end());
    }
  }
  return {};
}

// Keeps the generation before: the current file becomes previousCheckpointPath, then the new
// one is written. Killed in between, the previous generation is still there to resume from.
// Only a regular file is moved (anything else in the way fails the write, naming the file).
std::string writeGeneration(const std::string& path, const FiberModel& model,
  const CollisionSolverState& st, const CollisionSolverOptions& options, std::uint64_t fingerprint)
{
  struct stat info;
  if (::lstat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode))
  {
    const std::string prev = previousCheckpointPath(path);
    // ENOENT: another process writing the same file (ranks solving the same whole model) moved it.
    if (std::rename(path.c_str(), prev.c_str()) != 0 && errno != ENOENT)
    {
      return named(
        path, "cannot be kept as '" + prev + "' (" + std::string(std::strerror(errno)) + ")");
    }
  }
  return writeSolverCheckpoint(path, model, st, options, fingerprint);
}

struct Generation
{
  std::string file;
  FiberModel model;
  CollisionSolverState state;
};

// The generations of `path` that read (the file and its previous one), newest step first; with
// none, error is the file's own read error.
std::vector<Generation> readGenerations(const std::string& path,
  const CollisionSolverOptions& options, std::uint64_t fingerprint, std::string& error,
  std::string& newestProblem)
{
  std::vector<Generation> found;
  for (const std::string& file : { path, previousCheckpointPath(path) })
  {
    Generation g;
    g.file = file;
    const std::string problem = readSolverCheckpoint(file, options, fingerprint, g.model, g.state);
    if (problem.empty())
    {
      found.push_back(std::move(g));
    }
    else if (file == path)
    {
      error = problem;
      newestProblem = problem; // kept when the previous generation reads: the caller warns
    }
  }
  std::stable_sort(found.begin(), found.end(),
    [](const Generation& a, const Generation& b) { return a.state.steps > b.state.steps; });
  if (!found.empty())
  {
    error.clear();
  }
  return found;
}

// When this run's file is missing: the checkpoint files of `base` written by runs over another
// number of ranks ("" when there are none), so that resuming 2-rank checkpoints on 3 ranks says
// what exists instead of only "cannot be opened".
std::string otherRankCountFiles(const std::string& base, int ranks)
{
  const std::size_t slash = base.find_last_of('/');
  const std::string dir =
    slash == std::string::npos ? "." : (slash == 0 ? "/" : base.substr(0, slash));
  const std::string name = slash == std::string::npos ? base : base.substr(slash + 1);
  std::map<int, std::vector<std::string>> byRanks; // rank count -> files
  if (ranks > 1 && checkRegularFile(base).empty() && ::access(base.c_str(), F_OK) == 0)
  {
    byRanks[1].push_back(name);
  }
  if (DIR* d = ::opendir(dir.c_str()))
  {
    while (const dirent* e = ::readdir(d))
    {
      const std::string entry = e->d_name;
      int rank = -1, count = -1, used = 0;
      if (entry.size() > name.size() + 1 && entry.compare(0, name.size() + 1, name + ".") == 0 &&
        std::sscanf(entry.c_str() + name.size() + 1, "%d-of-%d%n", &rank, &count, &used) == 2 &&
        static_cast<std::size_t>(used) == entry.size() - name.size() - 1 && count != ranks &&
        count > 1)
      {
        byRanks[count].push_back(entry);
      }
    }
    ::closedir(d);
  }
  std::string text;
  for (auto& [count, files] : byRanks)
  {
    std::sort(files.begin(), files.end());
    std::string list;
    for (const std::string& f : files)
    {
      list += (list.empty() ? "'" : ", '") + f + "'";
    }
    text += (text.empty() ? "" : "; ") +
      std::string(count == 1 ? "a file of a serial run exists (" : "files for ") +
      (count == 1 ? list + ")" : formatNumber(count) + " ranks exist (" + list + ")");
  }
  return text.empty() ? text : text + ": resume on the number of ranks that wrote them";
}

std::string describe(const std::vector<Generation>& gens)
{
  std::string text;
  for (const Generation& g : gens)
  {
    text += (text.empty() ? "'" : ", '") + g.file + "' at step " + formatNumber(g.state.steps);
  }
  return text;
}

// Collective: the index in gens of the newest step every rank holds, or -1 and (the same on
// every rank) a message naming each rank's files and their steps.
int newestCommonGeneration(Comm* comm, const std::vector<Generation>& gens, std::string& error)
{
  if (!comm || comm->size() < 2)
  {
    return gens.empty() ? -1 : 0;
  }
  // Sent to every rank: the steps held, then the description for the message.
  std::string mine;
  for (const Generation& g : gens)
  {
    mine += formatNumber(g.state.steps) + " ";
  }
  mine += "|" + describe(gens);
  const std::vector<std::vector<char>> got = comm->exchange(std::vector<std::vector<char>>(
    static_cast<std::size_t>(comm->size()), std::vector<char>(mine.begin(), mine.end())));
  std::vector<int> common;
  for (const Generation& g : gens)
  {
    common.push_back(g.state.steps);
  }
  std::string all;
  for (std::size_t r = 0; r < got.size(); ++r)
  {
    const std::string text(got[r].begin(), got[r].end());
    const std::size_t bar = text.find('|');
    std::istringstream steps(text.substr(0, bar));
    std::vector<int> held;
    for (int v; steps >> v;)
    {
      held.push_back(v);
    }
    common.erase(std::remove_if(common.begin(), common.end(),
                   [&](int v) { return std::find(held.begin(), held.end(), v) == held.end(); }),
      common.end());
    all += (r ? "; rank " : "rank ") + formatNumber(r) + ": " + text.substr(bar + 1);
  }
  if (common.empty())
  {
    error = "the ranks' checkpoints are of different steps and no step is held by every rank (" +
      all + "): resume needs the same step on every rank";
    return -1;
  }
  for (std::size_t i = 0; i < gens.size(); ++i)
  {
    if (gens[i].state.steps == common.front())
    {
      return static_cast<int>(i);
    }
  }
  return -1; // not reached: common is a subset of gens' steps
}

// A hash of a global index, so that a sum over the indices catches swapped/duplicated ones that
// keep the plain sum (31 bits: the sum of up to 2^32 of them stays exact in 64 bits).
std::int64_t indexHash(std::int64_t i)
{
  std::uint64_t z = static_cast<std::uint64_t>(i) + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return static_cast<std::int64_t>((z ^ (z >> 31)) & 0x7FFFFFFFULL);
}

// Collective: "" when the ranks' pieces hold every fiber of the model exactly once (their global
// indices cover 0..N-1, N the total fiber count: the same count, sum and hash sum), else (on
// every rank) a message naming this rank's file and step.
std::string checkFiberSet(Comm* comm, const Generation& g)
{
  const std::vector<std::int64_t>& global = g.state.global;
  std::vector<std::int64_t> sums{ static_cast<std::int64_t>(global.size()), 0, 0 };
  std::vector<double> extremes{ -1.0, 0.0 }; // max index, max of −index
  for (std::int64_t i : global)
  {
    sums[1] += i;
    sums[2] += indexHash(i);
    extremes[0] = std::max(extremes[0], static_cast<double>(i));
    extremes[1] = std::max(extremes[1], -static_cast<double>(i));
  }
  if (comm)
  {
    comm->sum(sums);
    comm->max(extremes);
  }
  const std::int64_t n = sums[0];
  std::int64_t hashes = 0;
  for (std::int64_t i = 0; i < n; ++i)
  {
    hashes += indexHash(i);
  }
  const bool inRange = n == 0 || (extremes[0] == static_cast<double>(n - 1) && extremes[1] == 0.0);
  if (static_cast<std::int64_t>(g.model.fibers.size()) != static_cast<std::int64_t>(global.size()))
  {
    sums[1] = -1; // a damaged local state; reported below like a wrong set
  }
  if (inRange && sums[1] == n * (n - 1) / 2 && sums[2] == hashes)
  {
    return {};
  }
  return named(g.file,
    "the checkpoints of step " + formatNumber(g.state.steps) + " do not hold each of the model's " +
      formatNumber(n) + " fibers exactly once (global indices are not 0.." + formatNumber(n - 1) +
      "): files of different runs or rank counts?");
}
} // namespace

CollisionSolverResult solveWithCheckpoints(FiberModel& model, const CollisionSolverOptions& options,
  const CheckpointOptions& checkpoint, const ProgressFn& progress, const StepObserver& observer,
  Comm* comm)
{
  // Every rank decides these alike (same properties everywhere), so none waits in agree() alone.
  CollisionSolverResult failed;
  if (checkpoint.interval < 0)
  {
    failed.error =
      "CheckpointInterval is " + formatNumber(checkpoint.interval) + ", must be >= 0 (0 = off)";
    return failed;
  }
  if (checkpoint.interval == 0 && !checkpoint.resume)
  {
    return solveCollisions(model, options, progress, observer, comm);
  }
  if (checkpoint.path.empty())
  {
    failed.error =
      "CheckpointFile is empty, but checkpoints are asked for (CheckpointInterval or resume)";
    return failed;
  }
  const std::string path = checkpointPath(checkpoint.path, comm);
  const std::uint64_t fingerprint = modelFingerprint(model);
  // A resumed run works on the file's model and hands it over at the end, so that a failed
  // resume leaves the caller's model unchanged.
  // The ranks may hold different steps (a rank could not write its last checkpoint, or the job
  // was killed between the ranks' writes): all resume from the newest step every rank holds, and
  // only if their pieces together are the whole model, else all fail alike (no rank waits alone).
  FiberModel resumed;
  CollisionSolverState saved;
  std::string resumedFile = path;
  std::string newestProblem; // why the newest generation was not the one resumed
  if (checkpoint.resume)
  {
    std::string problem;
    std::vector<Generation> gens =
      readGenerations(path, options, fingerprint, problem, newestProblem);
    if (gens.empty() && ::access(path.c_str(), F_OK) != 0)
    {
      const std::string others = otherRankCountFiles(checkpoint.path, comm ? comm->size() : 1);
      problem += others.empty() ? "" : "; " + others;
    }
    failed.error = agree(comm, problem);
    if (!failed.error.empty())
    {
      return failed;
    }
    const int chosen = newestCommonGeneration(comm, gens, failed.error);
    if (chosen < 0)
    {
      return failed;
    }
    Generation& g = gens[static_cast<std::size_t>(chosen)];
    failed.error = agree(comm, checkFiberSet(comm, g));
    if (!failed.error.empty())
    {
      return failed;
    }
    // The checksum says the file is as written, not that what was written is sound: the state
    // passes the checks of fresh input and of every scalar (Checkpoint/CheckpointState.h).
    const std::string unsound =
      checkResumedState(g.model, g.state, options, comm ? comm->size() : 1);
    failed.error = agree(comm, unsound.empty() ? unsound : named(g.file, unsound));
    if (!failed.error.empty())
    {
      return failed;
    }
    resumed = std::move(g.model);
    saved = std::move(g.state);
    resumedFile = g.file;
    if (resumedFile != path && newestProblem.empty())
    {
      newestProblem = named(path, "holds a step not every rank holds");
    }
  }
  FiberModel& work = checkpoint.resume ? resumed : model;
  CollisionSolverRun run(work, options, progress, observer, comm);
  if (checkpoint.resume)
  {
    // The state is checked on each rank and agreed on with the failing rank's file named, so that
    // every rank reports that file.
    failed.error = run.resume(saved,
      [&](const std::string& misfit) {
        return agree(comm, misfit.empty() ? misfit : named(resumedFile, "does not fit: " + misfit));
      });
    if (!failed.error.empty())
    {
      return failed;
    }
  }
  else if (!run.start())
  {
    return run.finish();
  }
  CollisionSolverResult result;
  bool written = true;
  while (run.step())
  {
    const CollisionSolverState& st = run.state();
    if (checkpoint.interval > 0 && st.steps % checkpoint.interval == 0)
    {
      const std::string problem =
        agree(comm, writeGeneration(path, work, st, options, fingerprint));
      if (!problem.empty())
      {
        result = run.finish();
        result.error = problem + " (at step " + formatNumber(st.steps) + ")";
        written = false;
        break;
      }
    }
  }
  if (written)
  {
    result = run.finish();
  }
  if (checkpoint.resume && result.error.empty()) // a failed resumed run leaves the caller's piece
  {
    model = std::move(resumed);
  }
  if (checkpoint.resume && resumedFile != path) // never silently: the newest file was not used
  {
    result.warnings.push_back(newestProblem + "; resumed from the previous generation '" +
      resumedFile + "' at step " + formatNumber(saved.steps));
  }
  return result;
}

} // namespace fiberpli
