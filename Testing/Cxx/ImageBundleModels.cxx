// Regression image: the paper's crossing, Y-shape and chiasm-like models (FiberBundleSource, small),
// solved by FiberCollisionSolver, side by side as tubes coloured by bundle_id.
#include "vtkFiberBundleSource.h"
#include "vtkFiberCollisionSolver.h"
#include "vtkFiberTubes.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

int main(int argc, char* argv[])
{
  vtkNew<vtkRenderer> renderer;
  const int shapes[3] = { vtkFiberBundleSource::CROSSING, vtkFiberBundleSource::YSHAPE, vtkFiberBundleSource::CHIASM };
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
    vtkNew<vtkFiberTubes> tubes;
    tubes->SetInputConnection(solver->GetOutputPort());
    tubes->SetNumberOfSides(10);
    tubes->SetNumberOfThreads(1);

    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(tubes->GetOutputPort());
    mapper->SetScalarModeToUseCellFieldData();
    mapper->SelectColorArray("bundle_id");
    mapper->SetScalarRange(0, 3);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
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
