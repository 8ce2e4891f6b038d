#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberGuard.h"
#include "FiberSolverComm.h"

#include "Parallel/Collectives.h"
#include "Util/ByteBuffer.h"
#include "Util/NumberFormat.h"

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkDataObject.h>
#include <vtkExecutive.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <vector>

namespace fiberpli
{

namespace
{
/// Collects the ErrorEvent messages of an algorithm, without the "ERROR: In <file>, line <n>" and
/// "<class> (<address>): " decoration vtkErrorMacro adds.
class ErrorCapture : public vtkCommand
{
public:
  static ErrorCapture* New() { return new ErrorCapture; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    std::string text = data ? static_cast<const char*>(data) : "";
    Raw += text;
    if (text.rfind("ERROR: In ", 0) == 0 && text.find('\n') != std::string::npos)
    {
      text = text.substr(text.find('\n') + 1);
    }
    const std::size_t object = text.find("): ");
    if (object != std::string::npos && text.find(" (0x") < object)
    {
      text = text.substr(object + 3);
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
    {
      text.pop_back();
    }
    Message += (Message.empty() ? "" : "; ") + text;
  }
  std::string Message, Raw;
};
} // namespace

vtkMultiProcessController* FiberCollective::ControllerFor(vtkInformation* info)
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  if (!c || c->GetNumberOfProcesses() < 2 || !info ||
    !info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()))
  {
    return nullptr;
  }
  return info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) ==
      c->GetNumberOfProcesses()
    ? c
    : nullptr;
}

std::string FiberCollective::AgreeOnError(
  vtkInformation* info, const std::string& who, const std::string& localError)
{
  vtkMultiProcessController* c = ControllerFor(info);
  if (!c)
  {
    return localError;
  }
  // Who failed and whose message wins is the Core's one rule; the text is the pipeline's: a
  // failing rank keeps its own error, the others name the rank that failed.
  FiberSolverComm comm(c);
  const RankFailure agreed = agreeOnFailure(comm, localError);
  if (!agreed.failed())
  {
    return {};
  }
  if (!localError.empty())
  {
    return localError;
  }
  return who + ": rank " + fiberpli::formatNumber(agreed.rank) +
    " failed, so no rank gives output: " + agreed.message;
}

double FiberCollective::GlobalMax(vtkInformation* info, double local)
{
  vtkMultiProcessController* c = ControllerFor(info);
  if (!c)
  {
    return local;
  }
  FiberSolverComm comm(c);
  return maxOverRanks(comm, local);
}

std::string FiberCollective::AgreeOnPeriodicCell(
  vtkInformation* info, const std::string& who, vtkDataObject* piece)
{
  RankCell mine;
  mine.present = PeriodicCellValues(piece, mine.values);
  mine.count = mine.values.size();
  std::vector<RankCell> all{ mine };
  if (vtkMultiProcessController* c = ControllerFor(info))
  {
    // Every rank sends its cell to every rank: present, value count, then up to 6 values (a longer
    // field is malformed anyway: its count alone says so).
    std::vector<char> record;
    ByteWriter w(record);
    w.put<char>(mine.present ? 1 : 0);
    w.put<std::uint64_t>(mine.count);
    w.putVector(std::vector<double>(
      mine.values.begin(), mine.values.begin() + std::min<std::size_t>(6, mine.count)));
    FiberSolverComm comm(c);
    const std::vector<std::vector<char>> got =
      comm.exchange(std::vector<std::vector<char>>(static_cast<std::size_t>(comm.size()), record));
    all.assign(got.size(), RankCell{});
    for (std::size_t r = 0; r < got.size(); ++r)
    {
      ByteReader rd(got[r]);
      RankCell& cell = all[r];
      cell.present = rd.get<char>() != 0;
      cell.count = static_cast<std::size_t>(rd.get<std::uint64_t>());
      rd.getVector(cell.values);
    }
  }
  const std::string error = compareRankCells(all);
  return error.empty() ? error : who + ": " + error;
}

int FiberCollective::RunCollectively(vtkAlgorithm* self, vtkInformation* request,
  vtkInformationVector* outputVector, const std::string& who, const std::function<int()>& piece)
{
  // While piece runs, its errors are captured for the other ranks; if nobody else listens, they
  // are displayed afterwards as they would have been.
  const bool observed = self->HasObserver(vtkCommand::ErrorEvent) != 0;
  vtkNew<ErrorCapture> capture;
  const unsigned long tag = self->AddObserver(vtkCommand::ErrorEvent, capture);
  const int rc = GuardRequest(self, nullptr, who, piece); // an exception is this rank's error
  self->RemoveObserver(tag);
  if (!observed && !capture->Raw.empty())
  {
    vtkOutputWindow::GetInstance()->DisplayErrorText(capture->Raw.c_str());
  }
  std::string local;
  if (rc == 0)
  {
    local = capture->Message.empty() ? who + ": failed" : capture->Message;
  }
  int port = request && request->Has(vtkExecutive::FROM_OUTPUT_PORT())
    ? request->Get(vtkExecutive::FROM_OUTPUT_PORT())
    : 0;
  port = port >= 0 && port < outputVector->GetNumberOfInformationObjects() ? port : 0;
  const std::string error = AgreeOnError(outputVector->GetInformationObject(port), who, local);
  if (error.empty() || !local.empty())
  {
    return rc; // all succeeded, or this rank failed and its outputs are what piece left them
  }
  for (int p = 0; p < outputVector->GetNumberOfInformationObjects(); ++p)
  {
    if (vtkDataObject* data =
          outputVector->GetInformationObject(p)->Get(vtkDataObject::DATA_OBJECT()))
    {
      data->Initialize();
    }
  }
  vtkErrorWithObjectMacro(self, << error);
  return 0;
}

} // namespace fiberpli
