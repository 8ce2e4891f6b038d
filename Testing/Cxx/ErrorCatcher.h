// Catches VTK error and warning events of an algorithm and its executive, so that bad-input tests
// can assert the message instead of printing it (a printed "ERR|" fails every test).
#pragma once

#include <gtest/gtest.h>

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkDataSet.h>
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
    for (vtkObject* o :
      { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
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

/// The bad-input tests' check: updating `algorithm` reports an error containing `text` and leaves
/// output 0 without points.
inline void ExpectUpdateError(
  vtkAlgorithm* algorithm, ErrorCatcher* catcher, const std::string& text)
{
  catcher->Clear();
  algorithm->Update();
  EXPECT_NE(catcher->Errors.find(text), std::string::npos) << catcher->Errors;
  auto* output = vtkDataSet::SafeDownCast(algorithm->GetOutputDataObject(0));
  EXPECT_EQ(output ? output->GetNumberOfPoints() : 0, 0) << text;
}

/// The recovery check of the bad-input tests: updating `algorithm` again reports no error.
inline void ExpectUpdateClean(vtkAlgorithm* algorithm, ErrorCatcher* catcher)
{
  catcher->Clear();
  algorithm->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
}
