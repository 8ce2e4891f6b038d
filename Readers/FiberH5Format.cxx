#include "FiberH5Format.h"

#include "IO/AtomicFile.h"
#include "IO/RegularFile.h"
#include "Model/PeriodicCellRule.h"
#include "Util/MemoryBudget.h"
#include "Util/PrintableText.h"
#include "Util/ValueCheck.h"

#include "vtk_hdf5.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace fiberpli
{

namespace
{
// Far beyond any real fiber (and 3.2 GB of float64): a larger declared size is a broken file.
constexpr hsize_t kMaxPointsPerFiber = 100000000;
// Compression HDF5 files reach on fiber coordinates is far below this: declared float64 data
// beyond 64 times the file size is a broken or malicious file (hard links included).
constexpr double kMaxExpansion = 64.0;
// Memory per point once read: FiberModel (point 24 B, radius 8 B) and the vtkPolyData built from
// it (point 24 B, radius 8 B, connectivity 8 B), alive together in vtkFiberReader.
constexpr double kBytesPerPointRead = 72.0;
// Per fiber: Fiber object and its vectors, a polyline cell with its offsets and cell data.
constexpr double kBytesPerFiberRead = 160.0;

/// Silences HDF5's own error printing while an object lives (HDF5 errors become our messages).
class QuietHdf5
{
public:
  QuietHdf5()
  {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
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
  Handle(hid_t id, herr_t (*close)(hid_t))
    : id_(id)
    , close_(close)
  {
  }
  ~Handle()
  {
    if (id_ >= 0)
    {
      close_(id_);
    }
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// The periodic cell as a 6-value float64 attribute `periodic_cell` of `group` (FiberPLI's own).
bool writeCellAttribute(hid_t group, const PeriodicCell& cell)
{
  const double b[6] = { cell.lo.x, cell.hi.x, cell.lo.y, cell.hi.y, cell.lo.z, cell.hi.z };
  const hsize_t n = 6;
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  Handle attr(
    H5Acreate2(group, "periodic_cell", H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
    H5Aclose);
  return attr.ok() && H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, b) >= 0;
}

/// Reads the attribute `periodic_cell` of `group` into cell when present; an error text when it is
/// not 6 finite values with max > min.
std::string readCellAttribute(hid_t group, PeriodicCell& cell)
{
  cell = PeriodicCell{};
  if (H5Aexists(group, "periodic_cell") <= 0)
  {
    return {};
  }
  Handle attr(H5Aopen(group, "periodic_cell", H5P_DEFAULT), H5Aclose);
  Handle space(attr.ok() ? H5Aget_space(attr.get()) : -1, H5Sclose);
  const hssize_t n = space.ok() ? H5Sget_simple_extent_npoints(space.get()) : -1;
  if (n != 6)
  {
    return "attribute periodic_cell has " + std::to_string(n) +
      " values, must have 6 (xmin xmax ymin ymax zmin zmax)";
  }
  double b[6];
  if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, b) < 0)
  {
    return "attribute periodic_cell cannot be read as float64";
  }
  const std::string bad = periodicCellFromBounds(b, 6, cell);
  return bad.empty() ? bad : "attribute " + bad;
}

/// Values per inner_radius attribute: HDF5's original object header (the file format fastPLI's
/// files have) holds no attribute message above 64 KiB, so a long fiber's inner radii are split
/// into "inner_radius", "inner_radius_1", "inner_radius_2", … of at most this many float64 values.
constexpr std::size_t kInnerRadiiPerAttribute = 4096;

std::string innerRadiusAttributeName(std::size_t part)
{
  return part == 0 ? "inner_radius" : "inner_radius_" + std::to_string(part);
}

/// The fiber's inner radii as float64 attributes of its dataset: fastPLI reads only the (n, 4)
/// datasets and ignores attributes, so its files stay readable.
bool writeInnerRadiusAttribute(hid_t data, const std::vector<double>& inner)
{
  for (std::size_t first = 0, part = 0; first < inner.size() || part == 0;
       first += kInnerRadiiPerAttribute, ++part)
  {
    const hsize_t n = std::min(kInnerRadiiPerAttribute, inner.size() - first);
    Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
    Handle attr(H5Acreate2(data, innerRadiusAttributeName(part).c_str(), H5T_IEEE_F64LE,
                  space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
    if (!attr.ok() || H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, inner.data() + first) < 0)
    {
      return false;
    }
  }
  return true;
}

/// Reads the attributes `inner_radius`, `inner_radius_1`, … of a fiber's dataset into f.innerRadii
/// when present; an error text when together they do not hold one value per point, finite in
/// (0, radius].
std::string readInnerRadiusAttribute(hid_t data, Fiber& f)
{
  if (H5Aexists(data, "inner_radius") <= 0)
  {
    return {};
  }
  f.innerRadii.clear();
  for (std::size_t part = 0; H5Aexists(data, innerRadiusAttributeName(part).c_str()) > 0; ++part)
  {
    const std::string name = innerRadiusAttributeName(part);
    Handle attr(H5Aopen(data, name.c_str(), H5P_DEFAULT), H5Aclose);
    Handle space(attr.ok() ? H5Aget_space(attr.get()) : -1, H5Sclose);
    const hssize_t n = space.ok() ? H5Sget_simple_extent_npoints(space.get()) : -1;
    if (n < 0 || f.innerRadii.size() + static_cast<std::size_t>(n) > f.size())
    {
      const std::size_t total =
        f.innerRadii.size() + static_cast<std::size_t>(std::max<hssize_t>(n, 0));
      f.innerRadii.clear();
      return "attribute inner_radius has " + std::to_string(total) + " values for " +
        std::to_string(f.size()) + " points";
    }
    const std::size_t first = f.innerRadii.size();
    f.innerRadii.resize(first + static_cast<std::size_t>(n));
    if (n > 0 && H5Aread(attr.get(), H5T_NATIVE_DOUBLE, f.innerRadii.data() + first) < 0)
    {
      f.innerRadii.clear();
      return "attribute " + name + " cannot be read as float64";
    }
  }
  if (f.innerRadii.size() != f.size())
  {
    const std::string message = "attribute inner_radius has " +
      std::to_string(f.innerRadii.size()) + " values for " + std::to_string(f.size()) + " points";
    f.innerRadii.clear();
    return message;
  }
  for (std::size_t i = 0; i < f.size(); ++i)
  {
    if (!std::isfinite(f.innerRadii[i]) || f.innerRadii[i] <= 0.0 || f.innerRadii[i] > f.radii[i])
    {
      const std::string message = mustBe("attribute inner_radius of point " + formatNumber(i),
        f.innerRadii[i], "finite, > 0 and <= radius " + formatNumber(f.radii[i]));
      f.innerRadii.clear();
      return message;
    }
  }
  return {};
}

/// "a soft link", "an external link", …: what a link of this type is, for error messages.
const char* linkKind(H5L_type_t type)
{
  switch (type)
  {
    case H5L_TYPE_HARD:
      return "a hard link";
    case H5L_TYPE_SOFT:
      return "a soft link";
    case H5L_TYPE_EXTERNAL:
      return "an external link";
    default:
      return "a user-defined link";
  }
}

/// The members of a group whose names are `kind` ("bundle", "fiber") indices 0 .. INT_MAX (a
/// bundle index becomes bundle_id, an int), in numeric order.
/// Returns "" or the problem with member `bad`: a name that is no such index, or a link that is not
/// a hard link (soft and external links could leave the file, loop or dangle; fastPLI writes none).
std::string numericMembers(hid_t group, const char* kind,
  std::vector<std::pair<long, std::string>>& members, std::string& bad)
{
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0)
  {
    bad = "(unreadable group)";
    return "cannot be listed";
  }
  for (hsize_t i = 0; i < info.nlinks; ++i)
  {
    char name[256] = { 0 };
    const ssize_t length = H5Lget_name_by_idx(
      group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof(name), H5P_DEFAULT);
    if (length < 0 || length >= static_cast<ssize_t>(sizeof(name)))
    {
      bad = length < 0 ? "(unreadable name)" : std::string(name) + "...";
      return std::string("is not a ") + kind + " index";
    }
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(name, &end, 10);
    if (name[0] == '\0' || *end != '\0' || value < 0 || errno != 0)
    {
      bad = name;
      return std::string("is not a ") + kind + " index";
    }
    if (value > INT_MAX)
    {
      bad = name;
      return std::string("is larger than the largest ") + kind + " index, " +
        std::to_string(INT_MAX);
    }
    H5L_info_t link{};
    if (H5Lget_info(group, name, &link, H5P_DEFAULT) < 0 || link.type != H5L_TYPE_HARD)
    {
      bad = name;
      return std::string("is ") +
        (link.type != H5L_TYPE_HARD ? linkKind(link.type) : "an unreadable link") +
        "; only groups and datasets stored in this file are read";
    }
    members.emplace_back(value, name);
  }
  std::sort(members.begin(), members.end());
  return {};
}

/// True when `name` (a path below `loc`) exists and every link on the way is a hard link.
bool hardLinkExists(hid_t loc, const std::string& name)
{
  std::string prefix;
  std::size_t start = 0;
  while (start <= name.size())
  {
    const std::size_t slash = std::min(name.find('/', start), name.size());
    prefix = name.substr(0, slash);
    H5L_info_t link{};
    if (H5Lexists(loc, prefix.c_str(), H5P_DEFAULT) <= 0 ||
      H5Lget_info(loc, prefix.c_str(), &link, H5P_DEFAULT) < 0 || link.type != H5L_TYPE_HARD)
    {
      return false;
    }
    start = slash + 1;
  }
  return true;
}

/// True when `group` holds fastPLI bundles: a group "0" with a dataset "0" of shape (n, 4).
bool holdsBundles(hid_t group)
{
  if (!hardLinkExists(group, "0/0"))
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

/// What findBundleGroups has already seen: group addresses (hard links may form cycles, e.g. a
/// group linking to itself) and a budget of groups opened for the whole search.
struct GroupSearch
{
  std::set<haddr_t> visited;
  int budget = 10000;
  std::vector<std::string> found;
};

/// Paths ("/" = root) of the groups holding bundles, as fastPLI's save(..., group_name=...) makes
/// them. Follows hard links only, at most 8 levels deep and 10000 members per group, visits each
/// group once and at most 10000 groups in all, and does not look inside a group that holds bundles.
void findBundleGroups(hid_t group, const std::string& path, int depth, GroupSearch& search)
{
  H5O_info_t object;
  if (--search.budget < 0 || H5Oget_info2(group, &object, H5O_INFO_BASIC) < 0 ||
    !search.visited.insert(object.addr).second)
  {
    return;
  }
  if (holdsBundles(group))
  {
    search.found.push_back(path.empty() ? "/" : path);
    return;
  }
  H5G_info_t info;
  if (depth >= 8 || search.found.size() > 16 || H5Gget_info(group, &info) < 0)
  {
    return;
  }
  for (hsize_t i = 0; i < std::min<hsize_t>(info.nlinks, 10000) && search.budget > 0; ++i)
  {
    char name[256] = { 0 };
    H5L_info_t link{};
    if (H5Lget_name_by_idx(
          group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof(name), H5P_DEFAULT) < 0 ||
      H5Lget_info(group, name, &link, H5P_DEFAULT) < 0 || link.type != H5L_TYPE_HARD ||
      search.visited.count(link.u.address))
    {
      continue;
    }
    Handle child(H5Gopen2(group, name, H5P_DEFAULT), H5Gclose); // fails quietly for datasets
    if (child.ok())
    {
      findBundleGroups(child.get(), path + "/" + name, depth + 1, search);
    }
  }
}

/// The bundle groups of a file (see findBundleGroups).
std::vector<std::string> bundleGroupsOf(hid_t file)
{
  GroupSearch search;
  findBundleGroups(file, "", 0, search);
  return search.found;
}
/// One (n, 4) dataset found by the first pass of Read.
struct FiberDataset
{
  long bundle;
  std::string bundleName, fiberName;
  hsize_t points;
};

/// The group of the open `file` to read: `requested` when it names a group of the file; with
/// `requested` empty, the one group holding bundles (root included), or the root when none does.
/// Several such groups are an error listing them.
std::string bundleGroup(
  const Handle& file, const std::string& path, const std::string& requested, std::string& group)
{
  if (!requested.empty())
  {
    // Only hard links, as everywhere in the reader: H5Gopen2 would follow soft and external links.
    const std::string relative = requested.find_first_not_of('/') == std::string::npos
      ? std::string()
      : requested.substr(requested.find_first_not_of('/'));
    if (!relative.empty() && !hardLinkExists(file.get(), relative))
    {
      return path + ": Group '" + requested +
        "' is not a group stored in the file (only hard links are followed)";
    }
    Handle g(H5Gopen2(file.get(), requested.c_str(), H5P_DEFAULT), H5Gclose);
    if (!g.ok())
    {
      return path + ": Group '" + requested + "' is not a group of the file";
    }
    group = requested;
    return {};
  }
  const std::vector<std::string> groups = bundleGroupsOf(file.get());
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
} // namespace

bool FiberH5Format::LooksLikeFiberH5(const std::string& path)
{
  QuietHdf5 quiet;
  if (!fiberpli::checkRegularFile(path).empty() || H5Fis_hdf5(path.c_str()) <= 0)
  {
    return false; // never open a FIFO or device (it could block or never end)
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  return file.ok() && !bundleGroupsOf(file.get()).empty();
}

std::string FiberH5Format::Read(
  const std::string& path, const std::string& requestedGroup, FiberModel& model, PeriodicCell* cell)
{
  QuietHdf5 quiet;
  model.fibers.clear();
  const std::string special =
    fiberpli::checkRegularFile(path); // a FIFO would block the read forever
  if (!special.empty())
  {
    return "cannot read " + special;
  }
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
  const std::string groupError = bundleGroup(file, path, requestedGroup, groupPath);
  if (!groupError.empty())
  {
    return groupError;
  }
  Handle root(H5Gopen2(file.get(), groupPath.c_str(), H5P_DEFAULT), H5Gclose);
  // Messages name datasets by their full path: "/fiber_bundles/0/3".
  const std::string prefix =
    groupPath == "/" ? "" : (groupPath.front() == '/' ? groupPath : "/" + groupPath);
  std::vector<std::pair<long, std::string>> bundles;
  std::string bad = "(unreadable group)";
  std::string problem =
    root.ok() ? numericMembers(root.get(), "bundle", bundles, bad) : "cannot be opened";
  if (!problem.empty())
  {
    return path + ": member '" + printableText(prefix + "/" + bad, 80) + "' " + problem +
      " (expected bundle groups \"0\", \"1\", ... " +
      (prefix.empty() ? "at the root, or set Group" : "in Group " + prefix) + ")";
  }
  if (cell)
  {
    const std::string cellError = readCellAttribute(root.get(), *cell);
    if (!cellError.empty())
    {
      return path + ": group '" + printableText(prefix.empty() ? "/" : prefix, 80) + "' " +
        cellError;
    }
  }

  // First pass: every dataset's declared size, so that the total (a dataset hard-linked many times
  // counts every time) is checked against the file and the memory budget before any allocation.
  std::vector<FiberDataset> datasets;
  double totalPoints = 0.0;
  for (const auto& [bundleIndex, bundleName] : bundles)
  {
    Handle group(H5Gopen2(root.get(), bundleName.c_str(), H5P_DEFAULT), H5Gclose);
    if (!group.ok())
    {
      return path + ": '" + printableText(prefix + "/" + bundleName, 80) + "' is not a group";
    }
    std::vector<std::pair<long, std::string>> fibers;
    problem = numericMembers(group.get(), "fiber", fibers, bad);
    if (!problem.empty())
    {
      return path + ": member '" + printableText(prefix + "/" + bundleName + "/" + bad, 80) + "' " +
        problem;
    }
    for (const auto& fiber : fibers)
    {
      const std::string& fiberName = fiber.second;
      const std::string where =
        path + ": dataset '" + printableText(prefix + "/" + bundleName + "/" + fiberName, 80) + "'";
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
      // A chunked dataset may declare far more than the file stores.
      if (dims[0] > kMaxPointsPerFiber ||
        static_cast<double>(dims[0]) * 4 * sizeof(double) >
          kMaxExpansion * static_cast<double>(fileSize + 1))
      {
        std::ostringstream msg;
        msg << where << " declares " << dims[0] << " points, more than the file of " << fileSize
            << " bytes can hold (limit " << kMaxPointsPerFiber << ")";
        return msg.str();
      }
      totalPoints += static_cast<double>(dims[0]);
      datasets.push_back(FiberDataset{ bundleIndex, bundleName, fiberName, dims[0] });
    }
  }
  if (totalPoints * 4 * sizeof(double) > kMaxExpansion * static_cast<double>(fileSize + 1))
  {
    std::ostringstream msg;
    msg << path << ": its " << datasets.size() << " fiber datasets declare " << totalPoints
        << " points in total, more than the file of " << fileSize
        << " bytes can hold (a dataset hard-linked several times counts every time)";
    return msg.str();
  }
  std::ostringstream what;
  what << path << ": reading " << totalPoints << " points in " << datasets.size() << " fibers";
  problem = checkMemoryBudget(
    totalPoints * kBytesPerPointRead + static_cast<double>(datasets.size()) * kBytesPerFiberRead,
    what.str());
  if (!problem.empty())
  {
    return problem;
  }

  model.fibers.reserve(datasets.size());
  std::vector<double> values;
  std::int64_t nextId = 0;
  for (const FiberDataset& d : datasets)
  {
    const std::string where = path + ": dataset '" +
      printableText(prefix + "/" + d.bundleName + "/" + d.fiberName, 80) + "'";
    const std::string name = d.bundleName + "/" + d.fiberName;
    Handle data(H5Dopen2(root.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    values.resize(static_cast<std::size_t>(d.points * 4));
    if (!data.ok() ||
      (!values.empty() &&
        H5Dread(data.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0))
    {
      model.fibers.clear();
      return where + " cannot be read as floating-point numbers";
    }
    Fiber f;
    f.id = nextId++;
    f.bundle = static_cast<int>(d.bundle); // <= INT_MAX, checked by numericMembers
    f.points.resize(static_cast<std::size_t>(d.points));
    f.radii.resize(static_cast<std::size_t>(d.points));
    for (std::size_t i = 0; i < f.points.size(); ++i)
    {
      f.points[i] = { values[4 * i], values[4 * i + 1], values[4 * i + 2] };
      f.radii[i] = values[4 * i + 3];
    }
    const std::string innerError = readInnerRadiusAttribute(data.get(), f);
    if (!innerError.empty())
    {
      model.fibers.clear();
      return where + " " + innerError;
    }
    model.fibers.push_back(std::move(f));
  }
  return {};
}

std::string FiberH5Format::Write(
  const std::string& path, const FiberModel& model, const PeriodicCell& cell)
{
  std::map<int, std::vector<const Fiber*>> bundles;
  double points = 0.0;
  for (const Fiber& f : model.fibers)
  {
    if (f.bundle < 0)
    {
      // Group names are bundle indices "0", "1", …: a negative id could not be read back.
      return path + ": bundle_id " + std::to_string(f.bundle) +
        " is negative; .h5 bundles are numbered from 0";
    }
    bundles[f.bundle].push_back(&f);
    points += static_cast<double>(f.points.size());
  }
  // The file image (32 B per point plus HDF5's headers) is built in memory, next to one fiber's
  // buffer, then written by writeFileAtomically like .dat and .tck.
  const std::string tooBig = checkMemoryBudget(
    2.0 * (32.0 * points + 1024.0 * static_cast<double>(model.fibers.size())) + (1 << 20),
    path + ": the .h5 file image");
  if (!tooBig.empty())
  {
    return tooBig;
  }

  std::vector<char> image;
  {
    QuietHdf5 quiet;
    // The core driver without a backing store never touches the disk, so a full disk can only fail
    // our own checked write below, and HDF5 holds no half-written file afterwards; CLOSE_STRONG
    // makes H5Fclose release every object still open after an error.
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    if (!fapl.ok() || H5Pset_fapl_core(fapl.get(), 1 << 20, 0) < 0 ||
      H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG) < 0)
    {
      return path + ": cannot set up HDF5's in-memory file";
    }
    // The name only identifies the in-memory file inside HDF5; it must be unique while open.
    static std::atomic<unsigned> serial{ 0 };
    const std::string memoryName = path + ".in-memory-" + std::to_string(serial.fetch_add(1));
    const hid_t fileId = H5Fcreate(memoryName.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.get());
    if (fileId < 0)
    {
      return path + ": cannot create the HDF5 file in memory";
    }
    std::string error;
    if (cell.enabled() && !writeCellAttribute(fileId, cell))
    {
      error = path + ": cannot write the attribute periodic_cell";
    }
    for (auto it = bundles.begin(); it != bundles.end() && error.empty(); ++it)
    {
      const std::string groupName = std::to_string(it->first);
      Handle group(
        H5Gcreate2(fileId, groupName.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      if (!group.ok())
      {
        error = path + ": cannot create group '/" + groupName + "'";
        break;
      }
      const std::vector<const Fiber*>& fibers = it->second;
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
        Handle data(H5Dcreate2(group.get(), name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                      H5P_DEFAULT, H5P_DEFAULT),
          H5Dclose);
        if (!data.ok() ||
          H5Dwrite(data.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
        {
          error = path + ": cannot write dataset '/" + groupName + "/" + name + "'";
          break;
        }
        if (f.innerRadii.size() == f.points.size() &&
          !writeInnerRadiusAttribute(data.get(), f.innerRadii))
        {
          error = path + ": cannot write the attribute inner_radius of dataset '/" + groupName +
            "/" + name + "'";
          break;
        }
      }
    }
    if (error.empty() && H5Fflush(fileId, H5F_SCOPE_GLOBAL) < 0)
    {
      error = path + ": cannot flush the HDF5 file";
    }
    const ssize_t size = error.empty() ? H5Fget_file_image(fileId, nullptr, 0) : -1;
    if (error.empty() && size <= 0)
    {
      error = path + ": cannot get the HDF5 file image";
    }
    if (error.empty())
    {
      image.resize(static_cast<std::size_t>(size));
      if (H5Fget_file_image(fileId, image.data(), image.size()) != size)
      {
        error = path + ": cannot get the HDF5 file image";
      }
    }
    if (H5Fclose(fileId) < 0 && error.empty())
    {
      error = path + ": cannot close the HDF5 file";
    }
    if (!error.empty())
    {
      return error;
    }
  }
  return writeFileAtomically(path,
    [&image](std::ostream& out)
    {
      out.write(image.data(), static_cast<std::streamsize>(image.size()));
      return std::string();
    });
}

} // namespace fiberpli
