/// ValueCheck: the one shape of the message for a refused value, "<name> is <value>, must be
/// <rule>" with the value in NumberFormat's short form (and the readers' shorter "<what> <value>
/// must be <rule>"), and the few rules most options follow.
/// A validation written with it reads as the list of rules it applies, in order, and every
/// refusal names the option and the value the same way.
#pragma once

#include "Util/NumberFormat.h"

#include <cmath>
#include <string>

namespace fiberpli
{

/// "<name> is <value>, must be <rule>"; with a unit, "<name> is <value> <unit>, must be <rule>".
template <typename T>
std::string mustBe(
  const std::string& name, T value, const std::string& rule, const std::string& unit = {})
{
  return name + " is " + formatNumber(value) + (unit.empty() ? "" : " " + unit) + ", must be " +
    rule;
}

/// "<what> <value> must be <rule>" (with a unit, "<what> <value> <unit> must be <rule>"): the
/// shorter shape the file readers and writers use for a value they found ("radius -2 must be > 0"
/// on a line of a file, "DefaultRadius 0 must be finite and > 0").
template <typename T>
std::string valueMustBe(
  const std::string& what, T value, const std::string& rule, const std::string& unit = {})
{
  return what + " " + formatNumber(value) + (unit.empty() ? "" : " " + unit) + " must be " + rule;
}

/// Checks applied in order; the first refusal is kept and later checks are skipped, so an
/// options struct is validated by one chain and reports its first bad option.
class ValueChecks
{
public:
  /// Any rule: refused when `ok` is false.
  template <typename T>
  ValueChecks& require(bool ok, const std::string& name, T value, const std::string& rule)
  {
    if (this->Error.empty() && !ok)
    {
      this->Error = mustBe(name, value, rule);
    }
    return *this;
  }

  /// Finite and > 0.
  ValueChecks& positive(const std::string& name, double value)
  {
    return this->require(value > 0.0 && std::isfinite(value), name, value, "> 0");
  }

  /// Finite and >= lo.
  template <typename T>
  ValueChecks& atLeast(const std::string& name, T value, T lo)
  {
    return this->require(value >= lo && std::isfinite(static_cast<double>(value)), name, value,
      ">= " + formatNumber(lo));
  }

  /// In [lo, hi]; `note` follows the interval (e.g. " (0 = automatic)").
  template <typename T>
  ValueChecks& within(const std::string& name, T value, T lo, T hi, const std::string& note = {})
  {
    return this->require(value >= lo && value <= hi, name, value,
      "in [" + formatNumber(lo) + ", " + formatNumber(hi) + "]" + note);
  }

  /// A check written elsewhere: its message ("" when it passed).
  ValueChecks& then(const std::string& error)
  {
    if (this->Error.empty())
    {
      this->Error = error;
    }
    return *this;
  }

  /// "" when every check passed, else the first refusal.
  const std::string& error() const { return this->Error; }

private:
  std::string Error;
};

} // namespace fiberpli
