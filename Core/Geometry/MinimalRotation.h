/// MinimalRotation: the rotation that takes one unit direction to another along the shortest arc.
/// Both discrete parallel transports of the project use it: the bundle cross-section frames
/// (Tissue/Trajectory, docs/tissue-models.md §2) and the ring frames of the tube mesh
/// (Mesh/TubeMesher).
#pragma once

#include "Geometry/Vec3.h"

namespace fiberpli
{

/// The minimal rotation taking unit vector a to unit vector b, applied to w (Rodrigues about
/// a × b). It is linear in w, so transporting two frame axes separately keeps them orthonormal.
/// Hairpin rule (b = −a, a 180° reversal where a × b vanishes and fastPLI aborts) [ours]: rotation
/// by π about unit(a × e_m), e_m the coordinate axis least aligned with a — a proper rotation that
/// depends only on a, never on w.
Vec3 rotateMinimal(const Vec3& a, const Vec3& b, const Vec3& w);

} // namespace fiberpli
