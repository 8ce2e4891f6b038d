#include "Tissue/DiskPacking.h"

#include "Util/Random.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fiberpli
{

namespace
{
// Compression past jamming, relative to the best scale so far: deep enough that swaps have
// overlaps to remove (Gamma radii, s = 0.5, in a (30 µm)² cell at 0.85 separate at 1.019 / 1.025
// (seeds 42 / 7) after 1.06, 1.018 / 1.023 after 1.1).
constexpr double kOvercompression = 1.06;
// Compress–swap–decompress cycles, each compressed from the scale the previous one reached, and
// swap sweeps per cycle (each followed by a relaxation; they stop earlier when no swap helps).
// The 3-D solve is sensitive to the last 0.5 % of the scale: one cycle of 20 sweeps reaches
// 1.018 / 1.022 (seeds 42 / 7) at a third of the cost, too little for the (30 µm)³ Gamma cell at
// 0.85 to solve in 3 000 steps, which two cycles of 60 solve in 410 (bench/README.md,
// "Polydisperse seeding").
constexpr int kCycles = 2;
constexpr int kSwapRounds = 60;
// A scale this large leaves room enough (the dense targets' packings reach 1.02): no further
// cycle, which would only compress a loose packing (two populations at 0.72) into jamming.
constexpr double kAmpleScale = 1.05;
// Besides its contacts, every disk tries exchanges with this many disks anywhere: moving a large
// disk to a distant large hole is what raises the density most (1.009 → 1.019 for seed 42).
constexpr int kDistantPartners = 10;
// The scale is lowered in these steps until the disks separate.
constexpr double kScaleStep = 0.002;
constexpr int kRelaxIterations = 4000;
// A relaxation gives up when its energy has not halved in a window of iterations.
constexpr int kStallWindow = 200;
constexpr double kStallRatio = 0.5;
constexpr double kScaleCap = 1.1;

struct Vec
{
  double x, y;
};

class Packer
{
public:
  Packer(const std::vector<double>& radii, const DiskDomain& domain)
    : r_(radii)
    , a_(radii)
    , d_(domain)
    , p_(radii.size())
  {
    double sum = 0.0;
    for (double r : r_)
    {
      sum += r;
      rMax_ = std::max(rMax_, r);
    }
    rMean_ = sum / static_cast<double>(r_.size());
    // The grid is sized by the disks, but never finer than 4 cells per disk on average (nor
    // along one axis): a few disks in a large domain would otherwise allocate (domain / radius)²
    // cells. Dense packings (cells of 2 r̄ ≥ this bound) keep their grid.
    const double n = 4.0 * static_cast<double>(r_.size());
    minCell_ = std::max(std::sqrt(d_.width * d_.height / n), std::max(d_.width, d_.height) / n);
  }

  void randomStart(RandomStream& rng)
  {
    for (std::size_t i = 0; i < p_.size(); ++i)
    {
      const double x = rng.uniform() * d_.width;
      const double u = rng.uniform();
      double y = u * d_.height;
      if (!d_.periodicHeight)
      {
        const double lo = std::min(r_[i], 0.5 * d_.height);
        y = lo + u * (d_.height - 2.0 * lo);
      }
      p_[i] = { x, y };
    }
  }

  void setScale(double s)
  {
    scale_ = s;
    for (std::size_t i = 0; i < a_.size(); ++i)
      a_[i] = s * r_[i];
    buildGrid();
    buildPairs();
  }

  // FIRE (Bitzek et al. 2006) on the harmonic overlap energy at the current scale, unit masses.
  // True when every overlap is gone (the disks are separated at this scale).
  bool relax(int iterations)
  {
    std::vector<Vec> v(p_.size(), Vec{ 0.0, 0.0 }), f(p_.size());
    double dt = 0.1, alpha = 0.1;
    int positive = 0;
    double before = -1.0;
    for (int it = 0; it < iterations; ++it)
    {
      double energy = 0.0;
      if (forces(f, energy) == 0)
        return true;
      // Jammed (or so slow to separate that the next lower scale is cheaper): the energy no
      // longer halves in kStallWindow iterations.
      if (it % kStallWindow == 0)
      {
        if (before >= 0.0 && energy > kStallRatio * before)
          return false;
        before = energy;
      }
      double power = 0.0, vv = 0.0, ff = 0.0;
      for (std::size_t i = 0; i < p_.size(); ++i)
      {
        power += f[i].x * v[i].x + f[i].y * v[i].y;
        vv += v[i].x * v[i].x + v[i].y * v[i].y;
        ff += f[i].x * f[i].x + f[i].y * f[i].y;
      }
      if (ff < 1e-24 * rMean_ * rMean_)
        return false; // jammed: a mechanically stable overlapping state
      if (power > 0.0)
      {
        const double mix = alpha * std::sqrt(vv / ff);
        for (std::size_t i = 0; i < p_.size(); ++i)
        {
          v[i].x = (1.0 - alpha) * v[i].x + mix * f[i].x;
          v[i].y = (1.0 - alpha) * v[i].y + mix * f[i].y;
        }
        if (++positive > 5)
        {
          dt = std::min(1.1 * dt, 1.0);
          alpha *= 0.99;
        }
      }
      else
      {
        positive = 0;
        dt *= 0.5;
        alpha = 0.1;
        std::fill(v.begin(), v.end(), Vec{ 0.0, 0.0 });
      }
      double moved = 0.0;
      for (std::size_t i = 0; i < p_.size(); ++i)
      {
        v[i].x += dt * f[i].x;
        v[i].y += dt * f[i].y;
        p_[i].x += dt * v[i].x;
        p_[i].y += dt * v[i].y;
        const double dx = p_[i].x - built_[i].x, dy = p_[i].y - built_[i].y;
        moved = std::max(moved, dx * dx + dy * dy);
      }
      if (std::sqrt(moved) > 0.5 * skin())
      {
        buildGrid();
        buildPairs();
      }
    }
    double energy = 0.0;
    return forces(f, energy) == 0;
  }

  // One sweep of swap moves: every disk takes the place of the disk (one it touches, or one of
  // kDistantPartners drawn from rng anywhere) whose exchange lowers the overlap energy most, if
  // any. Exact energies from the cell grid. Returns the number of swaps.
  int swapSweep(RandomStream& rng)
  {
    buildGrid();
    // Energy of every disk with all its contacts; kept up to date around every exchange.
    std::vector<double> own(p_.size());
    for (std::size_t i = 0; i < p_.size(); ++i)
      own[i] = energyAt(i, p_[i], a_[i], i);
    int swaps = 0;
    for (std::size_t i = 0; i < p_.size(); ++i)
    {
      std::size_t best = i;
      double gain = 1e-12 * rMean_ * rMean_;
      const auto consider = [&](std::size_t j)
      {
        if (j == i || std::fabs(r_[j] - r_[i]) <= 1e-9 * rMean_)
          return;
        // The pair (i, j) itself keeps its energy.
        const double pair = 2.0 * pairEnergy(i, j);
        const double before = own[i] + own[j] - pair;
        if (before <= gain)
          return;
        const double after = energyAt(i, p_[j], a_[i], j) + energyAt(j, p_[i], a_[j], i);
        if (before - after > gain)
        {
          gain = before - after;
          best = j;
        }
      };
      visit(p_[i], a_[i], 0.0,
        [&](std::size_t j)
        {
          const Vec d = delta(p_[i], p_[j]);
          const double reach = a_[i] + a_[j];
          if (d.x * d.x + d.y * d.y < reach * reach)
            consider(j);
        });
      for (int k = 0; k < kDistantPartners; ++k)
        consider(std::min(
          p_.size() - 1, static_cast<std::size_t>(rng.uniform() * static_cast<double>(p_.size()))));
      if (best != i)
      {
        exchange(i, best);
        ++swaps;
        // Around each place, the neighbours of the disk that left it as well as of the one that
        // came: reach of the larger of the two radii.
        const double reach = std::max(a_[i], a_[best]);
        for (const std::size_t m : { i, best })
        {
          own[m] = energyAt(m, p_[m], a_[m], m);
          visit(p_[m], reach, 0.0, [&](std::size_t k) { own[k] = energyAt(k, p_[k], a_[k], k); });
        }
      }
    }
    buildPairs();
    return swaps;
  }

  const std::vector<Vec>& positions() const { return p_; }
  void setPositions(const std::vector<Vec>& p) { p_ = p; }

  // min over pairs of distance / (r_i + r_j) and over walls of the room / r_i, capped at
  // kScaleCap (the cell grid visits every pair closer than kScaleCap times the two largest radii).
  double exactScale()
  {
    setScale(1.0);
    double s = kScaleCap;
    for (std::size_t i = 0; i < p_.size(); ++i)
    {
      if (!d_.periodicHeight)
        s = std::min(s, std::min(p_[i].y, d_.height - p_[i].y) / r_[i]);
      visit(p_[i], kScaleCap * r_[i], (kScaleCap - 1.0) * rMax_,
        [&](std::size_t j)
        {
          if (j <= i)
            return;
          const Vec d = delta(p_[i], p_[j]);
          s = std::min(s, std::sqrt(d.x * d.x + d.y * d.y) / (r_[i] + r_[j]));
        });
    }
    return s;
  }

  std::vector<Seed2D> centres() const
  {
    std::vector<Seed2D> out(p_.size());
    for (std::size_t i = 0; i < p_.size(); ++i)
    {
      const double x = p_[i].x - d_.width * std::floor(p_[i].x / d_.width);
      double y = p_[i].y;
      if (d_.periodicHeight)
        y -= d_.height * std::floor(y / d_.height);
      out[i] = { x, y };
    }
    return out;
  }

private:
  double skin() const { return 0.3 * rMean_ * scale_; }

  // Minimum image of to − from. Positions are wrapped into the domain when the grid is built and
  // move less than a skin before the next build, so one period added or taken suffices.
  Vec delta(const Vec& from, const Vec& to) const
  {
    double dx = to.x - from.x, dy = to.y - from.y;
    dx += dx > 0.5 * d_.width ? -d_.width : dx < -0.5 * d_.width ? d_.width : 0.0;
    if (d_.periodicHeight)
      dy += dy > 0.5 * d_.height ? -d_.height : dy < -0.5 * d_.height ? d_.height : 0.0;
    return { dx, dy };
  }

  void wrap(Vec& q) const
  {
    q.x -= d_.width * std::floor(q.x / d_.width);
    if (d_.periodicHeight)
      q.y -= d_.height * std::floor(q.y / d_.height);
  }

  // Overlap energy of disk i (radius a) if it were at q, without its pair with `skip` (unchanged
  // by an exchange of i and skip).
  double energyAt(std::size_t i, const Vec& q, double a, std::size_t skip) const
  {
    double e = 0.0;
    if (!d_.periodicHeight)
    {
      const double lo = a - q.y, hi = q.y + a - d_.height;
      e += lo > 0.0 ? 0.5 * lo * lo : 0.0;
      e += hi > 0.0 ? 0.5 * hi * hi : 0.0;
    }
    visit(q, a, 0.0,
      [&](std::size_t k)
      {
        if (k == i || k == skip)
          return;
        const Vec d = delta(q, p_[k]);
        const double o = a + a_[k] - std::sqrt(d.x * d.x + d.y * d.y);
        if (o > 0.0)
          e += 0.5 * o * o;
      });
    return e;
  }

  double pairEnergy(std::size_t i, std::size_t j) const
  {
    const Vec d = delta(p_[i], p_[j]);
    const double o = a_[i] + a_[j] - std::sqrt(d.x * d.x + d.y * d.y);
    return o > 0.0 ? 0.5 * o * o : 0.0;
  }

  void exchange(std::size_t i, std::size_t j)
  {
    std::swap(cells_[cellOf_[i]][slot_[i]], cells_[cellOf_[j]][slot_[j]]);
    std::swap(cellOf_[i], cellOf_[j]);
    std::swap(slot_[i], slot_[j]);
    std::swap(p_[i], p_[j]);
    cellMax_[cellOf_[i]] = std::max(cellMax_[cellOf_[i]], a_[i]);
    cellMax_[cellOf_[j]] = std::max(cellMax_[cellOf_[j]], a_[j]);
  }

  // Forces of the overlap energy into f, the energy into energy; returns the number of
  // overlapping pairs and walls.
  int forces(std::vector<Vec>& f, double& energy) const
  {
    std::fill(f.begin(), f.end(), Vec{ 0.0, 0.0 });
    int overlaps = 0;
    energy = 0.0;
    for (const auto& [i, j] : pairs_)
    {
      const Vec d = delta(p_[i], p_[j]);
      const double dist = std::sqrt(d.x * d.x + d.y * d.y);
      const double o = a_[i] + a_[j] - dist;
      if (o <= 0.0)
        continue;
      ++overlaps;
      energy += 0.5 * o * o;
      // Coincident centres: any fixed direction separates them.
      const double ux = dist > 0.0 ? d.x / dist : 1.0, uy = dist > 0.0 ? d.y / dist : 0.0;
      f[i].x -= o * ux;
      f[i].y -= o * uy;
      f[j].x += o * ux;
      f[j].y += o * uy;
    }
    if (!d_.periodicHeight)
    {
      for (std::size_t i = 0; i < p_.size(); ++i)
      {
        const double lo = a_[i] - p_[i].y, hi = p_[i].y + a_[i] - d_.height;
        if (lo > 0.0)
        {
          f[i].y += lo;
          energy += 0.5 * lo * lo;
          ++overlaps;
        }
        if (hi > 0.0)
        {
          f[i].y -= hi;
          energy += 0.5 * hi * hi;
          ++overlaps;
        }
      }
    }
    return overlaps;
  }

  // Cell index along one axis (periodic: wrapped; walls: clamped).
  int cellIndex(double t, double extent, int n, bool periodic) const
  {
    if (periodic)
      t -= extent * std::floor(t / extent);
    return std::clamp(static_cast<int>(t / extent * n), 0, n - 1);
  }

  void buildGrid()
  {
    const double cell = std::max(2.0 * rMean_ * scale_, minCell_);
    nx_ = std::max(1, static_cast<int>(d_.width / cell));
    ny_ = std::max(1, static_cast<int>(d_.height / cell));
    cells_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), {});
    cellMax_.assign(cells_.size(), 0.0);
    cellOf_.resize(p_.size());
    slot_.resize(p_.size());
    for (std::size_t i = 0; i < p_.size(); ++i)
    {
      wrap(p_[i]);
      const std::size_t c =
        static_cast<std::size_t>(cellIndex(p_[i].y, d_.height, ny_, d_.periodicHeight)) *
          static_cast<std::size_t>(nx_) +
        static_cast<std::size_t>(cellIndex(p_[i].x, d_.width, nx_, true));
      cellOf_[i] = c;
      cellMax_[c] = std::max(cellMax_[c], a_[i]);
      slot_[i] = cells_[c].size();
      cells_[c].push_back(i);
    }
  }

  // Calls f(j) for every disk j (each once) of the cells that may hold a disk closer than
  // a + r_j + extra to q: the cells within reach of the largest disk, less those whose own largest
  // disk is too far (a broad distribution's few large disks would otherwise widen every search).
  template <class F>
  void visit(const Vec& q, double a, double extra, F&& f) const
  {
    const double cx = d_.width / nx_, cy = d_.height / ny_;
    const double reach = a + rMax_ * scale_ + extra;
    const int rx = static_cast<int>(std::ceil(reach / cx)),
              ry = static_cast<int>(std::ceil(reach / cy));
    const int ix = cellIndex(q.x, d_.width, nx_, true);
    const int iy = cellIndex(q.y, d_.height, ny_, d_.periodicHeight);
    const bool allX = 2 * rx + 1 >= nx_;
    const bool allY = d_.periodicHeight ? 2 * ry + 1 >= ny_ : false;
    const int x0 = allX ? 0 : ix - rx, x1 = allX ? nx_ - 1 : ix + rx;
    const int y0 = allY ? 0 : (d_.periodicHeight ? iy - ry : std::max(0, iy - ry));
    const int y1 = allY ? ny_ - 1 : (d_.periodicHeight ? iy + ry : std::min(ny_ - 1, iy + ry));
    // q in the frame of the unwrapped cell indices around (ix, iy).
    const double qx = q.x - d_.width * std::floor(q.x / d_.width);
    const double qy = d_.periodicHeight ? q.y - d_.height * std::floor(q.y / d_.height) : q.y;
    for (int y = y0; y <= y1; ++y)
    {
      const int wy = ((y % ny_) + ny_) % ny_;
      const double gy = allY ? 0.0 : std::max({ 0.0, y * cy - qy, qy - (y + 1) * cy });
      for (int x = x0; x <= x1; ++x)
      {
        const int wx = ((x % nx_) + nx_) % nx_;
        const std::size_t c = static_cast<std::size_t>(wy) * static_cast<std::size_t>(nx_) +
          static_cast<std::size_t>(wx);
        const double gx = allX ? 0.0 : std::max({ 0.0, x * cx - qx, qx - (x + 1) * cx });
        const double room = a + cellMax_[c] + extra;
        if (gx * gx + gy * gy > room * room)
          continue;
        for (std::size_t j : cells_[c])
          f(j);
      }
    }
  }

  // The pairs closer than a_i + a_j + skin, for the relaxation until some disk has moved half a
  // skin.
  void buildPairs()
  {
    pairs_.clear();
    built_ = p_;
    const double s = skin();
    for (std::size_t i = 0; i < p_.size(); ++i)
    {
      visit(p_[i], a_[i], s,
        [&](std::size_t j)
        {
          if (j <= i)
            return;
          const Vec d = delta(p_[i], p_[j]);
          const double reach = a_[i] + a_[j] + s;
          if (d.x * d.x + d.y * d.y < reach * reach)
            pairs_.emplace_back(i, j);
        });
    }
  }

  std::vector<double> r_, a_;
  DiskDomain d_;
  std::vector<Vec> p_, built_;
  double rMax_ = 0.0, rMean_ = 0.0, scale_ = 1.0, minCell_ = 0.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
  std::vector<double> cellMax_; // largest current radius in each cell (an upper bound after swaps)
  std::vector<std::size_t> cellOf_, slot_;
  std::vector<std::pair<std::size_t, std::size_t>> pairs_;
};
} // namespace

double diskPackingBytes(double disks)
{
  // Per disk: radii (2), positions (current, at the last pair build, kept), velocities and forces
  // (2 doubles each), cell and slot (2), its swap energy, ~4 grid cells (a vector and a maximum
  // each) and ~4 near pairs (2 indices each).
  constexpr double perDisk = 8.0 * (2 + 5 * 2 + 2 + 1) + 4.0 * (24.0 + 8.0) + 4.0 * 16.0;
  return perDisk * disks;
}

DiskPacking packDisks(const std::vector<double>& radii, const DiskDomain& domain,
  std::uint64_t seed, std::uint64_t key, const ProgressFn& progress)
{
  DiskPacking out;
  if (radii.empty() || !(domain.width > 0.0) || !(domain.height > 0.0) ||
    !std::isfinite(domain.width) || !std::isfinite(domain.height))
    return out;
  for (double r : radii)
    if (!(r > 0.0) || !std::isfinite(r))
      return out;
  Packer packer(radii, domain);
  RandomStream rng(seed, key, 0);
  packer.randomStart(rng);
  double best = 0.0;
  std::vector<Vec> kept = packer.positions();
  // Progress after every relaxation and at the end of every cycle: cycle by cycle, 90 % of a cycle
  // for its swap rounds, the rest for the decompression. It only reads the state, so the packing
  // does not depend on it.
  const auto goOn = [&](int cycle, double withinCycle)
  { return reportProgress(progress, (cycle + std::min(1.0, withinCycle)) / kCycles); };
  for (int cycle = 0; cycle < kCycles && best < kAmpleScale; ++cycle)
  {
    // Past jamming, swap until no exchange lowers the energy (or the rounds run out) …
    const double top = std::max(1.0, best) * kOvercompression;
    packer.setScale(top);
    packer.relax(kRelaxIterations);
    for (int round = 0; round < kSwapRounds && packer.swapSweep(rng) > 0; ++round)
    {
      packer.relax(kRelaxIterations);
      if (!goOn(cycle, 0.9 * (round + 1) / kSwapRounds))
        return DiskPacking{ {}, 0.0, true };
    }
    // … then down to the first scale at which the disks separate (or to 1, overlapping).
    for (double s = top;; s -= kScaleStep)
    {
      packer.setScale(std::max(1.0, s));
      if (packer.relax(kRelaxIterations) || s <= 1.0)
        break;
      if (!goOn(cycle, 0.9 + 0.1 * (top - s) / (top - 1.0)))
        return DiskPacking{ {}, 0.0, true };
    }
    const double reached = packer.exactScale();
    if (reached > best)
    {
      best = reached;
      kept = packer.positions();
    }
    if (!goOn(cycle, 1.0))
      return DiskPacking{ {}, 0.0, true };
  }
  packer.setPositions(kept);
  out.scale = best;
  out.centres = packer.centres();
  return out;
}

} // namespace fiberpli
