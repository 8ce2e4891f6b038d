#include "vtkFiberTubes.h"

#include "FiberAdapter.h"
#include "FiberGuard.h"
#include "FiberInnerRadii.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "Mesh/TubeMesher.h"
#include "Model/DataNames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>

vtkStandardNewMacro(vtkFiberTubes);

//------------------------------------------------------------------------------
int vtkFiberTubes::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Any exception escaping the work becomes a VTK error (FiberGuard.h), never an abort.
  return fiberpli::GuardRequest(this, outputVector, fiberpli::ProxyName(this),
    [&]() -> int
    {
      const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
      if (!fiberpli::CheckThreads(this, this->NumberOfThreads))
      {
        return 0;
      }
      vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
      vtkPolyData* output = vtkPolyData::GetData(outputVector);
      output->Initialize();
      if (fiberpli::FiberPolyData::IsEmpty(input))
      {
        return 1;
      }

      fiberpli::FiberConversion in =
        fiberpli::FiberPolyData::ToModel(input, fiberpli::ProxyName(this));
      if (!in.ok())
      {
        vtkErrorMacro(<< in.error);
        return 0;
      }
      if (!in.warning.empty())
      {
        vtkWarningMacro(<< in.warning);
      }
      if (this->InnerTubes)
      {
        const std::string innerError =
          fiberpli::ReadInnerRadii(input, in, fiberpli::ProxyName(this));
        if (!innerError.empty())
        {
          vtkErrorMacro(<< innerError);
          return 0;
        }
      }

      this->SetProgressText("Meshing tubes");
      fiberpli::TubeOptions options;
      options.sides = this->NumberOfSides;
      options.capping = this->Capping;
      options.innerTubes = this->InnerTubes;
      options.numberOfThreads = this->NumberOfThreads;
      const std::string optionError = fiberpli::checkTubeOptions(options);
      if (!optionError.empty())
      {
        fiberpliErrorMacro(<< optionError);
        return 0;
      }
      const fiberpli::TubeMesh mesh =
        fiberpli::meshTubes(in.model, options, fiberpli::MakeProgress(this, 0.0, 0.8));
      if (mesh.aborted)
      {
        return 1;
      }

      const auto numPoints = static_cast<vtkIdType>(mesh.numberOfPoints());
      const auto numTriangles = static_cast<vtkIdType>(mesh.numberOfTriangles());
      vtkNew<vtkDoubleArray> coords;
      coords->SetNumberOfComponents(3);
      coords->SetNumberOfTuples(numPoints);
      std::copy(mesh.points.begin(), mesh.points.end(), coords->GetPointer(0));
      vtkNew<vtkPoints> points;
      points->SetData(coords);

      vtkNew<vtkFloatArray> normals;
      normals->SetName("Normals");
      normals->SetNumberOfComponents(3);
      normals->SetNumberOfTuples(numPoints);
      std::copy(mesh.normals.begin(), mesh.normals.end(), normals->GetPointer(0));

      vtkNew<vtkIdTypeArray> offsets;
      offsets->SetNumberOfTuples(numTriangles + 1);
      for (vtkIdType t = 0; t <= numTriangles; ++t)
      {
        offsets->SetValue(t, 3 * t);
      }
      vtkNew<vtkIdTypeArray> connectivity;
      connectivity->SetNumberOfTuples(3 * numTriangles);
      std::copy(mesh.triangles.begin(), mesh.triangles.end(), connectivity->GetPointer(0));
      vtkNew<vtkCellArray> polys;
      polys->SetData(offsets, connectivity);

      vtkNew<vtkIdTypeArray> fiberId;
      fiberId->SetName(fiberpli::fiberfield::kFiberId);
      fiberId->SetNumberOfTuples(numTriangles);
      vtkNew<vtkIntArray> bundleId;
      bundleId->SetName(fiberpli::fiberfield::kBundleId);
      bundleId->SetNumberOfTuples(numTriangles);
      for (vtkIdType t = 0; t < numTriangles; ++t)
      {
        const fiberpli::Fiber& f =
          in.model
            .fibers[static_cast<std::size_t>(mesh.triangleFiber[static_cast<std::size_t>(t)])];
        fiberId->SetValue(t, static_cast<vtkIdType>(f.id));
        bundleId->SetValue(t, f.bundle);
      }
      this->UpdateProgress(1.0);

      output->SetPoints(points);
      output->SetPolys(polys);
      output->GetPointData()->SetNormals(normals);
      output->GetCellData()->AddArray(fiberId);
      output->GetCellData()->AddArray(bundleId);
      if (this->InnerTubes)
      {
        vtkNew<vtkUnsignedCharArray> surface;
        surface->SetName("tube_surface");
        surface->SetNumberOfTuples(numTriangles);
        std::copy(mesh.triangleSurface.begin(), mesh.triangleSurface.end(), surface->GetPointer(0));
        output->GetCellData()->AddArray(surface);
      }
      output->GetCellData()->SetActiveScalars(fiberpli::fiberfield::kBundleId);
      // The model's field data (solved, collisions, periodic_cell, seed, …) describe the tubes as
      // well: a saved tubes file still says what it is.
      output->GetFieldData()->PassData(input->GetFieldData());
      return 1;
    });
}

//------------------------------------------------------------------------------
void vtkFiberTubes::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSides: " << this->NumberOfSides << "\n";
  os << indent << "Capping: " << this->Capping << "\n";
  os << indent << "InnerTubes: " << this->InnerTubes << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
