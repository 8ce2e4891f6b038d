/// RayMarcher: Müller-matrix light propagation of one ray through a voxelised block
/// (docs/pli-simulation.md §4.2–§4.4): Stokes vectors for every polarizer angle, tilted views, step
/// rule, label-aware axis sampling.
#pragma once

#include "PLI/PLITypes.h"
#include "PLI/Voxeliser.h"

#include <cstdint>
#include <vector>

namespace fiberpli
{
namespace pli
{

/// Per-label optical properties (§3.2): row 0 = embedding medium.
struct LabelProps
{
  std::vector<double> dn;
  std::vector<double> mu; ///< 1/mm
  static LabelProps fromSpec(const TissueSpec& spec);
};

/// Everything of one view that does not depend on the column: beam direction L, rotation R
/// (§4.3), step lengths and sample offsets (§4.4), cos 2ρ_k / sin 2ρ_k.
class RayMarcher
{
public:
  RayMarcher(const SectionLattice& lattice, const SimParams& params, const View& view,
    const LabelProps& props);

  /// Lateral reach of the ray around its column centre, voxels (ceil((n_z/2)·tan θ_t)).
  static std::int64_t lateralReach(std::int64_t nz, double theta);
  std::int64_t numberOfSteps() const { return static_cast<std::int64_t>(len_.size()); }

  /// SectionLattice position (voxel units, lateral) where the ray of column (i, j) crosses the
  /// section's mid-plane: the column centre, or on the tilted sensor its stretched image
  /// (View::stretch).
  void midPlanePoint(std::int64_t i, std::int64_t j, double out[2]) const;

  /// Columns holding the mid-plane points of the rays of `cols` (grown by 1 on the tilted sensor,
  /// where they are not column centres, so the halo of §3.5 still covers every sample).
  GridRange midPlaneColumns(const GridRange& cols) const;

  /// Marches the ray of column (i, j) through `block` and writes I(ρ_k) = ½(S0 − S1) for every k
  /// to out[0..nrho). `clamp` = lateral stencil bounds for interpolation (see sampleAxis).
  void march(const TissueBlock& block, std::int64_t i, std::int64_t j, const GridRange& clamp,
    double* out) const;

private:
  SectionLattice lat_;
  SimParams par_;
  LabelProps props_;
  bool tilted_ = false;
  double L_[3] = { 0, 0, 1 };
  double B_[3][3]; ///< v_b = B·v
  double p0off_[2] = { 0, 0 };
  double dir_[2] = { 1, 0 };      ///< tilt azimuth d
  double stretch_ = 1.0;          ///< View::stretch
  double centre_[2] = { 0, 0 };   ///< image centre c, voxel units
  std::vector<double> len_, mid_; ///< step lengths and midpoint distances along the ray (voxels)
  std::vector<double> c2r_, s2r_;
};

} // namespace pli
} // namespace fiberpli
