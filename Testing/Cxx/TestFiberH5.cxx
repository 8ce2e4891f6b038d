// fastPLI .h5 through FiberReader / FiberWriter, hardened: hard links cannot inflate a
// small file into gigabytes, soft and external links are refused, group names outside the
// bundle_id range are errors, and writing goes through the atomic path (exclusive temporary file,
// permission bits kept, a full file system leaves the old file intact). Files with links are made
// with the HDF5 API directly.
#include "ErrorCatcher.h"
#include "FiberTestData.h"
#include "vtkFiberReader.h"
#include "vtkFiberWriter.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include "vtk_hdf5.h"

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <dirent.h>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace
{
const std::string kTmp = FIBERPLI_TEST_TMP_DIR;

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A fresh HDF5 file; datasets (n, 4) of float64 with the point k = (k, 0, 0, 1).
struct H5File
{
  hid_t id;
  explicit H5File(const std::string& path)
    : id(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT))
  {
  }
  ~H5File() { H5Fclose(id); }
  void group(const char* name)
  {
    H5Gclose(H5Gcreate2(id, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  }
  void fiber(const char* name, hsize_t n)
  {
    std::vector<double> v(4 * n);
    for (hsize_t k = 0; k < n; ++k)
    {
      v[4 * k] = static_cast<double>(k);
      v[4 * k + 3] = 1.0;
    }
    const hsize_t dims[2] = { n, 4 };
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    const hid_t data =
      H5Dcreate2(id, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(data, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Dclose(data);
    H5Sclose(space);
  }
  void hardLink(const char* target, const char* name)
  {
    H5Lcreate_hard(id, target, id, name, H5P_DEFAULT, H5P_DEFAULT);
  }
};

struct ReadResult
{
  vtkSmartPointer<vtkPolyData> data;
  std::string errors;
};

ReadResult Read(const std::string& path)
{
  vtkNew<vtkFiberReader> reader;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  ReadResult r{ vtkSmartPointer<vtkPolyData>::New(), catcher->Errors };
  r.data->DeepCopy(reader->GetOutput());
  return r;
}

std::string Write(vtkPolyData* pd, const std::string& path)
{
  vtkNew<vtkFiberWriter> writer;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(writer);
  writer->SetInputData(pd);
  writer->SetFileName(path.c_str());
  const bool ok = writer->Write() == 1 && writer->GetErrorCode() == 0;
  return ok ? std::string() : "failed: " + catcher->Errors;
}

/// Peak resident memory of this process, bytes.
double PeakRss()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return 1024.0 * static_cast<double>(u.ru_maxrss);
}

/// Runs body in a child process and returns its exit status (0 = passed), so that peak-memory and
/// resource-limit checks see only what body did.
template <class Body>
int InChild(Body body)
{
  const pid_t pid = fork();
  if (pid == 0)
  {
    _exit(body());
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100 + WTERMSIG(status);
}

std::vector<std::string> FilesIn(const std::string& dir)
{
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str()))
  {
    while (dirent* e = readdir(d))
    {
      const std::string n = e->d_name;
      if (n != "." && n != "..")
      {
        names.push_back(n);
      }
    }
    closedir(d);
  }
  return names;
}

std::string FreshDir(const std::string& name)
{
  const std::string dir = kTmp + "/" + name;
  for (const std::string& f : FilesIn(dir))
  {
    unlink((dir + "/" + f).c_str());
  }
  mkdir(dir.c_str(), 0755);
  return dir;
}
} // namespace

// A 30 KB file whose one dataset is hard-linked thousands of times used to read as 60.8 M points
// (4.5 GB). Every link counts against the file size before anything is allocated.
TEST(FiberH5, HardLinkBombIsRefusedInBoundedMemory)
{
  const std::string path = kTmp + "/hardlinks.h5";
  {
    H5File f(path);
    f.group("0");
    f.fiber("0/0", 20000);
    for (int k = 1; k <= 3000; ++k)
    {
      f.hardLink("0/0", ("0/" + std::to_string(k)).c_str());
    }
  }
  struct stat st;
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  ASSERT_LT(st.st_size, 2 << 20); // 3001 x 20000 points declared in well under 2 MB
  const int status = InChild(
    [&]
    {
      const double before = PeakRss();
      const ReadResult r = Read(path);
      const bool refused = r.data->GetNumberOfPoints() == 0 &&
        r.errors.find(path) != std::string::npos &&
        r.errors.find("hard-linked") != std::string::npos;
      // 60 M points would be 1.9 GB as float64 alone; the refusal needs almost nothing.
      const bool bounded = PeakRss() - before < 64.0 * 1024 * 1024;
      if (!refused)
      {
        std::fprintf(stderr, "not refused: %s\n", r.errors.c_str());
      }
      return refused && bounded ? 0 : 1;
    });
  EXPECT_EQ(status, 0);
}

// A few hard links are legitimate (identical fibers): every link becomes a fiber.
TEST(FiberH5, FewHardLinksReadAsCopies)
{
  const std::string path = kTmp + "/fewlinks.h5";
  {
    H5File f(path);
    f.group("0");
    f.fiber("0/0", 10);
    f.hardLink("0/0", "0/1");
    f.hardLink("0", "1"); // the whole bundle again as bundle 1
  }
  const ReadResult r = Read(path);
  EXPECT_TRUE(r.errors.empty()) << r.errors;
  EXPECT_EQ(r.data->GetNumberOfLines(), 4);
  EXPECT_EQ(r.data->GetNumberOfPoints(), 40);
  EXPECT_EQ(r.data->GetCellData()->GetArray("bundle_id")->GetTuple1(3), 1.0);
}

// Within what the file holds but beyond the memory budget: refused before allocating.
TEST(FiberH5, TotalPointsCountAgainstTheMemoryBudget)
{
  const std::string path = kTmp + "/budget.h5";
  {
    H5File f(path);
    f.group("0");
    f.fiber("0/0", 50000);
    f.fiber("0/1", 50000);
  }
  setenv("FIBERPLI_MEMORY_LIMIT", "1M", 1);
  const ReadResult r = Read(path);
  unsetenv("FIBERPLI_MEMORY_LIMIT");
  EXPECT_EQ(r.data->GetNumberOfPoints(), 0);
  EXPECT_NE(r.errors.find("100000 points"), std::string::npos) << r.errors;
  EXPECT_NE(r.errors.find("memory budget"), std::string::npos) << r.errors;
  EXPECT_EQ(Read(path).data->GetNumberOfPoints(), 100000); // the default budget reads it
}

// External links would open other files (anywhere, any size); soft links can dangle or loop.
TEST(FiberH5, SoftAndExternalLinksAreRefused)
{
  const std::string other = kTmp + "/linked-target.h5";
  {
    H5File f(other);
    f.group("0");
    f.fiber("0/0", 5);
  }
  const std::string ext = kTmp + "/external.h5";
  {
    H5File f(ext);
    f.group("0");
    H5Lcreate_external(other.c_str(), "/0/0", f.id, "0/0", H5P_DEFAULT, H5P_DEFAULT);
  }
  ReadResult r = Read(ext);
  EXPECT_EQ(r.data->GetNumberOfPoints(), 0);
  EXPECT_NE(r.errors.find("'/0/0' is an external link"), std::string::npos) << r.errors;
  vtkNew<vtkFiberReader> sniffer;
  EXPECT_EQ(sniffer->CanReadFile(ext.c_str()), 0);

  const std::string rootExt = kTmp + "/external-root.h5";
  {
    H5File f(rootExt);
    H5Lcreate_external(other.c_str(), "/0", f.id, "0", H5P_DEFAULT, H5P_DEFAULT);
  }
  r = Read(rootExt);
  EXPECT_NE(r.errors.find("member '/0' is an external link"), std::string::npos) << r.errors;

  const std::string soft = kTmp + "/soft.h5";
  {
    H5File f(soft);
    f.group("0");
    f.fiber("0/0", 5);
    H5Lcreate_soft("/0/0", f.id, "0/1", H5P_DEFAULT, H5P_DEFAULT);
    H5Lcreate_soft("/nowhere", f.id, "0/2", H5P_DEFAULT, H5P_DEFAULT);
  }
  r = Read(soft);
  EXPECT_NE(r.errors.find("'/0/1' is a soft link"), std::string::npos) << r.errors;
}

// Group 2147483648 became bundle -2147483648.
TEST(FiberH5, GroupNamesOutsideTheBundleIdRangeAreRefused)
{
  const std::string big = kTmp + "/biggroup.h5";
  {
    H5File f(big);
    f.group("2147483648");
    f.fiber("2147483648/0", 3);
  }
  ReadResult r = Read(big);
  EXPECT_EQ(r.data->GetNumberOfPoints(), 0);
  EXPECT_NE(r.errors.find(big), std::string::npos) << r.errors;
  EXPECT_NE(
    r.errors.find("'/2147483648' is larger than the largest bundle index"), std::string::npos)
    << r.errors;
  EXPECT_NE(r.errors.find("2147483647"), std::string::npos) << r.errors;

  const std::string largest = kTmp + "/largestgroup.h5";
  {
    H5File f(largest);
    f.group("2147483647");
    f.fiber("2147483647/0", 3);
  }
  r = Read(largest);
  EXPECT_TRUE(r.errors.empty()) << r.errors;
  ASSERT_EQ(r.data->GetNumberOfLines(), 1);
  EXPECT_EQ(r.data->GetCellData()->GetArray("bundle_id")->GetTuple1(0), 2147483647.0);
}

// A 0600 file stayed 0600 for .dat but became 0644 for .h5.
TEST(FiberH5, ReplacedFileKeepsItsMode)
{
  const std::string dir = FreshDir("h5mode");
  const std::string path = dir + "/private.h5";
  ASSERT_EQ(Write(MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 1 } } }), path), "");
  ASSERT_EQ(chmod(path.c_str(), 0600), 0);
  ASSERT_EQ(Write(MakeFibers({ { { 0, 0, 0, 1 }, { 2, 0, 0, 1 } } }), path), "");
  struct stat st;
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(Read(path).data->GetNumberOfPoints(), 2);
  EXPECT_EQ(FilesIn(dir).size(), 1u) << "temporary file left behind";
}

// The old temporary name <target>.tmp-<pid> was predictable and a symlink planted there was
// followed, overwriting its target.
TEST(FiberH5, PlantedSymlinkIsNotFollowed)
{
  const std::string dir = FreshDir("h5symlink");
  const std::string victim = dir + "/victim.txt";
  std::ofstream(victim) << "precious";
  const std::string path = dir + "/out.h5";
  const std::string pid = std::to_string(getpid());
  for (const std::string& name :
    { path + ".tmp-" + pid, path + ".tmp-" + pid + "-0", path + ".tmp-" + pid + "-1" })
  {
    ASSERT_EQ(symlink(victim.c_str(), name.c_str()), 0);
  }
  ASSERT_EQ(Write(MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 1 } } }), path), "");
  EXPECT_EQ(Slurp(victim), "precious");
  EXPECT_EQ(Read(path).data->GetNumberOfPoints(), 2);
  EXPECT_EQ(FilesIn(dir).size(), 5u) << "temporary file left behind";
}

// A full file system (here: RLIMIT_FSIZE in a child process, which fails writes with EFBIG like
// ENOSPC) gives an error naming the file, keeps the old file and leaves no temporary file.
TEST(FiberH5, FullFileSystemKeepsTheOldFile)
{
  const std::string dir = FreshDir("h5full");
  const std::string path = dir + "/keep.h5";
  ASSERT_EQ(Write(MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 1 } } }), path), "");
  const std::string before = Slurp(path);
  std::vector<std::vector<std::array<double, 4>>> fibers(200);
  for (std::size_t f = 0; f < fibers.size(); ++f)
  {
    for (int k = 0; k < 50; ++k)
    {
      fibers[f].push_back({ static_cast<double>(k), static_cast<double>(f), 0.0, 1.0 });
    }
  }
  auto big = MakeFibers(fibers);
  const int status = InChild(
    [&]
    {
      std::signal(SIGXFSZ, SIG_IGN);
      const rlimit limit{ static_cast<rlim_t>(before.size() + 4096),
        static_cast<rlim_t>(before.size() + 4096) };
      setrlimit(RLIMIT_FSIZE, &limit);
      const std::string error = Write(big, path);
      const bool ok =
        error.find(path) != std::string::npos && error.find("File too large") != std::string::npos;
      if (!ok)
      {
        std::fprintf(stderr, "unexpected: %s\n", error.c_str());
      }
      return ok ? 0 : 1;
    });
  EXPECT_EQ(status, 0);
  EXPECT_EQ(Slurp(path), before);
  EXPECT_EQ(FilesIn(dir).size(), 1u) << "temporary file left behind";
}

// inner_radius (myelinated fibers) round-trips through .h5 as an attribute of each fiber's dataset,
// also past HDF5's 64 KiB object-header limit (a 10 000-point fiber), while the (n, 4) datasets
// that fastPLI reads stay exactly as they were and nothing else is added to the bundle groups.
TEST(FiberH5, InnerRadiusRoundTripsBesideTheFastPLIDatasets)
{
  std::vector<std::vector<std::array<double, 4>>> fibers(2);
  for (int k = 0; k < 10000; ++k)
  {
    fibers[0].push_back({ 0.01 * k, 0.0, 0.0, 1.0 + 0.1 * std::sin(0.01 * k) });
  }
  for (int k = 0; k < 5; ++k)
  {
    fibers[1].push_back({ 0.0, 5.0, 1.0 * k, 0.8 });
  }
  auto pd = MakeFibers(fibers);
  vtkNew<vtkDoubleArray> inner;
  inner->SetName("inner_radius");
  vtkDataArray* radius = pd->GetPointData()->GetArray("radius");
  for (vtkIdType p = 0; p < pd->GetNumberOfPoints(); ++p)
  {
    inner->InsertNextValue((0.55 + 0.1 * (p % 3)) * radius->GetTuple1(p));
  }
  pd->GetPointData()->AddArray(inner);
  const std::string path = kTmp + "/myelin.h5";
  ASSERT_EQ(Write(pd, path), "");

  const ReadResult r = Read(path);
  ASSERT_TRUE(r.errors.empty()) << r.errors;
  vtkDataArray* back = r.data->GetPointData()->GetArray("inner_radius");
  ASSERT_NE(back, nullptr);
  ASSERT_EQ(back->GetNumberOfTuples(), pd->GetNumberOfPoints());
  for (vtkIdType p = 0; p < pd->GetNumberOfPoints(); ++p)
  {
    ASSERT_EQ(back->GetTuple1(p), inner->GetValue(p)) << p; // float64 both ways: exact
    ASSERT_EQ(r.data->GetPointData()->GetArray("radius")->GetTuple1(p), radius->GetTuple1(p));
  }

  // What fastPLI sees: group "0" with exactly one (n, 4) float64 dataset "0" holding x, y, z, r.
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  H5G_info_t info;
  const hid_t group = H5Gopen2(file, "0", H5P_DEFAULT);
  ASSERT_GE(H5Gget_info(group, &info), 0);
  EXPECT_EQ(info.nlinks, 1u);
  const hid_t data = H5Dopen2(group, "0", H5P_DEFAULT);
  const hid_t space = H5Dget_space(data);
  hsize_t dims[2] = { 0, 0 };
  ASSERT_EQ(H5Sget_simple_extent_dims(space, dims, nullptr), 2);
  EXPECT_EQ(dims[0], 10000u);
  EXPECT_EQ(dims[1], 4u);
  std::vector<double> values(4 * 10000);
  ASSERT_GE(H5Dread(data, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  EXPECT_EQ(values[4 * 123], pd->GetPoint(123)[0]);
  EXPECT_EQ(values[4 * 123 + 3], radius->GetTuple1(123));
  EXPECT_GT(H5Aexists(data, "inner_radius_2"), 0); // 10 000 values in attributes of 4096
  EXPECT_EQ(H5Aexists(data, "inner_radius_3"), 0);
  EXPECT_GT(H5Aexists(data, "inner_radius"), 0);
  H5Sclose(space);
  H5Dclose(data);
  H5Gclose(group);
  H5Fclose(file);

  // Without the array: no attribute, no inner_radius read back.
  pd->GetPointData()->RemoveArray("inner_radius");
  ASSERT_EQ(Write(pd, path), "");
  EXPECT_EQ(Read(path).data->GetPointData()->GetArray("inner_radius"), nullptr);
}

TEST(FiberH5, MalformedInnerRadiusAttributeIsNamed)
{
  const std::string path = kTmp + "/badmyelin.h5";
  {
    H5File f(path);
    f.group("0");
    f.fiber("0/0", 4);
    const hid_t data = H5Dopen2(f.id, "0/0", H5P_DEFAULT);
    const hsize_t n = 3; // one value short
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t attr =
      H5Acreate2(data, "inner_radius", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    const double v[3] = { 0.5, 0.5, 0.5 };
    H5Awrite(attr, H5T_NATIVE_DOUBLE, v);
    H5Aclose(attr);
    H5Sclose(space);
    H5Dclose(data);
  }
  const ReadResult r = Read(path);
  EXPECT_NE(
    r.errors.find("'/0/0' attribute inner_radius has 3 values for 4 points"), std::string::npos)
    << r.errors;
  EXPECT_EQ(r.data->GetNumberOfPoints(), 0);
}
