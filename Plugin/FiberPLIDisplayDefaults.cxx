#include "FiberPLIDisplayDefaults.h"

#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionManager.h"
#include "vtkSMTransferFunctionProxy.h"

#include "vtkSMProperty.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace
{
// Categorical colours (ColorBrewer Set1 then Dark2), repeated for more bundles.
const double kBundleColors[][3] = { { 0.894, 0.102, 0.110 }, { 0.216, 0.494, 0.722 },
  { 0.302, 0.686, 0.290 }, { 0.596, 0.306, 0.639 }, { 1.000, 0.498, 0.000 },
  { 0.651, 0.337, 0.157 }, { 0.969, 0.506, 0.749 }, { 0.600, 0.600, 0.600 },
  { 0.106, 0.620, 0.467 }, { 0.851, 0.373, 0.008 }, { 0.459, 0.439, 0.702 },
  { 0.902, 0.671, 0.008 } };
const int kNumberOfBundleColors = sizeof(kBundleColors) / sizeof(kBundleColors[0]);
// Up to this many distinct bundle ids get one annotated colour each; more stay continuous.
const int kMaxCategories = 64;

vtkPVArrayInformation* pointArray(vtkPVDataInformation* info, const char* name)
{
  return info->GetPointDataInformation()->GetArrayInformation(name);
}

vtkPVArrayInformation* cellArray(vtkPVDataInformation* info, const char* name)
{
  return info->GetCellDataInformation()->GetArrayInformation(name);
}

// Colour tables of true-colour displays: a colour bar of such a table would show a blue-red
// "fom Magnitude" scale that has nothing to do with the pixel colours.
std::vector<vtkWeakPointer<vtkSMProxy>>& trueColourTables()
{
  static std::vector<vtkWeakPointer<vtkSMProxy>> tables;
  return tables;
}

void showTrueColour(vtkSMProxy* repr)
{
  vtkSMPVRepresentationProxy::SetScalarColoring(repr, "fom", vtkDataObject::POINT);
  vtkSMPropertyHelper(repr, "MapScalars").Set(0);
  repr->UpdateVTKObjects();
  vtkSMProxy* lut = vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy();
  auto& tables = trueColourTables();
  if (lut && std::find(tables.begin(), tables.end(), lut) == tables.end())
  {
    tables.emplace_back(lut);
  }
}

// The GUI shows a colour bar for every new coloured display right after creating it. For a colour
// bar of a true-colour table that first switch-on is undone; a user who wants the (meaningless)
// bar anyway clicks the colour-legend button once more.
class FirstShowVeto : public vtkCommand
{
public:
  static FirstShowVeto* New() { return new FirstShowVeto; }
  vtkWeakPointer<vtkSMProxy> Bar;
  void Execute(vtkObject* caller, unsigned long, void*) override
  {
    if (!this->Bar || vtkSMPropertyHelper(this->Bar, "Visibility").GetAsInt() == 0)
    {
      return;
    }
    caller->RemoveObserver(this); // one-shot: deletes this command once Execute returns
    vtkSMPropertyHelper(this->Bar, "Visibility").Set(0);
  }
};

void vetoFirstShow(vtkSMProxy* bar)
{
  vtkSMProxy* lut = vtkSMPropertyHelper(bar, "LookupTable", true).GetAsProxy();
  const auto& tables = trueColourTables();
  vtkSMProperty* visibility = bar->GetProperty("Visibility");
  if (!lut || !visibility || std::find(tables.begin(), tables.end(), lut) == tables.end())
  {
    return;
  }
  // A new bar is visible by default; whoever created it switches it on right after registering
  // it, and that switch-on is undone.
  vtkSMPropertyHelper(visibility).Set(0);
  bar->UpdateVTKObjects();
  vtkNew<FirstShowVeto> veto;
  veto->Bar = bar;
  visibility->AddObserver(vtkCommand::ModifiedEvent, veto);
}

void showIntensityComponent(vtkSMProxy* repr)
{
  vtkSMPVRepresentationProxy::SetScalarColoring(repr, "intensity", vtkDataObject::POINT, 0);
  vtkSMProxy* lut = vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy();
  if (lut)
  {
    vtkSMTransferFunctionProxy::ApplyPreset(lut, "Grayscale", false);
    vtkSMPVRepresentationProxy::RescaleTransferFunctionToDataRange(repr, false, false);
  }
  repr->UpdateVTKObjects();
}

// bundle_id has one colour table for every display (ParaView keeps one per array name). Its
// categories only grow: a value keeps its colour (kBundleColors by value) and a model with fewer
// bundles shown later does not take the colours of another model's bundles away.
void showBundlesAsCategories(vtkSMProxy* repr, vtkPVArrayInformation* bundles)
{
  vtkSMPVRepresentationProxy::SetScalarColoring(repr, "bundle_id", vtkDataObject::CELL);
  vtkSMProxy* lut = vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy();
  const double* range = bundles->GetComponentRange(0);
  if (!lut || !std::isfinite(range[0]) || !std::isfinite(range[1]) ||
    range[1] - range[0] >= kMaxCategories)
  {
    return; // no table, or too many bundles for one colour each: keep the continuous map
  }
  int first = static_cast<int>(range[0]);
  int last = static_cast<int>(range[1]);
  vtkSMPropertyHelper annotations(lut, "Annotations");
  if (vtkSMPropertyHelper(lut, "IndexedLookup").GetAsInt() == 1)
  {
    for (unsigned int k = 0; k + 1 < annotations.GetNumberOfElements(); k += 2)
    {
      const int value = std::atoi(annotations.GetAsString(k));
      first = std::min(first, value);
      last = std::max(last, value);
    }
  }
  if (last - first >= kMaxCategories)
  {
    return; // the union is too wide: leave the table as it is
  }
  const int count = last - first + 1;
  vtkSMPropertyHelper colors(lut, "IndexedColors");
  std::vector<std::string> values(static_cast<std::size_t>(count));
  annotations.SetNumberOfElements(2 * count);
  colors.SetNumberOfElements(3 * count);
  for (int k = 0; k < count; ++k)
  {
    const std::string value = std::to_string(first + k);
    annotations.Set(2 * k, value.c_str());
    annotations.Set(2 * k + 1, ("bundle " + value).c_str());
    const int slot =
      ((first + k) % kNumberOfBundleColors + kNumberOfBundleColors) % kNumberOfBundleColors;
    for (int c = 0; c < 3; ++c)
    {
      colors.Set(3 * k + c, kBundleColors[slot][c]);
    }
  }
  vtkSMPropertyHelper(lut, "IndexedLookup").Set(1);
  lut->UpdateVTKObjects();
}

// PLIAnalysis' and the ground truth's `direction` is an axis angle in [0, 180) degrees: 0 and 180
// are the same orientation, so its colour table is cyclic ("hsv", whose two ends are one colour)
// over exactly [0, 180], kept there (no automatic rescale to the data's range). Set once, when
// FiberPLI first shows such an output; the user's later changes stay.
void prepareDirectionTable(vtkSMProxy* repr)
{
  vtkSMSessionProxyManager* pxm = repr->GetSessionProxyManager();
  if (!pxm)
  {
    return;
  }
  static std::map<vtkSMSessionProxyManager*, vtkWeakPointer<vtkSMProxy>> prepared;
  vtkNew<vtkSMTransferFunctionManager> manager;
  vtkSMProxy* lut = manager->GetColorTransferFunction("direction", pxm);
  auto known = prepared.find(pxm);
  if (!lut || (known != prepared.end() && known->second == lut))
  {
    return;
  }
  prepared[pxm] = lut;
  vtkSMTransferFunctionProxy::ApplyPreset(lut, "hsv", false);
  vtkSMPropertyHelper(lut, "AutomaticRescaleRangeMode").Set(-1); // "Never"
  vtkSMTransferFunctionProxy::RescaleTransferFunction(lut, 0.0, 180.0);
  // Else the first display coloured by it rescales the table to its data once.
  if (lut->GetProperty("ScalarRangeInitialized"))
  {
    vtkSMPropertyHelper(lut, "ScalarRangeInitialized").Set(1);
  }
  lut->UpdateVTKObjects();
}

void applyDefaults(vtkSMProxy* repr);

// A display created while its producer's output is empty (e.g. after an aborted first run) has no
// array to colour by, and ParaView then paints it in one plain colour for good. It gets the
// starting colouring once, at the first update that brings data, if nobody coloured it meanwhile.
class FirstDataObserver : public vtkCommand
{
public:
  static FirstDataObserver* New() { return new FirstDataObserver; }
  vtkWeakPointer<vtkSMProxy> Representation;
  void Execute(vtkObject* caller, unsigned long, void*) override
  {
    auto* producer = vtkSMSourceProxy::SafeDownCast(caller);
    if (!this->Representation)
    {
      caller->RemoveObserver(this);
      return;
    }
    vtkSMPropertyHelper input(this->Representation, "Input", true);
    vtkPVDataInformation* info =
      producer ? producer->GetDataInformation(input.GetOutputPort()) : nullptr;
    if (!info || info->GetNumberOfPoints() == 0)
    {
      return; // still empty
    }
    vtkSMProxy* repr = this->Representation;
    caller->RemoveObserver(this); // deletes this command once Execute returns
    auto* pv = vtkSMPVRepresentationProxy::SafeDownCast(repr);
    if (pv && !pv->GetUsingScalarColoring())
    {
      applyDefaults(repr);
    }
  }
};

// Sets the starting colouring of a new representation from what its input carries.
void applyDefaults(vtkSMProxy* repr)
{
  if (!vtkSMPVRepresentationProxy::SafeDownCast(repr) || !repr->GetProperty("MapScalars") ||
    !repr->GetProperty("Input"))
  {
    return; // not a data display with colouring (e.g. a spreadsheet row or a scalar bar)
  }
  vtkSMPropertyHelper input(repr, "Input", true);
  auto* producer = vtkSMSourceProxy::SafeDownCast(input.GetAsProxy());
  if (!producer)
  {
    return;
  }
  vtkPVDataInformation* info = producer->GetDataInformation(input.GetOutputPort());
  if (!info)
  {
    return;
  }
  if (info->GetNumberOfPoints() == 0 && producer->GetXMLGroup() &&
    (std::string(producer->GetXMLGroup()) == "sources" ||
      std::string(producer->GetXMLGroup()) == "filters"))
  {
    vtkNew<FirstDataObserver> later;
    later->Representation = repr;
    producer->AddObserver(vtkCommand::UpdateDataEvent, later);
    return;
  }
  vtkPVArrayInformation* fom = pointArray(info, "fom");
  if (fom && fom->GetDataType() == VTK_UNSIGNED_CHAR && fom->GetNumberOfComponents() == 3)
  {
    showTrueColour(repr);
    return;
  }
  vtkPVArrayInformation* intensity = pointArray(info, "intensity");
  if (intensity && intensity->GetNumberOfComponents() > 1)
  {
    showIntensityComponent(repr);
    return;
  }
  if (pointArray(info, "direction") && pointArray(info, "inclination"))
  {
    prepareDirectionTable(repr);
  }
  vtkPVArrayInformation* bundles = cellArray(info, "bundle_id");
  if (bundles && cellArray(info, "fiber_id") && bundles->GetNumberOfComponents() == 1)
  {
    showBundlesAsCategories(repr, bundles);
  }
}

// Every session proxy manager forwards its registrations to the proxy-manager singleton; a new
// display is registered in "representations" once its input and first colouring are set up, a
// colour bar in "scalar_bars" before the GUI switches it on.
class RepresentationObserver : public vtkCommand
{
public:
  static RepresentationObserver* New() { return new RepresentationObserver; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    auto* info = static_cast<vtkSMProxyManager::RegisteredProxyInformation*>(callData);
    if (!info || info->Type != vtkSMProxyManager::RegisteredProxyInformation::PROXY ||
      !info->Proxy || !info->GroupName)
    {
      return;
    }
    // A state file being loaded brings its displays as they were saved: only new displays get
    // the starting colouring.
    vtkSMSessionProxyManager* pxm = info->Proxy->GetSessionProxyManager();
    if (pxm && pxm->GetInLoadXMLState())
    {
      return;
    }
    const std::string group = info->GroupName;
    if (group == "representations")
    {
      applyDefaults(info->Proxy);
    }
    else if (group == "scalar_bars")
    {
      vetoFirstShow(info->Proxy);
    }
  }
};
}

void fiberpli_display_defaults_init()
{
  static bool installed = false;
  if (installed || !vtkSMProxyManager::IsInitialized())
  {
    return; // server processes have no proxy manager; a second load changes nothing
  }
  installed = true;
  vtkNew<RepresentationObserver> observer;
  vtkSMProxyManager::GetProxyManager()->AddObserver(vtkCommand::RegisterEvent, observer);
}
