#include "FiberH5Format.h"

#include "vtk_hdf5.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <map>
#include <sstream>
#include <vector>

namespace fiberpli
{

namespace
{
// Far beyond any real fiber (and 3.2 GB of float64): a larger declared size is a broken file.
constexpr hsize_t kMaxPointsPerFiber = 100000000;

/// Silences HDF5's own error printing while an object lives (HDF5 errors become our messages).
class QuietHdf5
{
public:
  QuietHdf5() { H5Eget_auto2(H5E_DEFAULT, &func_, &data_); H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// Closes an HDF5 handle with the right function when it goes out of scope.
class Handle
{
public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() { if (id_ >= 0) { close_(id_); } }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// Member names of a group that are non-negative integers, in numeric order; false if another
/// name is present.
bool numericMembers(hid_t group, std::vector<std::pair<long, std::string>>& members, std::string& bad)
{
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0)
  {
    bad = "(unreadable group)";
    return false;
  }
  for (hsize_t i = 0; i < info.nlinks; ++i)
  {
    char name[256] = { 0 };
    if (H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof(name), H5P_DEFAULT) < 0)
    {
      bad = "(unreadable name)";
      return false;
    }
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(name, &end, 10);
    if (name[0] == '\0' || *end != '\0' || value < 0 || errno != 0)
    {
      bad = name;
      return false;
    }
    members.emplace_back(value, name);
  }
  std::sort(members.begin(), members.end());
  return true;
}

/// True when `group` holds fastPLI bundles: a group "0" with a dataset "0" of shape (n, 4).
bool holdsBundles(hid_t group)
{
  if (H5Lexists(group, "0", H5P_DEFAULT) <= 0 || H5Lexists(group, "0/0", H5P_DEFAULT) <= 0)
  {
    return false;
  }
  Handle data(H5Dopen2(group, "0/0", H5P_DEFAULT), H5Dclose);
  if (!data.ok())
  {
    return false;
  }
  Handle space(H5Dget_space(data.get()), H5Sclose);
  hsize_t dims[2] = { 0, 0 };
  return space.ok() && H5Sget_simple_extent_ndims(space.get()) == 2 &&
    H5Sget_simple_extent_dims(space.get(), dims, nullptr) == 2 && dims[1] == 4;
}

/// Paths ("/" = root) of the groups holding bundles, as fastPLI's save(..., group_name=...) makes
/// them. Follows hard links only, at most 8 levels deep and 10000 members per group, and does not
/// look inside a group that holds bundles.
void findBundleGroups(hid_t group, const std::string& path, int depth, std::vector<std::string>& found)
{
  if (holdsBundles(group))
  {
    found.push_back(path.empty() ? "/" : path);
    return;
  }
  H5G_info_t info;
  if (depth >= 8 || found.size() > 16 || H5Gget_info(group, &info) < 0)
  {
    return;
  }
  for (hsize_t i = 0; i < std::min<hsize_t>(info.nlinks, 10000); ++i)
  {
    char name[256] = { 0 };
    H5L_info_t link;
    if (H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof(name), H5P_DEFAULT) < 0 ||
      H5Lget_info(group, name, &link, H5P_DEFAULT) < 0 || link.type != H5L_TYPE_HARD)
    {
      continue;
    }
    Handle child(H5Gopen2(group, name, H5P_DEFAULT), H5Gclose); // fails quietly for datasets
    if (child.ok())
    {
      findBundleGroups(child.get(), path + "/" + name, depth + 1, found);
    }
  }
}
} // namespace

bool FiberH5Format::LooksLikeFiberH5(const std::string& path)
{
  QuietHdf5 quiet;
  if (H5Fis_hdf5(path.c_str()) <= 0)
  {
    return false;
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  std::vector<std::string> groups;
  if (file.ok())
  {
    findBundleGroups(file.get(), "", 0, groups);
  }
  return !groups.empty();
}

std::string FiberH5Format::BundleGroup(const std::string& path, const std::string& requested, std::string& group)
{
  QuietHdf5 quiet;
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok())
  {
    return path + ": cannot open the HDF5 file";
  }
  if (!requested.empty())
  {
    Handle g(H5Gopen2(file.get(), requested.c_str(), H5P_DEFAULT), H5Gclose);
    if (!g.ok())
    {
      return path + ": Group '" + requested + "' is not a group of the file";
    }
    group = requested;
    return {};
  }
  std::vector<std::string> groups;
  findBundleGroups(file.get(), "", 0, groups);
  if (groups.size() > 1)
  {
    std::string list;
    for (const std::string& g : groups)
    {
      list += (list.empty() ? "" : ", ") + g;
    }
    return path + ": several groups hold fiber bundles (" + list + "); set Group to one of them";
  }
  // None found: read the root, whose own messages say what is wrong with it.
  group = groups.empty() ? "/" : groups.front();
  return {};
}

std::string FiberH5Format::Read(const std::string& path, const std::string& requestedGroup, FiberModel& model)
{
  QuietHdf5 quiet;
  model.fibers.clear();
  if (H5Fis_hdf5(path.c_str()) <= 0)
  {
    return path + ": not an HDF5 file";
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok())
  {
    return path + ": cannot open the HDF5 file";
  }
  hsize_t fileSize = 0;
  H5Fget_filesize(file.get(), &fileSize);
  std::string groupPath;
  const std::string groupError = BundleGroup(path, requestedGroup, groupPath);
  if (!groupError.empty())
  {
    return groupError;
  }
  Handle root(H5Gopen2(file.get(), groupPath.c_str(), H5P_DEFAULT), H5Gclose);
  // Messages name datasets by their full path: "/fiber_bundles/0/3".
  const std::string prefix = groupPath == "/" ? "" : (groupPath.front() == '/' ? groupPath : "/" + groupPath);
  std::vector<std::pair<long, std::string>> bundles;
  std::string bad;
  if (!root.ok() || !numericMembers(root.get(), bundles, bad))
  {
    return path + ": member '" + prefix + "/" + bad + "' is not a bundle index (expected groups \"0\", \"1\", ... " +
      (prefix.empty() ? "at the root, or set Group" : "in Group " + prefix) + ")";
  }
  std::int64_t nextId = 0;
  for (const auto& [bundleIndex, bundleName] : bundles)
  {
    Handle group(H5Gopen2(root.get(), bundleName.c_str(), H5P_DEFAULT), H5Gclose);
    if (!group.ok())
    {
      return path + ": '" + prefix + "/" + bundleName + "' is not a group";
    }
    std::vector<std::pair<long, std::string>> fibers;
    if (!numericMembers(group.get(), fibers, bad))
    {
      return path + ": member '" + prefix + "/" + bundleName + "/" + bad + "' is not a fiber index";
    }
    for (const auto& [fiberIndex, fiberName] : fibers)
    {
      const std::string where = path + ": dataset '" + prefix + "/" + bundleName + "/" + fiberName + "'";
      Handle data(H5Dopen2(group.get(), fiberName.c_str(), H5P_DEFAULT), H5Dclose);
      if (!data.ok())
      {
        return where + " cannot be opened as a dataset";
      }
      Handle space(H5Dget_space(data.get()), H5Sclose);
      hsize_t dims[2] = { 0, 0 };
      if (!space.ok() || H5Sget_simple_extent_ndims(space.get()) != 2 ||
        H5Sget_simple_extent_dims(space.get(), dims, nullptr) != 2 || dims[1] != 4)
      {
        return where + " does not have the shape (n, 4)";
      }
      // A chunked dataset may declare far more than the file stores: check against the file size
      // (uncompressed float64) before allocating, allowing for compression up to 64x.
      if (dims[0] > kMaxPointsPerFiber || dims[0] * 4 * sizeof(double) > 64 * (fileSize + 1))
      {
        std::ostringstream msg;
        msg << where << " declares " << dims[0] << " points, more than the file of " << fileSize
            << " bytes can hold (limit " << kMaxPointsPerFiber << ")";
        return msg.str();
      }
      std::vector<double> values(static_cast<std::size_t>(dims[0] * 4));
      if (!values.empty() &&
        H5Dread(data.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
      {
        return where + " cannot be read as floating-point numbers";
      }
      Fiber f;
      f.id = nextId++;
      f.bundle = static_cast<int>(bundleIndex);
      f.points.resize(static_cast<std::size_t>(dims[0]));
      f.radii.resize(static_cast<std::size_t>(dims[0]));
      for (std::size_t i = 0; i < f.points.size(); ++i)
      {
        f.points[i] = { values[4 * i], values[4 * i + 1], values[4 * i + 2] };
        f.radii[i] = values[4 * i + 3];
      }
      model.fibers.push_back(std::move(f));
    }
  }
  return {};
}

std::string FiberH5Format::Write(const std::string& path, const FiberModel& model)
{
  QuietHdf5 quiet;
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!file.ok())
  {
    return path + ": cannot create the HDF5 file";
  }
  std::map<int, std::vector<const Fiber*>> bundles;
  for (const Fiber& f : model.fibers)
  {
    if (f.bundle < 0)
    {
      // Group names are bundle indices "0", "1", …: a negative id could not be read back.
      return path + ": bundle_id " + std::to_string(f.bundle) + " is negative; .h5 bundles are numbered from 0";
    }
    bundles[f.bundle].push_back(&f);
  }
  for (const auto& [bundle, fibers] : bundles)
  {
    const std::string groupName = std::to_string(bundle);
    Handle group(H5Gcreate2(file.get(), groupName.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (!group.ok())
    {
      return path + ": cannot create group '/" + groupName + "'";
    }
    for (std::size_t j = 0; j < fibers.size(); ++j)
    {
      const Fiber& f = *fibers[j];
      std::vector<double> values(4 * f.points.size());
      for (std::size_t i = 0; i < f.points.size(); ++i)
      {
        values[4 * i] = f.points[i].x;
        values[4 * i + 1] = f.points[i].y;
        values[4 * i + 2] = f.points[i].z;
        values[4 * i + 3] = f.radii[i];
      }
      const hsize_t dims[2] = { f.points.size(), 4 };
      Handle space(H5Screate_simple(2, dims, nullptr), H5Sclose);
      const std::string name = std::to_string(j);
      Handle data(H5Dcreate2(group.get(), name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
      if (!data.ok() || H5Dwrite(data.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
      {
        return path + ": cannot write dataset '/" + groupName + "/" + name + "'";
      }
    }
  }
  if (H5Fflush(file.get(), H5F_SCOPE_GLOBAL) < 0)
  {
    return path + ": cannot flush the HDF5 file";
  }
  return {};
}

} // namespace fiberpli
