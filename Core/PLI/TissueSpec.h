/// TissueSpec construction: the `Layers` property grammar and its validation
/// (docs/pli-simulation.md §3.2).
#pragma once

#include "PLI/PLITypes.h"

#include <string>
#include <vector>

namespace fiberpli
{
namespace pli
{

/// Builds the layer table for the given bundle ids (any order, duplicates allowed) from the
/// `Layers` text of §3.2: groups separated by '|', optional "<bundle_id>:" prefix, ';'-separated
/// tuples "scale dn mu model" (model p, r or b). Empty text = one layer (1, defaultDn, defaultMu,
/// p) for every bundle — or, with `myelin` (the model carries inner_radius), two: the axon inside
/// the inner radius (isotropic, Δn 0, μ defaultMu) and the myelin sheath up to the radius (radial,
/// Δn −defaultDn, μ defaultMu). A non-empty text is used as it is. Errors name the group/tuple and
/// the value; warnings follow §3.2 (unsorted, scale > 1, sign of Δn against the model).
Status makeTissueSpec(const std::string& layersText, const std::vector<int>& bundleIds,
  double defaultDn, double defaultMu, double backgroundMu, TissueSpec& spec, bool myelin = false);

/// Checks a layer list (§3.2) and sorts it by scale. `where` prefixes messages.
Status validateLayers(std::vector<Layer>& layers, const std::string& where);

} // namespace pli
} // namespace fiberpli
