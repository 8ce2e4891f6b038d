/**
 * @class   FiberExecutions
 * @brief   the FiberPLI executions running now in this process, so that a GUI abort reaches them
 *
 * Every FiberPLI RequestData opens an AbortScope (FiberProgress.h), which enters its algorithm
 * here for the time of the execution. Abort() asks exactly those algorithms to stop (their
 * progress callbacks then return false, the Core stops at its next check and the AbortScope clears
 * the request when the execution ends), so an abort never lingers on an algorithm that is not
 * running. ParaView 5.11's abort button is connected to nothing; the plugin's Qt part
 * (Plugin/FiberPLIAbortButton.h) connects it to Abort(). Used from the thread that executes the
 * pipeline (in the GUI: the GUI thread, also for the click that aborts).
 */
#ifndef FiberExecutions_h
#define FiberExecutions_h

#include "FiberPLIConversionModule.h" // for export macro

class vtkAlgorithm;

namespace fiberpli
{

class FIBERPLICONVERSION_EXPORT FiberExecutions
{
public:
  /// An execution of `algorithm` starts / ends (AbortScope calls these; nesting is allowed).
  static void Enter(vtkAlgorithm* algorithm);
  static void Leave(vtkAlgorithm* algorithm);
  /// True while any FiberPLI execution runs in this process.
  static bool Running();
  /// Asks every running execution to stop; returns how many were asked.
  static int Abort();
};

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberExecutions.h
