// FiberReader on fastPLI .h5 files saved under a group (fastPLI's fiber_bundles.save(...,
// group_name=...)): the files are written here with the raw HDF5 API, as h5py lays them out, not
// with our writer.
#include "ErrorCatcher.h"
#include "vtkFiberReader.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include "vtk_hdf5.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace
{
const std::string kTmp = FIBERPLI_TEST_TMP_DIR;

/// Creates group `path` (intermediate groups too) in `file`.
hid_t MakeGroup(hid_t file, const std::string& path)
{
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  const hid_t g = H5Gcreate2(file, path.c_str(), lcpl, H5P_DEFAULT, H5P_DEFAULT);
  H5Pclose(lcpl);
  return g;
}

/// Writes bundles[b][f] = n×4 rows as datasets <group>/<b>/<f>.
void WriteBundles(hid_t file, const std::string& group,
  const std::vector<std::vector<std::vector<double>>>& bundles)
{
  for (std::size_t b = 0; b < bundles.size(); ++b)
  {
    const hid_t g = MakeGroup(file, group + "/" + std::to_string(b));
    for (std::size_t f = 0; f < bundles[b].size(); ++f)
    {
      const hsize_t dims[2] = { bundles[b][f].size() / 4, 4 };
      const hid_t space = H5Screate_simple(2, dims, nullptr);
      const hid_t d = H5Dcreate2(
        g, std::to_string(f).c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, bundles[b][f].data());
      H5Dclose(d);
      H5Sclose(space);
    }
    H5Gclose(g);
  }
}

/// A file with bundles under each of `groups` (bundle b of group k is shifted by 100·k in x) and
/// an unrelated dataset /meta/version, like fastPLI's simulation files carry.
std::string MakeFile(const std::string& name, const std::vector<std::string>& groups)
{
  const std::string path = kTmp + "/" + name;
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  for (std::size_t k = 0; k < groups.size(); ++k)
  {
    const double x = 100.0 * k;
    WriteBundles(file, groups[k],
      { { { x, 0, 0, 1, x + 1, 0, 0, 1 }, { x, 5, 0, 1, x + 1, 5, 0, 1, x + 2, 5, 0, 1 } },
        { { x, 0, 9, 2, x, 1, 9, 2 } } });
  }
  const hid_t meta = MakeGroup(file, "/meta");
  const hsize_t one = 1;
  const hid_t space = H5Screate_simple(1, &one, nullptr);
  const double version = 1.0;
  const hid_t d =
    H5Dcreate2(meta, "version", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &version);
  H5Dclose(d);
  H5Sclose(space);
  H5Gclose(meta);
  H5Fclose(file);
  return path;
}

struct ReadResult
{
  vtkIdType fibers = 0, points = 0;
  double firstX = -1;
  int lastBundle = -1;
  std::string errors;
};

ReadResult Read(const std::string& path, const char* group)
{
  vtkNew<vtkFiberReader> reader;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->SetGroup(group);
  reader->Update();
  ReadResult r;
  vtkPolyData* out = reader->GetOutput();
  r.fibers = out->GetNumberOfCells();
  r.points = out->GetNumberOfPoints();
  if (r.points > 0)
  {
    r.firstX = out->GetPoint(0)[0];
    r.lastBundle =
      static_cast<int>(out->GetCellData()->GetArray("bundle_id")->GetTuple1(r.fibers - 1));
  }
  r.errors = catcher->Errors;
  return r;
}
} // namespace

TEST(FiberReaderH5Groups, OneGroupIsFoundAutomatically)
{
  for (const char* group : { "/fiber_bundles", "/simulation/model/fibers" })
  {
    const std::string path = MakeFile("one_group.h5", { group });
    vtkNew<vtkFiberReader> sniff;
    EXPECT_EQ(sniff->CanReadFile(path.c_str()), 1) << group;
    const ReadResult automatic = Read(path, nullptr);
    EXPECT_TRUE(automatic.errors.empty()) << automatic.errors;
    EXPECT_EQ(automatic.fibers, 3) << group;
    EXPECT_EQ(automatic.points, 7) << group;
    EXPECT_EQ(automatic.lastBundle, 1);
    // Naming it gives the same, with or without the leading slash.
    EXPECT_EQ(Read(path, group).points, 7);
    EXPECT_EQ(Read(path, group + 1).points, 7);
  }
}

TEST(FiberReaderH5Groups, SeveralGroupsNeedTheGroupProperty)
{
  const std::string path = MakeFile("two_groups.h5", { "/before", "/after" });
  const ReadResult automatic = Read(path, "");
  EXPECT_EQ(automatic.fibers, 0);
  EXPECT_NE(automatic.errors.find("several groups hold fiber bundles (/after, /before); set Group"),
    std::string::npos)
    << automatic.errors;
  const ReadResult after = Read(path, "after");
  EXPECT_TRUE(after.errors.empty()) << after.errors;
  EXPECT_EQ(after.firstX, 100.0); // the second group written
  EXPECT_EQ(Read(path, "/before").firstX, 0.0);
}

TEST(FiberReaderH5Groups, BadGroupIsAnErrorNamingIt)
{
  const std::string path = MakeFile("bad_group.h5", { "/fiber_bundles" });
  const ReadResult missing = Read(path, "nope");
  EXPECT_NE(missing.errors.find("Group 'nope' is not a group"), std::string::npos)
    << missing.errors;
  const ReadResult notBundles = Read(path, "/meta");
  EXPECT_NE(
    notBundles.errors.find("member '/meta/version' is not a bundle index"), std::string::npos)
    << notBundles.errors;
  // The reader stays usable.
  EXPECT_EQ(Read(path, "").fibers, 3);
}

TEST(FiberReaderH5Groups, SelfLinkedGroupsAreVisitedOnce)
{
  // A group holding 30 hard links to itself: a search without a visited set would walk 30^8
  // paths (FiberReader and File→Open hung).
  const std::string path = MakeFile("self_linked.h5", { "/fiber_bundles" });
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t loop = MakeGroup(file, "/loop");
  for (int k = 0; k < 30; ++k)
  {
    H5Lcreate_hard(
      file, "/loop", loop, ("self" + std::to_string(k)).c_str(), H5P_DEFAULT, H5P_DEFAULT);
  }
  H5Gclose(loop);
  H5Fclose(file);
  vtkNew<vtkFiberReader> sniff;
  EXPECT_EQ(sniff->CanReadFile(path.c_str()), 1);
  const ReadResult automatic = Read(path, nullptr);
  EXPECT_TRUE(automatic.errors.empty()) << automatic.errors;
  EXPECT_EQ(automatic.fibers, 3);
}

TEST(FiberReaderH5Groups, GroupThroughASoftLinkIsRefused)
{
  // Only data stored in the file by hard links is read; Group must not bypass that.
  const std::string path = MakeFile("soft_group.h5", { "/fiber_bundles" });
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  H5Lcreate_soft("/fiber_bundles", file, "/alias", H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(file);
  const ReadResult soft = Read(path, "alias");
  EXPECT_EQ(soft.fibers, 0);
  EXPECT_NE(soft.errors.find("Group 'alias' is not a group stored in the file (only hard links"),
    std::string::npos)
    << soft.errors;
  EXPECT_EQ(Read(path, "fiber_bundles").fibers, 3);
}
