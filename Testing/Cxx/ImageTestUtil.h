// Shared by the regression-image tests: fibers as tubes coloured by bundle_id, and the window that
// renders and compares against the baseline given on the command line (-V, -T).
#pragma once

#include "vtkFiberTubes.h"

#include <vtkActor.h>
#include <vtkAlgorithm.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

namespace fiberpli_test
{
// An actor of `fibers` as tubes with `sides` sides, coloured by bundle_id over [0, lastBundle].
inline vtkSmartPointer<vtkActor> bundleTubesActor(vtkAlgorithm* fibers, int sides, int lastBundle)
{
  vtkNew<vtkFiberTubes> tubes;
  tubes->SetInputConnection(fibers->GetOutputPort());
  tubes->SetNumberOfSides(sides);
  tubes->SetNumberOfThreads(1);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(tubes->GetOutputPort());
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray("bundle_id");
  mapper->SetScalarRange(0, lastBundle);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

// Renders `renderer` in a 400 x 300 window and compares it with the baseline; the exit code of the
// test (0 = image matches). The clipping range is reset after the first render, once every
// pipeline has run and the bounds are final.
inline int renderAndCompare(int argc, char* argv[], vtkRenderer* renderer)
{
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  window->Render();
  renderer->ResetCameraClippingRange();
  window->Render();

  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return !result;
}
} // namespace fiberpli_test
