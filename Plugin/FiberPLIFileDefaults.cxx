#include "FiberPLIFileDefaults.h"

#include <pqActiveObjects.h>
#include <pqServer.h>

#include <vtkSMPropertyHelper.h>
#include <vtkSMProxy.h>
#include <vtkSMSessionProxyManager.h>
#include <vtkSMSettings.h>

#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* const kReaderDetails = ".settings.RepresentedArrayListSettings.ReaderDetails";

// ParaView's serial and parallel XML writers of every dataset type (group "writers").
const char* const kXMLWriters[] = { "XMLPolyDataWriter", "XMLImageDataWriter",
  "XMLUnstructuredGridWriter", "XMLStructuredGridWriter", "XMLRectilinearGridWriter",
  "XMLPPolyDataWriter", "XMLPImageDataWriter", "XMLPUnstructuredGridWriter",
  "XMLPStructuredGridWriter", "XMLPRectilinearGridWriter", "XMLMultiBlockDataWriter",
  "XMLPartitionedDataSetWriter", "XMLPartitionedDataSetCollectionWriter", "XMLHyperTreeGridWriter",
  "XMLTableWriter" };

bool patternsCoverDat(const std::string& patterns)
{
  std::istringstream words(patterns);
  std::string word;
  while (words >> word)
  {
    if (word == "*.dat" || word == "*.DAT" || word == "*")
    {
      return true;
    }
  }
  return false;
}
} // namespace

void FiberPLIFileDefaults::startup()
{
  FiberPLIFileDefaults::writeXMLBinary();
  FiberPLIFileDefaults::openDatWithFiberReader();
}

void FiberPLIFileDefaults::writeXMLBinary()
{
  std::string json = "{ \"writers\": {";
  const char* separator = "";
  for (const char* writer : kXMLWriters)
  {
    json += separator;
    json += " \"" + std::string(writer) + "\": { \"DataMode\": 1 }";
    separator = ",";
  }
  json += " } }";
  // Priority 0: below the user's and the site's settings, above the XML defaults only.
  vtkSMSettings::GetInstance()->AddCollectionFromString(json, 0.0);
}

void FiberPLIFileDefaults::openDatWithFiberReader()
{
  vtkSMSettings* settings = vtkSMSettings::GetInstance();
  const unsigned int entries = settings->GetSettingNumberOfElements(kReaderDetails) / 3;
  for (unsigned int e = 0; e < entries; ++e)
  {
    if (patternsCoverDat(settings->GetSettingAsString(kReaderDetails, 3 * e, "")))
    {
      return; // a default reader for .dat exists already: the user's choice
    }
  }
  // An entry is: patterns, the reader's file description, the reader's proxy name.
  const std::vector<std::string> entry = { "*.dat", "FiberPLI fiber files", "FiberReader" };
  for (unsigned int k = 0; k < 3; ++k)
  {
    settings->SetSetting(kReaderDetails, 3 * entries + k, entry[k]);
  }
  // The settings proxy of a session that exists already shows the new entry as well.
  pqServer* server = pqActiveObjects::instance().activeServer();
  vtkSMSessionProxyManager* pxm = server ? server->proxyManager() : nullptr;
  if (vtkSMProxy* proxy = pxm ? pxm->GetProxy("settings", "RepresentedArrayListSettings") : nullptr)
  {
    vtkSMPropertyHelper details(proxy, "ReaderDetails");
    for (unsigned int k = 0; k < 3; ++k)
    {
      details.Set(3 * entries + k, entry[k].c_str());
    }
    proxy->UpdateVTKObjects();
  }
}
