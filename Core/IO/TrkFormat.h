/// TrkFormat: TrackVis `.trk` streamlines, read only (docs/api.md §4; TrackVis file
/// format page, trackvis.org/docs/?subsect=fileformat, and nibabel.streamlines.trk).
///
/// Header, 1000 bytes (offsets in bytes): id_string[6] "TRACK" (0), short dim[3] (6),
/// float voxel_size[3] (12), float origin[3] (24, unused by TrackVis), short n_scalars (36),
/// char scalar_name[10][20] (38), short n_properties (238), char property_name[10][20] (240),
/// float vox_to_ras[4][4] row-major (440), reserved (504), char voxel_order[4] (948), pad2 (952),
/// image_orientation_patient[6] (956), pad1 (980), invert/swap flags (982), int n_count (988,
/// 0 = not stored), int version (992, 1 or 2), int hdr_size (996, must be 1000). The byte order
/// is the one in which hdr_size reads 1000.
/// Body, per track: int32 n, then n × (x, y, z, n_scalars floats), then n_properties floats.
///
/// Coordinates: track points are stored in "voxmm" space: millimetres along the voxel axes of the
/// reference image, measured from the CORNER of voxel (0,0,0), so the centre of voxel i lies at
/// (i + 0.5) · voxel_size. The transform applied here is nibabel's (get_affine_trackvis_to_rasmm):
///   1. v = p / voxel_size − 0.5          (continuous voxel index, voxel centres at integers);
///   2. if voxel_order (e.g. "LPS"; empty means "LPS", as in nibabel) disagrees with the axis
///      directions of vox_to_ras, permute/flip v to the affine's voxel axes: a flipped axis of
///      length dim becomes (dim − 1 − v);
///   3. world = vox_to_ras · (v, 1).
/// When vox_to_ras was not recorded (vox_to_ras[3][3] == 0, old TrackVis files), vox_to_ras is
/// taken as diag(voxel_size, 1) — voxel axes scaled by the voxel size, as TrackVis itself displays
/// such files — so world = p − voxel_size / 2, and step 2 is skipped. Units stay those of the file
/// (mm); there is no conversion to µm. Scalars and properties are skipped; radii are not stored:
/// every point gets defaultRadius.
#pragma once

#include "IO/FiberReadResult.h"

#include <istream>
#include <string>

namespace fiberpli
{

/// Reads a .trk stream; fileName is only used in messages. Fiber ids are track positions in the
/// file, bundle 0 for all; tracks of fewer than 2 points are dropped and counted. Errors name the
/// byte offset: file shorter than the header, wrong magic, hdr_size not 1000 in either byte
/// order, unsupported version, voxel_size not finite and > 0, non-finite vox_to_ras, negative
/// n_scalars/n_properties/n_count/point count, a track larger than the rest of the file (checked
/// before allocating), non-finite coordinates, n_count disagreeing with the tracks present,
/// defaultRadius not finite and > 0.
FiberReadResult readTrk(std::istream& in, const std::string& fileName, double defaultRadius);

/// Content sniffing for CanReadFile: "TRACK" magic and hdr_size 1000 (either byte order) in the
/// first 1000 bytes. The stream position is restored.
bool looksLikeTrk(std::istream& in);

} // namespace fiberpli
