/// PLITypes: the value types shared by the 3D-PLI simulation (docs/pli-simulation.md §7.2); the
/// lattice, the pixel and column ranges, the radius taper and the tilt convention are those of
/// Core/Section. Units: µm, nm for the wavelength, 1/mm for absorption, radians inside Core.
#pragma once

#include "Section/LinkTable.h"
#include "Section/PixelGrid.h"
#include "Section/SectionLattice.h"
#include "Section/TiltConvention.h"
#include "Util/Status.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{
namespace pli
{

/// Optic-axis model of one layer (§3.2): p = parallel, r = radial, b = isotropic.
enum class AxisModel : std::uint8_t
{
  Background,
  Parallel,
  Radial
};

/// One concentric layer (§3.2): covers s_{l-1}·r < ρ <= scale·r of the local fiber radius r.
/// An inner-radius layer (§3.2, myelinated fibers) covers ρ <= the local inner_radius instead
/// (the axon; `scale` 1 is then only its upper bound).
struct Layer
{
  double scale = 1.0;
  double dn = -0.001;
  double muPerMm = 0.0;
  AxisModel model = AxisModel::Parallel;
  bool innerRadius = false;
};

/// Optic-axis interpolation (§4.5).
enum class Interp : std::uint8_t
{
  NN,
  Lerp,
  Slerp
};

/// Ray step lengths (§4.4).
enum class StepRule : std::uint8_t
{
  ExactLength,
  FastPLIMidpoint
};

/// What tilted rays see outside the lateral VOI (§2.1 Core switches).
enum class LateralOutside : std::uint8_t
{
  SampleFibers,
  Background
};

/// Layers of every bundle (§3.2). Slot b belongs to bundleIds[b] (sorted, distinct); labels are
/// 1 + b·L + l with L = max layer count; label 0 is the embedding medium (Δn 0, backgroundMu).
struct TissueSpec
{
  std::vector<int> bundleIds;
  std::vector<std::vector<Layer>> layers;
  double backgroundMu = 0.0;
  RadiusModel radius = RadiusModel::Linear;

  int maxLayers() const;
  int labelCount() const { return 1 + static_cast<int>(bundleIds.size()) * maxLayers(); }
  /// Slot of a bundle id, -1 when the bundle has no layers.
  int slotOf(int bundleId) const;
};

/// One view (§4.3): in-tissue tilt θ_t and tilt azimuth φ_t, radians. (0, 0) = untilted.
/// stretch: 1 = the image registered onto the sample's pixel grid (every ray crosses the section's
/// mid-plane at its column centre); s > 1 = the tilted sensor (§4.6): the ray of sensor column m
/// crosses the mid-plane at c + s·((m − c)·d)·d + (m − c − ((m − c)·d)·d), c the image centre and d
/// the tilt azimuth, s = 1/cos τ of the stage tilt τ.
struct View
{
  double theta = 0.0;
  double phi = 0.0;
  double stretch = 1.0;
};

/// Light propagation settings (§4, §6.1).
struct SimParams
{
  double wavelengthNm = 525.0;
  double lightIntensity = 26000.0;
  double step = 1.0;       ///< voxels
  std::vector<double> rho; ///< polarizer angles, radians
  Interp interp = Interp::Slerp;
  TiltConvention conv = TiltConvention::Physical;
  StepRule stepRule = StepRule::ExactLength;
  LateralOutside lateral = LateralOutside::SampleFibers;
  int tile = 64;   ///< B of the column tiles (§3.5)
  int threads = 0; ///< 0 = all cores
};

/// Image stack of one view: value of column/pixel (x0 + i, y0 + j) and rotation k at
/// data[(j·nx + i)·nrho + k] (x fastest, §4.4).
struct Stack
{
  std::int64_t x0 = 0, y0 = 0; ///< global index of the first column/pixel
  std::int64_t nx = 0, ny = 0;
  int nrho = 0;
  std::vector<double> data;

  void resize(const GridRange& r, int rotations)
  {
    x0 = r.i0;
    y0 = r.j0;
    nx = r.nx();
    ny = r.ny();
    nrho = rotations;
    data.assign(static_cast<std::size_t>(nx * ny * nrho), 0.0);
  }
  double& at(std::int64_t i, std::int64_t j, int k)
  {
    return data[static_cast<std::size_t>(((j - y0) * nx + (i - x0)) * nrho + k)];
  }
  const double* ptr(std::int64_t i, std::int64_t j) const
  {
    return data.data() + ((j - y0) * nx + (i - x0)) * nrho;
  }
  double at(std::int64_t i, std::int64_t j, int k) const
  {
    return data[static_cast<std::size_t>(((j - y0) * nx + (i - x0)) * nrho + k)];
  }
};

} // namespace pli
} // namespace fiberpli
