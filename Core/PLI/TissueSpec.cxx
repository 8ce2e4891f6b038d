#include "PLI/TissueSpec.h"

#include "PLI/OptionLimits.h"
#include "Util/NumberFormat.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace fiberpli
{
namespace pli
{

int TissueSpec::maxLayers() const
{
  std::size_t m = 0;
  for (const auto& l : layers)
  {
    m = std::max(m, l.size());
  }
  return static_cast<int>(m);
}

int TissueSpec::slotOf(int bundleId) const
{
  const auto it = std::lower_bound(bundleIds.begin(), bundleIds.end(), bundleId);
  return (it != bundleIds.end() && *it == bundleId) ? static_cast<int>(it - bundleIds.begin()) : -1;
}

namespace
{
std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos)
  {
    return std::string();
  }
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& s, char sep)
{
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep))
  {
    out.push_back(cur);
  }
  if (!s.empty() && s.back() == sep)
  {
    out.emplace_back();
  }
  return out;
}

std::string parseGroup(const std::string& body, const std::string& where, std::vector<Layer>& out)
{
  for (const std::string& rawTuple : split(body, ';'))
  {
    const std::string tuple = trim(rawTuple);
    if (tuple.empty())
    {
      return "Layers: empty tuple in " + where;
    }
    std::istringstream in(tuple);
    Layer l;
    std::string model, extra;
    if (!(in >> l.scale >> l.dn >> l.muPerMm >> model) || (in >> extra))
    {
      return "Layers: tuple '" + tuple + "' in " + where + " is not 'scale dn mu model'";
    }
    if (model == "p")
      l.model = AxisModel::Parallel;
    else if (model == "r")
      l.model = AxisModel::Radial;
    else if (model == "b")
      l.model = AxisModel::Background;
    else
      return "Layers: model '" + model + "' in " + where + " must be p, r or b";
    out.push_back(l);
  }
  return std::string();
}
} // namespace

Status validateLayers(std::vector<Layer>& layers, const std::string& where)
{
  Status st;
  if (layers.empty())
  {
    st.error = "Layers: " + where + " has no layer";
    return st;
  }
  for (const Layer& l : layers)
  {
    if (!std::isfinite(l.scale) || l.scale <= 0.0)
    {
      st.error = "Layers: scale " + formatNumber(l.scale) + " in " + where + " must be > 0";
      return st;
    }
    if (!std::isfinite(l.dn) || !std::isfinite(l.muPerMm) || l.muPerMm < 0.0)
    {
      st.error = "Layers: dn and mu in " + where + " must be finite, mu >= 0 (mu " +
        formatNumber(l.muPerMm) + ")";
      return st;
    }
    if (!(std::fabs(l.dn) <= kMaxBirefringence))
    {
      std::ostringstream m;
      m << "Layers: dn " << l.dn << " in " << where << " must be in [-" << kMaxBirefringence << ", "
        << kMaxBirefringence << "]";
      st.error = m.str();
      return st;
    }
    if (l.model == AxisModel::Background && l.dn != 0.0)
    {
      st.error = "Layers: layer 'b' in " + where + " has dn " + formatNumber(l.dn) + ", must be 0";
      return st;
    }
    if (l.scale > 1.0)
      st.warnings.push_back("Layers: scale " + formatNumber(l.scale) + " > 1 in " + where);
    if (l.model == AxisModel::Parallel && l.dn > 0.0)
      st.warnings.push_back(
        "Layers: parallel layer with dn > 0 in " + where + " shows up rotated by 90 deg");
    if (l.model == AxisModel::Radial && l.dn < 0.0)
      st.warnings.push_back(
        "Layers: radial layer with dn < 0 in " + where + " shows up rotated by 90 deg");
  }
  if (!std::is_sorted(layers.begin(), layers.end(),
        [](const Layer& a, const Layer& b) { return a.scale < b.scale; }))
  {
    std::stable_sort(layers.begin(), layers.end(),
      [](const Layer& a, const Layer& b) { return a.scale < b.scale; });
    st.warnings.push_back("Layers: " + where + " sorted by scale");
  }
  for (std::size_t i = 1; i < layers.size(); ++i)
  {
    if (layers[i].scale == layers[i - 1].scale)
    {
      st.error = "Layers: two layers with scale " + formatNumber(layers[i].scale) + " in " + where;
      return st;
    }
  }
  return st;
}

Status makeTissueSpec(const std::string& layersText, const std::vector<int>& bundleIds,
  double defaultDn, double defaultMu, double backgroundMu, TissueSpec& spec, bool myelin)
{
  Status st;
  spec = TissueSpec();
  if (!std::isfinite(backgroundMu) || backgroundMu < 0.0)
  {
    st.error = mustBe("BackgroundAbsorption", backgroundMu, ">= 0");
    return st;
  }
  spec.backgroundMu = backgroundMu;
  std::set<int> ids(bundleIds.begin(), bundleIds.end());
  spec.bundleIds.assign(ids.begin(), ids.end());

  std::vector<Layer> general;
  bool haveGeneral = false;
  std::map<int, std::vector<Layer>> specific;
  if (trim(layersText).empty())
  {
    if (myelin)
    {
      // The sheath's optic axis is radial (§2.2): its Δn has the opposite sign of a parallel
      // layer's for the same net birefringence along the fiber.
      general.push_back(Layer{ 1.0, 0.0, defaultMu, AxisModel::Background, true });
      general.push_back(Layer{ 1.0, -defaultDn, defaultMu, AxisModel::Radial });
    }
    else
    {
      general.push_back(Layer{ 1.0, defaultDn, defaultMu, AxisModel::Parallel });
    }
    haveGeneral = true;
    if (!std::isfinite(defaultMu) || defaultMu < 0.0)
    {
      st.error = mustBe("Absorption", defaultMu, ">= 0");
      return st;
    }
    if (!(std::fabs(defaultDn) <= kMaxBirefringence))
    {
      st.error = mustBe("Birefringence", defaultDn,
        "in [-" + formatNumber(kMaxBirefringence) + ", " + formatNumber(kMaxBirefringence) + "]");
      return st;
    }
  }
  else
  {
    int groupIndex = 0;
    for (const std::string& rawGroup : split(layersText, '|'))
    {
      std::string group = trim(rawGroup);
      const std::string where0 = "group " + formatNumber(groupIndex++);
      const auto colon = group.find(':');
      std::vector<Layer> layers;
      if (colon == std::string::npos)
      {
        if (haveGeneral)
        {
          st.error = "Layers: two groups without a bundle prefix (" + where0 + ")";
          return st;
        }
        st.error = parseGroup(group, where0, general);
        haveGeneral = true;
        if (!st.ok())
          return st;
        Status v = validateLayers(general, where0);
        st.warnings.insert(st.warnings.end(), v.warnings.begin(), v.warnings.end());
        if (!v.ok())
          return v;
      }
      else
      {
        std::istringstream in(group.substr(0, colon));
        int id = 0;
        std::string extra;
        if (!(in >> id) || (in >> extra))
        {
          st.error = "Layers: bundle prefix '" + group.substr(0, colon) + "' in " + where0 +
            " is not an integer";
          return st;
        }
        if (specific.count(id))
        {
          st.error = "Layers: bundle " + formatNumber(id) + " has two groups";
          return st;
        }
        const std::string where = where0 + " (bundle " + formatNumber(id) + ")";
        st.error = parseGroup(group.substr(colon + 1), where, layers);
        if (!st.ok())
          return st;
        Status v = validateLayers(layers, where);
        st.warnings.insert(st.warnings.end(), v.warnings.begin(), v.warnings.end());
        if (!v.ok())
          return v;
        specific[id] = layers;
      }
    }
  }
  for (int id : spec.bundleIds)
  {
    const auto it = specific.find(id);
    if (it != specific.end())
    {
      spec.layers.push_back(it->second);
    }
    else if (haveGeneral)
    {
      spec.layers.push_back(general);
    }
    else
    {
      st.error =
        "Layers: bundle " + formatNumber(id) + " has no group and there is no default group";
      return st;
    }
  }
  return st;
}

} // namespace pli
} // namespace fiberpli
