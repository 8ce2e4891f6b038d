// Regression image: the paper's crossing, Y-shape and chiasm-like models (FiberBundleSource,
// small), solved by FiberCollisionSolver, side by side as tubes coloured by bundle_id.
#include "ImageTestUtil.h"
#include "vtkFiberBundleSource.h"
#include "vtkFiberCollisionSolver.h"

#include <vtkCamera.h>

int main(int argc, char* argv[])
{
  vtkNew<vtkRenderer> renderer;
  const int shapes[3] = { vtkFiberBundleSource::CROSSING, vtkFiberBundleSource::YSHAPE,
    vtkFiberBundleSource::CHIASM };
  for (int i = 0; i < 3; ++i)
  {
    vtkNew<vtkFiberBundleSource> source;
    source->SetShape(shapes[i]);
    source->SetBundleRadius(4.0);
    source->SetLength(24.0);
    source->SetFiberRadius(0.8);
    source->SetRadiusSpread(0.0);
    source->SetFiberSpacing(2.0);
    source->SetNumberOfFibers(0);
    source->SetSegmentLength(2.0);
    source->SetDisplacement(0.2);
    source->SetCrossingAngle(shapes[i] == vtkFiberBundleSource::YSHAPE ? 60.0 : 90.0);
    source->SetUncrossedFraction(0.25);
    source->SetRanvierSpacing(-1.0);
    source->SetSeed(5);
    vtkNew<vtkFiberCollisionSolver> solver;
    solver->SetInputConnection(source->GetOutputPort());
    solver->SetSegmentLength(2.0);
    solver->SetMaxSteps(5000);
    solver->SetNumberOfThreads(2);
    vtkSmartPointer<vtkActor> actor = fiberpli_test::bundleTubesActor(solver, 10, 3);
    actor->SetPosition(-32.0 + 32.0 * i, 0.0, 0.0);
    renderer->AddActor(actor);
  }
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, -30, 115);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();

  return fiberpli_test::renderAndCompare(argc, argv, renderer);
}
