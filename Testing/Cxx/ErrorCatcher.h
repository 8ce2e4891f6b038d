// Catches VTK error and warning events of an algorithm and its executive, so that bad-input tests
// can assert the message instead of printing it (a printed "ERR|" fails every test).
#pragma once

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>

#include <string>

class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }

  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const std::string text = data ? static_cast<const char*>(data) : "";
    if (event == vtkCommand::ErrorEvent)
    {
      Errors += text + "\n";
    }
    else
    {
      Warnings += text + "\n";
    }
  }

  void Watch(vtkAlgorithm* algorithm)
  {
    for (vtkObject* o : { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
    {
      o->AddObserver(vtkCommand::ErrorEvent, this);
      o->AddObserver(vtkCommand::WarningEvent, this);
    }
  }

  void Clear()
  {
    Errors.clear();
    Warnings.clear();
  }

  std::string Errors;
  std::string Warnings;
};
