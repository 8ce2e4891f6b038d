// FiberReader / FiberWriter: round trips through every format pair, content sniffing, bad files
// (clear error naming the file, pipeline usable afterwards), and writes that never destroy a file.
#include "ErrorCatcher.h"
#include "FiberTestData.h"
#include "vtkFiberCubeSource.h"
#include "vtkFiberReader.h"
#include "vtkFiberWriter.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace
{
const std::string kTmp = FIBERPLI_TEST_TMP_DIR;
const std::string kData = FIBERPLI_TEST_DATA_DIR;

/// Three bundles of fibers with varying radii (what .dat and .h5 can hold completely).
vtkSmartPointer<vtkPolyData> Model()
{
  auto pd = MakeFibers({ { { 0.125, 1, 2, 0.5 }, { 1.5, 1.25, 2, 0.75 }, { 3, 1.5, 2.5, 0.5 } },
    { { -1, -2, -3, 1.0 }, { -1.5, -2.5, -3.5, 1.5 } },
    { { 10, 0, 0, 0.3 }, { 10, 1, 0, 0.3 }, { 10, 2, 1, 0.4 }, { 10, 3, 1, 0.3 } },
    { { 5, 5, 5, 2.0 }, { 6, 5, 5, 2.0 } } });
  // bundles 0, 1, 0, 1 from MakeFibers; make the last one a third bundle.
  vtkDataArray* bundle = pd->GetCellData()->GetArray("bundle_id");
  bundle->SetTuple1(3, 2);
  return pd;
}

bool Write(vtkPolyData* pd, const std::string& path, ErrorCatcher* catcher = nullptr)
{
  vtkNew<vtkFiberWriter> writer;
  if (catcher)
  {
    catcher->Watch(writer);
  }
  writer->SetInputData(pd);
  writer->SetFileName(path.c_str());
  return writer->Write() == 1 && writer->GetErrorCode() == 0;
}

vtkSmartPointer<vtkPolyData> Read(
  const std::string& path, ErrorCatcher* catcher = nullptr, double defaultRadius = 1.0)
{
  vtkNew<vtkFiberReader> reader;
  if (catcher)
  {
    catcher->Watch(reader);
  }
  reader->SetFileName(path.c_str());
  reader->SetDefaultRadius(defaultRadius);
  reader->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(reader->GetOutput());
  return out;
}

/// Points equal within tol, radii compared when compareRadii, bundle grouping when compareBundles.
void ExpectSameFibers(
  vtkPolyData* a, vtkPolyData* b, double tol, bool compareRadii, bool compareBundles)
{
  ASSERT_EQ(a->GetNumberOfLines(), b->GetNumberOfLines());
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(p[k], q[k], tol) << "point " << i;
    }
    if (compareRadii)
    {
      EXPECT_NEAR(a->GetPointData()->GetArray("radius")->GetTuple1(i),
        b->GetPointData()->GetArray("radius")->GetTuple1(i), tol);
    }
  }
  if (compareBundles)
  {
    for (vtkIdType c = 0; c < a->GetNumberOfLines(); ++c)
    {
      EXPECT_EQ(a->GetCellData()->GetArray("bundle_id")->GetTuple1(c),
        b->GetCellData()->GetArray("bundle_id")->GetTuple1(c));
    }
  }
}

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
} // namespace

TEST(FiberReaderWriter, DatAndH5KeepPointsRadiiAndBundles)
{
  // Fibers sorted by bundle (the writers group by bundle), so the order is comparable.
  auto model = MakeFibers({ { { 0.125, 1, 2, 0.5 }, { 1.5, 1.25, 2, 0.75 }, { 3, 1.5, 2.5, 0.5 } },
    { { -1, -2, -3, 1.0 }, { -1.5, -2.5, -3.5, 1.5 } } });
  model->GetCellData()->GetArray("bundle_id")->SetTuple1(1, 1);
  for (const char* ext : { ".dat", ".h5" })
  {
    const std::string path = kTmp + "/roundtrip" + ext;
    ASSERT_TRUE(Write(model, path)) << ext;
    auto back = Read(path);
    ExpectSameFibers(model, back, 0.0, true, true);
  }
}

TEST(FiberReaderWriter, EveryFormatPairKeepsWhatBothHold)
{
  // .dat/.h5 hold points, radii and bundles; .tck holds float32 points and, in .radius.tsf,
  // float32 radii, but no bundles.
  auto original = Model();
  const char* formats[] = { ".dat", ".h5", ".tck" };
  for (const char* from : formats)
  {
    const std::string first = kTmp + "/pair_from" + from;
    ASSERT_TRUE(Write(original, first)) << from;
    auto a = Read(first, nullptr, 0.5);
    for (const char* to : formats)
    {
      const std::string second = kTmp + "/pair_" + std::string(from + 1) + "_to" + to;
      ASSERT_TRUE(Write(a, second)) << from << " -> " << to;
      auto b = Read(second, nullptr, 0.5);
      const bool bundles = std::string(from) != ".tck" && std::string(to) != ".tck";
      // The writers group fibers by bundle: compare the bundle-sorted original with the result.
      ExpectSameFibers(a, b, std::string(to) == ".tck" ? 1e-6 : 0.0, true, bundles);
      EXPECT_EQ(b->GetNumberOfLines(), 4) << from << " -> " << to;
    }
  }
}

TEST(FiberReaderWriter, ReadsTheReferenceToolboxAndTrackSamples)
{
  vtkNew<ErrorCatcher> catcher;
  auto cube = Read(kData + "/fastpli/cube.dat", catcher);
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_GT(cube->GetNumberOfLines(), 0);
  auto trk = Read(kData + "/tracks/sample.trk", catcher, 0.7);
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  ASSERT_EQ(trk->GetNumberOfLines(), 1); // the second track has a single point: dropped, warned
  EXPECT_NE(
    catcher->Warnings.find("1 fiber(s) with fewer than 2 points dropped"), std::string::npos)
    << catcher->Warnings;
  EXPECT_EQ(trk->GetPointData()->GetArray("radius")->GetTuple1(0), 0.7);
  auto tck = Read(kData + "/tracks/sample.tck", catcher, 0.7);
  ASSERT_EQ(tck->GetNumberOfLines(), 2);
  double p[3];
  tck->GetPoint(3, p);
  EXPECT_EQ(p[0], 0.25);
}

TEST(FiberReaderWriter, CanReadFileLooksAtTheContent)
{
  vtkNew<vtkFiberReader> reader;
  const std::string tecplot = kTmp + "/tecplot.dat";
  std::ofstream(tecplot) << "TITLE = \"x\"\nVARIABLES = \"X\" \"Y\"\nZONE I=2\n1 2\n3 4\n";
  EXPECT_EQ(reader->CanReadFile(tecplot.c_str()), 0);
  EXPECT_EQ(reader->CanReadFile((kData + "/fastpli/fastpli.dat").c_str()), 1);
  EXPECT_EQ(reader->CanReadFile((kData + "/tracks/sample.tck").c_str()), 1);
  EXPECT_EQ(reader->CanReadFile((kData + "/tracks/sample.trk").c_str()), 1);
  const std::string h5 = kTmp + "/sniff.h5";
  ASSERT_TRUE(Write(Model(), h5));
  EXPECT_EQ(reader->CanReadFile(h5.c_str()), 1);
  const std::string fakeH5 = kTmp + "/fake.h5";
  std::ofstream(fakeH5) << "not hdf5";
  EXPECT_EQ(reader->CanReadFile(fakeH5.c_str()), 0);
  EXPECT_EQ(reader->CanReadFile((kTmp + "/missing.dat").c_str()), 0);
}

TEST(FiberReaderWriter, BadFilesGiveAnErrorNamingFileAndLineThenRecover)
{
  const std::string bad = kTmp + "/bad.dat";
  std::ofstream(bad) << "0 0 0 1\n1 0 0 1\n2 zero 0 1\n";
  vtkNew<vtkFiberReader> reader;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(reader);
  reader->SetFileName(bad.c_str());
  reader->Update();
  EXPECT_NE(catcher->Errors.find("bad.dat"), std::string::npos) << catcher->Errors;
  EXPECT_NE(catcher->Errors.find("line 3"), std::string::npos) << catcher->Errors;
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);

  catcher->Clear();
  const std::string truncated = kTmp + "/truncated.tck";
  const std::string full = Slurp(kData + "/tracks/sample.tck");
  std::ofstream(truncated, std::ios::binary) << full.substr(0, full.size() - 20);
  reader->SetFileName(truncated.c_str());
  reader->Update();
  EXPECT_NE(catcher->Errors.find("truncated.tck"), std::string::npos) << catcher->Errors;
  EXPECT_NE(catcher->Errors.find("byte"), std::string::npos) << catcher->Errors;

  catcher->Clear();
  reader->SetFileName((kData + "/fastpli/cube.dat").c_str());
  reader->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_GT(reader->GetOutput()->GetNumberOfLines(), 0);
}

TEST(FiberReaderWriter, AFailedWriteKeepsTheExistingFile)
{
  for (const char* ext : { ".dat", ".h5", ".tck" })
  {
    const std::string path = kTmp + "/keep" + ext;
    ASSERT_TRUE(Write(Model(), path));
    const std::string before = Slurp(path);
    // Invalid fibers (radius 0): the writer refuses, the file stays as it was.
    vtkNew<ErrorCatcher> catcher;
    EXPECT_FALSE(Write(MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 0 } } }), path, catcher)) << ext;
    EXPECT_NE(catcher->Errors.find("radius 0"), std::string::npos) << catcher->Errors;
    EXPECT_EQ(Slurp(path), before) << ext;
  }
  // A target in a directory that does not exist: an error naming the path, nothing written.
  vtkNew<ErrorCatcher> catcher;
  const std::string nowhere = kTmp + "/no/such/dir/x.dat";
  EXPECT_FALSE(Write(Model(), nowhere, catcher));
  EXPECT_NE(catcher->Errors.find(nowhere), std::string::npos) << catcher->Errors;
}

TEST(FiberReaderWriter, TckKeepsRadiiInItsTrackScalarFile)
{
  auto model = Model();
  const std::string path = kTmp + "/radii.tck";
  ASSERT_TRUE(Write(model, path));
  std::ifstream tsf(kTmp + "/radii.radius.tsf");
  ASSERT_TRUE(tsf.good()) << "no .radius.tsf written beside the .tck";
  auto back = Read(path, nullptr, 9.0);
  ASSERT_EQ(back->GetNumberOfPoints(), model->GetNumberOfPoints());
  vtkDataArray* r = back->GetPointData()->GetArray("radius");
  EXPECT_FLOAT_EQ(static_cast<float>(r->GetTuple1(0)), 0.5f);
  EXPECT_FLOAT_EQ(static_cast<float>(r->GetTuple1(1)), 0.75f);
  EXPECT_LT(r->GetRange()[1], 9.0); // no point fell back to DefaultRadius
}

TEST(FiberReaderWriter, H5RefusesNegativeBundleIds)
{
  auto model = Model();
  model->GetCellData()->GetArray("bundle_id")->SetTuple1(0, -1);
  vtkNew<ErrorCatcher> catcher;
  EXPECT_FALSE(Write(model, kTmp + "/negative.h5", catcher));
  EXPECT_NE(catcher->Errors.find("bundle_id -1 is negative"), std::string::npos) << catcher->Errors;
  EXPECT_TRUE(Write(model, kTmp + "/negative.dat")); // .dat renumbers bundles: fine
}

TEST(FiberReaderWriter, H5KeepsThePeriodicCell)
{
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPeriodic(true);
  cube->SetEdgeLength(12.0);
  cube->SetVolumeFraction(0.3);
  cube->SetPopulations(2);
  cube->Update();
  const std::string path = kTmp + "/periodic.h5";
  ASSERT_TRUE(Write(cube->GetOutput(), path));
  auto back = Read(path);
  vtkDataArray* cell = back->GetFieldData()->GetArray("periodic_cell");
  ASSERT_NE(cell, nullptr);
  ASSERT_EQ(cell->GetNumberOfTuples(), 6);
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(cell->GetTuple1(i), i % 2 ? 6.0 : -6.0);
  ExpectSameFibers(cube->GetOutput(), back, 0.0, true, true);
  // A file without the cell reads without it; .dat has no place for it.
  ASSERT_TRUE(Write(Model(), kTmp + "/open.h5"));
  EXPECT_EQ(Read(kTmp + "/open.h5")->GetFieldData()->GetArray("periodic_cell"), nullptr);

  // A malformed periodic_cell on the input is an error naming it, nothing is written.
  vtkNew<vtkPolyData> bad;
  bad->DeepCopy(cube->GetOutput());
  vtkDataArray* field = bad->GetFieldData()->GetArray("periodic_cell");
  field->SetTuple1(1, -6.0); // xmax == xmin... below it
  vtkNew<ErrorCatcher> catcher;
  EXPECT_FALSE(Write(bad, kTmp + "/bad_cell.h5", catcher));
  EXPECT_NE(catcher->Errors.find("periodic_cell axis x"), std::string::npos) << catcher->Errors;
}
