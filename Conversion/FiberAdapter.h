/**
 * @file FiberAdapter.h
 * @brief the small rules every FiberPLI source, filter, reader and writer follows when it turns
 * properties into Core options and reports what went wrong
 *
 * - A message starts with the proxy name, the name the user knows the algorithm by in ParaView and
 *   pvpython (ProxyName: the class name without "vtk"); fiberpliErrorMacro and
 *   fiberpliWarningMacro put it in front of the message, as vtkErrorMacro and vtkWarningMacro
 *   would write it, ProxyMessage in front of a message reported later.
 * - An enumerated property becomes its Core enum only through Util/EnumCode.h's one rule
 *   (CheckEnum); a switch is an enumeration of 0 and 1 (CheckSwitch).
 * - NumberOfThreads and Seed follow the rules of Util/Threads.h and Util/Random.h (CheckThreads,
 *   CheckSeed).
 * Field data is read and written through FiberFieldData.h, an exception that leaves the work is
 * caught by FiberGuard.h.
 */
#ifndef FiberAdapter_h
#define FiberAdapter_h

#include "Util/EnumCode.h"
#include "Util/Random.h"
#include "Util/Threads.h"

#include <vtkAlgorithm.h>
#include <vtkObject.h>

#include <cstring>
#include <string>

namespace fiberpli
{

/// The proxy name of a FiberPLI algorithm: its class name without the "vtk" prefix.
inline std::string ProxyName(vtkObject* algorithm)
{
  const char* name = algorithm->GetClassName();
  return std::strncmp(name, "vtk", 3) == 0 ? name + 3 : name;
}

/// "<Proxy>: <message>", for a message that is passed on before it is reported (a collective
/// error, a plan's error).
inline std::string ProxyMessage(vtkObject* algorithm, const std::string& message)
{
  return ProxyName(algorithm) + ": " + message;
}

/// Enumerated property `property` with the codes 0..last (`choices` names them, e.g. "0 (Auto) or
/// 1 (Tilt)"): true and `value` set, or false with an error "<Proxy>: <property> is <code>, must be
/// <choices>".
template <typename Enum>
bool CheckEnum(vtkAlgorithm* algorithm, int code, int last, const char* property,
  const char* choices, Enum& value)
{
  const std::string error = enumFromCode(code, last, property, choices, value);
  if (!error.empty())
  {
    vtkErrorWithObjectMacro(algorithm, << ProxyName(algorithm) << ": " << error);
    return false;
  }
  return true;
}

/// "" when the switch `property` is 0 or 1, else "<property> is <value>, must be 0 or 1".
inline std::string switchFromCode(int code, const char* property, bool& on)
{
  return enumFromCode(code, 1, property, "0 or 1", on);
}

/// NumberOfThreads rule: false (with an error naming the value) outside [0, kMaxThreads]; a
/// warning when it is clamped to 4 × the cores.
inline bool CheckThreads(vtkAlgorithm* algorithm, int requested)
{
  const std::string error = validateThreadCount(requested);
  if (!error.empty())
  {
    vtkErrorWithObjectMacro(algorithm, << ProxyName(algorithm) << ": " << error);
    return false;
  }
  const std::string warning = threadCountWarning(requested);
  if (!warning.empty())
  {
    vtkWarningWithObjectMacro(algorithm, << ProxyName(algorithm) << ": " << warning);
  }
  return true;
}

/// Seed rule: false (with an error naming the value) for a negative Seed.
inline bool CheckSeed(vtkAlgorithm* algorithm, long long seed)
{
  const std::string error = validateSeed(seed);
  if (!error.empty())
  {
    vtkErrorWithObjectMacro(algorithm, << ProxyName(algorithm) << ": " << error);
    return false;
  }
  return true;
}

} // namespace fiberpli

/// vtkErrorMacro and vtkWarningMacro of a FiberPLI algorithm: "<Proxy>: " and the message.
#define fiberpliErrorMacro(x) vtkErrorMacro(<< fiberpli::ProxyName(this) << ": " x)
#define fiberpliWarningMacro(x) vtkWarningMacro(<< fiberpli::ProxyName(this) << ": " x)

#endif
// VTK-HeaderTest-Exclude: FiberAdapter.h
