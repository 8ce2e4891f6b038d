// Regression image: a small 3-population cube rendered as tubes coloured by bundle_id.
#include "vtkFiberCubeSource.h"
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
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(3);
  cube->SetNumberOfFibers(60);
  cube->SetEdgeLength(24.0);
  cube->SetFiberRadius(0.8);
  cube->SetSegmentLength(2.0);
  cube->SetDisplacement(0.5);
  cube->SetSeed(1);
  vtkNew<vtkFiberTubes> tubes;
  tubes->SetInputConnection(cube->GetOutputPort());
  tubes->SetNumberOfSides(12);
  tubes->SetNumberOfThreads(1);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(tubes->GetOutputPort());
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray("bundle_id");
  mapper->SetScalarRange(0, 2);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(45, 35, 55);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();

  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  window->Render();

  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return !result;
}
