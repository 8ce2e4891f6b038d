// Fuzzing of the .h5 reader, at the level of the HDF5 objects: random files made
// with the HDF5 API (fixed seed) with bundles and fibers of random shapes, declared sizes (chunked
// datasets declaring up to 1e12 points), element types, names (negative, above INT_MAX, not
// numbers) and links (hard links to datasets and groups, soft links dangling or looping,
// external links to existing and missing files and to the file itself). Everything is read through
// FiberReader under a 64 MiB memory budget in a child process: nothing may crash or grow the
// peak memory beyond the budget; every read either fails with an error naming the file or gives
// fibers that satisfy the data contract. (Byte-level corruption is not fuzzed here: HDF5 1.10.8
// itself crashes on some corrupted link messages, inside H5Lget_name_by_idx, before any FiberPLI
// code can check anything.)
#include "ErrorCatcher.h"
#include "vtkFiberReader.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include "vtk_hdf5.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace
{
const std::string kTmp = FIBERPLI_TEST_TMP_DIR;

/// One random fastPLI-like file at `path`.
void RandomFile(const std::string& path, const std::string& other, std::mt19937_64& rng)
{
  auto pick = [&rng](std::uint64_t n) { return static_cast<int>(rng() % n); };
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const char* odd[] = { "-1", "2147483648", "99999999999999999999", "x", "", "0 ", "007" };
  const int bundles = 1 + pick(3);
  std::vector<std::string> datasets;
  for (int b = 0; b < bundles; ++b)
  {
    const std::string group = pick(25) == 0 ? odd[pick(7)] : std::to_string(b);
    if (group.empty() ||
      H5Gclose(H5Gcreate2(f, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)) < 0)
    {
      continue;
    }
    for (int k = 0, n = 1 + pick(4); k < n; ++k)
    {
      const std::string name = group + "/" + (pick(40) == 0 ? odd[pick(7)] : std::to_string(k));
      const int cols = pick(30) == 0 ? 3 : 4;
      const hsize_t points = static_cast<hsize_t>(pick(30) == 0 ? 0 : 1 + pick(50));
      const bool huge = pick(25) == 0; // chunked, declaring far more than is written
      hsize_t dims[2] = { huge ? hsize_t{ 1000000000000ULL } : points, static_cast<hsize_t>(cols) };
      hsize_t maxdims[2] = { H5S_UNLIMITED, static_cast<hsize_t>(cols) };
      const hid_t space = H5Screate_simple(2, dims, huge ? maxdims : nullptr);
      const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
      if (huge)
      {
        const hsize_t chunk[2] = { 16, static_cast<hsize_t>(cols) };
        H5Pset_chunk(dcpl, 2, chunk);
      }
      const hid_t types[] = { H5T_IEEE_F64LE, H5T_IEEE_F32BE, H5T_STD_I32LE, H5T_C_S1 };
      const hid_t type = types[pick(30) == 0 ? 1 + pick(3) : 0];
      const hid_t data = H5Dcreate2(f, name.c_str(), type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
      if (data >= 0 && !huge && points > 0 && type != H5T_C_S1)
      {
        std::vector<double> v(points * cols);
        for (std::size_t i = 0; i < v.size(); ++i)
        {
          const double specials[] = { NAN, INFINITY, -1.0, 0.0, 1e308 };
          v[i] = pick(1500) == 0 ? specials[pick(5)] : 1.0 + 0.1 * static_cast<double>(i % 7);
        }
        H5Dwrite(data, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
      }
      if (data >= 0)
      {
        datasets.push_back(name);
        H5Dclose(data);
      }
      H5Pclose(dcpl);
      H5Sclose(space);
    }
    const std::string extra = group + "/" + std::to_string(10 + pick(1000));
    switch (pick(10))
    {
      case 0: // many hard links to one dataset (counted every time)
        for (int k = 0, n = 1 + pick(3000); k < n && !datasets.empty(); ++k)
        {
          H5Lcreate_hard(f, datasets.front().c_str(), f,
            (group + "/" + std::to_string(100 + k)).c_str(), H5P_DEFAULT, H5P_DEFAULT);
        }
        break;
      case 1: // a group hard-linked into itself
        H5Lcreate_hard(f, group.c_str(), f, extra.c_str(), H5P_DEFAULT, H5P_DEFAULT);
        break;
      case 2: // dangling or looping soft links
        H5Lcreate_soft(
          pick(2) ? "/nowhere" : ("/" + extra).c_str(), f, extra.c_str(), H5P_DEFAULT, H5P_DEFAULT);
        break;
      case 3: // external links: another file, a missing file, this file
      {
        const std::string target = pick(3) == 0 ? path : (pick(2) ? other : kTmp + "/missing.h5");
        H5Lcreate_external(target.c_str(), "/0/0", f, extra.c_str(), H5P_DEFAULT, H5P_DEFAULT);
        H5Lcreate_external(target.c_str(), "/0", f, std::to_string(bundles + pick(3)).c_str(),
          H5P_DEFAULT, H5P_DEFAULT);
        break;
      }
      default:
        break;
    }
  }
  H5Fclose(f);
}

/// 0 when every mutated file was read safely, else the number of contract violations.
int FuzzLoop()
{
  H5Eset_auto2(
    H5E_DEFAULT, nullptr, nullptr); // the generator's own failures (e.g. a name twice) are expected
  setenv("FIBERPLI_MEMORY_LIMIT", "64M", 1);
  const double before = []
  {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return 1024.0 * u.ru_maxrss;
  }();
  std::mt19937_64 rng(20261201);
  int violations = 0, reads = 0;
  const std::string other = kTmp + "/fuzz-other.h5", path = kTmp + "/fuzz-case.h5";
  RandomFile(other, other, rng);
  for (int m = 0; m < 300; ++m)
  {
    RandomFile(path, other, rng);
    vtkNew<vtkFiberReader> reader;
    vtkNew<ErrorCatcher> catcher;
    catcher->Watch(reader);
    reader->CanReadFile(path.c_str());
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkPolyData* out = reader->GetOutput();
    if (!catcher->Errors.empty())
    {
      if (catcher->Errors.find(path) == std::string::npos || out->GetNumberOfPoints() != 0)
      {
        std::fprintf(stderr, "file %d: error without the file name or with output: %s\n", m,
          catcher->Errors.c_str());
        ++violations;
      }
      continue;
    }
    ++reads;
    vtkDataArray* r = out->GetPointData()->GetArray("radius");
    const bool valid = r && r->GetNumberOfTuples() == out->GetNumberOfPoints() &&
      (out->GetNumberOfPoints() == 0 ||
        (r->GetRange()[0] > 0.0 && std::isfinite(r->GetRange()[1])));
    if (!valid)
    {
      std::fprintf(stderr, "file %d: read without error but invalid fibers\n", m);
      ++violations;
    }
  }
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const double grown = 1024.0 * u.ru_maxrss - before;
  std::fprintf(stderr, "h5 fuzz: %d of 300 files read without error, peak RSS grew by %.0f MB\n",
    reads, grown / 1048576.0);
  return violations + (grown > 256.0 * 1024 * 1024 ? 1 : 0);
}
} // namespace

TEST(FiberH5Fuzz, RandomFilesNeverCrashOrExhaustMemory)
{
  const pid_t pid = fork();
  if (pid == 0)
  {
    _exit(FuzzLoop() == 0 ? 0 : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "the reader crashed (signal "
                                 << (WIFSIGNALED(status) ? WTERMSIG(status) : 0) << ")";
  EXPECT_EQ(WEXITSTATUS(status), 0);
}
