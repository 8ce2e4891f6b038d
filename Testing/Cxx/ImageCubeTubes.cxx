// Regression image: a small 3-population cube rendered as tubes coloured by bundle_id.
#include "ImageTestUtil.h"
#include "vtkFiberCubeSource.h"

#include <vtkCamera.h>

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
  vtkSmartPointer<vtkActor> actor = fiberpli_test::bundleTubesActor(cube, 12, 2);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(45, 35, 55);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();

  return fiberpli_test::renderAndCompare(argc, argv, renderer);
}
