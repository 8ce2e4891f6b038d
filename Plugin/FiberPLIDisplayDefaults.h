// Display defaults of FiberPLI outputs in every ParaView client (GUI, pvpython, pvbatch).
#ifndef FiberPLIDisplayDefaults_h
#define FiberPLIDisplayDefaults_h

/// Called once when the plugin loads (paraview_add_plugin INITIALIZERS): from then on every new
/// representation of a FiberPLI output starts with the colouring that output needs:
/// - fiber orientation maps (`fom`, RGB bytes) and their legend: true colour (Map Scalars off);
/// - PLISimulation's `intensity` stack: component 0 in grey, not the Magnitude of 18 angles;
/// - fibers and tubes (cell arrays `fiber_id` and `bundle_id`): `bundle_id` as categories, one
///   fixed colour per value in the one `bundle_id` table that only gains categories (a one-bundle
///   model shown later leaves the others' colours alone);
/// - `direction` (0 deg = 180 deg) of PLIAnalysis and the ground truth: a cyclic table over [0,
/// 180];
/// - a display made while its output is empty (an aborted first run) gets this colouring at the
///   first update that brings data, instead of staying in ParaView's plain colour.
/// Only the starting state is set; the user changes it as any other display property.
void fiberpli_display_defaults_init();

#endif
