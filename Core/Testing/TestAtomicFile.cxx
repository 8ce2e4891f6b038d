// Atomic replacement of files (AtomicFile.h, docs/api.md §4): a failed write never
// destroys the existing target and leaves no temporary file behind. Tests run as root, so failures
// are provoked with a missing directory, a directory as target, a failing content callback and a
// throwing one (chmod would not stop root).
#include "IO/AtomicFile.h"
#include "IO/FiberFile.h"

#include <gtest/gtest.h>

#include <dirent.h>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

using namespace fiberpli;

namespace
{

struct TempDir
{
  std::string path;
  TempDir()
  {
    char tmpl[] = "/tmp/fiberpli-atomic-XXXXXX";
    path = ::mkdtemp(tmpl);
  }
  ~TempDir()
  {
    for (const std::string& f : entries())
    {
      const std::string p = path + "/" + f;
      struct stat st;
      if (::stat(p.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
      {
        ::rmdir(p.c_str());
      }
      else
      {
        ::unlink(p.c_str());
      }
    }
    ::rmdir(path.c_str());
  }
  std::vector<std::string> entries() const
  {
    std::vector<std::string> names;
    if (DIR* d = ::opendir(path.c_str()))
    {
      while (dirent* e = ::readdir(d))
      {
        const std::string n = e->d_name;
        if (n != "." && n != "..")
        {
          names.push_back(n);
        }
      }
      ::closedir(d);
    }
    return names;
  }
};

std::string slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
}

} // namespace

TEST(AtomicFile, WritesNewAndReplacesExistingFile)
{
  TempDir dir;
  const std::string target = dir.path + "/a.txt";
  ASSERT_EQ(writeFileAtomically(target,
              [](std::ostream& out)
              {
                out << "first";
                return std::string();
              }),
    "");
  EXPECT_EQ(slurp(target), "first");
  ::chmod(target.c_str(), 0640);
  const std::string big(300000, 'x'); // larger than the stream buffer
  ASSERT_EQ(writeFileAtomically(target,
              [&](std::ostream& out)
              {
                out << big;
                return std::string();
              }),
    "");
  EXPECT_EQ(slurp(target), big);
  struct stat st;
  ASSERT_EQ(::stat(target.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u) << "a replaced file keeps its permissions";
  EXPECT_EQ(dir.entries().size(), 1u) << "no temporary file left";
}

TEST(AtomicFile, FailingContentKeepsTheOldFile)
{
  TempDir dir;
  const std::string target = dir.path + "/keep.dat";
  spit(target, "old content");
  const std::string err = writeFileAtomically(target,
    [](std::ostream& out)
    {
      out << "half of the new content";
      return std::string("fiber 3 is broken");
    });
  EXPECT_EQ(err, "fiber 3 is broken");
  EXPECT_EQ(slurp(target), "old content");
  EXPECT_EQ(dir.entries().size(), 1u);

  const std::string thrown = writeFileAtomically(target,
    [](std::ostream& out) -> std::string
    {
      out << "partial";
      throw std::runtime_error("out of memory");
    });
  EXPECT_NE(thrown.find(target), std::string::npos) << thrown;
  EXPECT_NE(thrown.find("out of memory"), std::string::npos) << thrown;
  EXPECT_EQ(slurp(target), "old content");
  EXPECT_EQ(dir.entries().size(), 1u);
}

TEST(AtomicFile, UnwritableTargetsAreErrorsNamingThePath)
{
  TempDir dir;
  const std::string missing = dir.path + "/no/such/dir/x.dat";
  std::string err = writeFileAtomically(missing,
    [](std::ostream& out)
    {
      out << "x";
      return std::string();
    });
  EXPECT_NE(err.find(missing), std::string::npos) << err;
  EXPECT_NE(err.find("No such file or directory"), std::string::npos) << err;

  const std::string sub = dir.path + "/sub";
  ASSERT_EQ(::mkdir(sub.c_str(), 0755), 0);
  err = writeFileAtomically(sub,
    [](std::ostream& out)
    {
      out << "x";
      return std::string();
    });
  EXPECT_NE(err.find(sub), std::string::npos) << err;
  EXPECT_NE(err.find("directory"), std::string::npos) << err;
  struct stat st;
  ASSERT_EQ(::stat(sub.c_str(), &st), 0);
  EXPECT_TRUE(S_ISDIR(st.st_mode));
  EXPECT_EQ(dir.entries().size(), 1u);

  EXPECT_NE(writeFileAtomically("", [](std::ostream&) { return std::string(); }), "");
}

TEST(AtomicFile, FiberWriterKeepsOldFileOnInvalidModel)
{
  TempDir dir;
  const std::string target = dir.path + "/model.dat";
  FiberModel good;
  Fiber f;
  f.points = { { 0, 0, 0 }, { 1, 0, 0 } };
  f.radii = { 1, 1 };
  good.fibers = { f };
  ASSERT_EQ(writeFiberFile(target, good), "");
  const std::string before = slurp(target);
  EXPECT_EQ(before, "0 0 0 1\n1 0 0 1\n\n");

  FiberModel bad = good;
  bad.fibers[0].radii[1] = -1.0;
  const std::string err = writeFiberFile(target, bad);
  EXPECT_NE(err.find(target), std::string::npos) << err;
  EXPECT_NE(err.find("radius"), std::string::npos) << err;
  EXPECT_EQ(slurp(target), before);
  EXPECT_EQ(dir.entries().size(), 1u);

  const FiberReadResult back = readFiberFile(target, 1.0);
  ASSERT_TRUE(back.ok()) << back.error;
  EXPECT_EQ(back.model.fibers.size(), 1u);
  EXPECT_TRUE(canReadFiberFile(target));
  EXPECT_NE(writeFiberFile(dir.path + "/model.trk", good).find("cannot write this extension"),
    std::string::npos);
  EXPECT_NE(readFiberFile(dir.path + "/nothing.dat", 1.0).error.find(dir.path + "/nothing.dat"),
    std::string::npos);
}

TEST(AtomicFile, FailedRenameRemovesTheTemporaryFile)
{
  // The target turns into a non-empty directory while the content is written, so rename(2) fails
  // after the temporary file is complete: the error names the path and no temporary file remains.
  TempDir dir;
  const std::string target = dir.path + "/late.dat";
  const std::string err = writeFileAtomically(target,
    [&](std::ostream& out)
    {
      out << "content";
      ::mkdir(target.c_str(), 0755);
      std::ofstream(target + "/inside") << "x";
      return std::string();
    });
  EXPECT_NE(err.find("cannot replace " + target), std::string::npos) << err;
  EXPECT_EQ(dir.entries().size(), 1u) << "temporary file left behind";
  ::unlink((target + "/inside").c_str());
}

TEST(AtomicFile, TemporaryNameIsUnpredictable)
{
  // <target>.tmp-<pid>-<n> could be guessed and a symlink planted there; the name is now random
  // and differs from one write to the next.
  TempDir dir;
  const std::string target = dir.path + "/out.dat";
  std::vector<std::string> temporaries;
  for (int k = 0; k < 2; ++k)
  {
    ASSERT_EQ(writeFileAtomically(target,
                [&](std::ostream& out)
                {
                  for (const std::string& name : dir.entries())
                  {
                    if (name.rfind("out.dat.tmp-", 0) == 0)
                    {
                      temporaries.push_back(name);
                    }
                  }
                  out << "x";
                  return std::string();
                }),
      "");
  }
  ASSERT_EQ(temporaries.size(), 2u);
  EXPECT_NE(temporaries[0], temporaries[1]);
  for (const std::string& name : temporaries)
  {
    const std::string suffix = name.substr(std::string("out.dat.tmp-").size());
    EXPECT_EQ(suffix.size(), 16u) << name;
    EXPECT_EQ(suffix.find_first_not_of("0123456789abcdef"), std::string::npos) << name;
  }
  EXPECT_EQ(dir.entries().size(), 1u);
}

TEST(AtomicFile, FilePairFailingSecondWriteKeepsBothOldFiles)
{
  // The second file cannot be written (its content fails half-way, as on a full disk): neither
  // old file may change, and no temporary or backup file may remain.
  TempDir dir;
  const std::string a = dir.path + "/pair.tck";
  const std::string b = dir.path + "/pair.radius.tsf";
  spit(a, "old a");
  spit(b, "old b");
  const std::string err = writeFilesAtomically({
    AtomicPart{ a,
      [](std::ostream& out)
      {
        out << "new a";
        return std::string();
      } },
    AtomicPart{ b,
      [](std::ostream& out)
      {
        out << "half of new b";
        return std::string("No space left on device");
      } },
  });
  EXPECT_EQ(err, "No space left on device");
  EXPECT_EQ(slurp(a), "old a");
  EXPECT_EQ(slurp(b), "old b");
  EXPECT_EQ(dir.entries().size(), 2u);

  ASSERT_EQ(writeFilesAtomically({
              AtomicPart{ a,
                [](std::ostream& out)
                {
                  out << "new a";
                  return std::string();
                } },
              AtomicPart{ b,
                [](std::ostream& out)
                {
                  out << "new b";
                  return std::string();
                } },
            }),
    "");
  EXPECT_EQ(slurp(a), "new a");
  EXPECT_EQ(slurp(b), "new b");
  EXPECT_EQ(dir.entries().size(), 2u);
}

TEST(AtomicFile, FilePairFailedSecondRenamePutsTheFirstBack)
{
  // Both contents are complete, the first file is renamed into place, then the second rename
  // fails (its target became a non-empty directory): the first target gets its old content back.
  TempDir dir;
  const std::string a = dir.path + "/first.dat";
  const std::string b = dir.path + "/second.dat";
  spit(a, "old first");
  const std::string err = writeFilesAtomically({
    AtomicPart{ a,
      [](std::ostream& out)
      {
        out << "new first";
        return std::string();
      } },
    AtomicPart{ b,
      [&](std::ostream& out)
      {
        out << "new second";
        ::mkdir(b.c_str(), 0755);
        std::ofstream(b + "/inside") << "x";
        return std::string();
      } },
  });
  EXPECT_NE(err.find("cannot replace " + b), std::string::npos) << err;
  EXPECT_EQ(slurp(a), "old first");
  EXPECT_EQ(dir.entries().size(), 2u) << "temporary or backup file left behind";
  ::unlink((b + "/inside").c_str());
}

TEST(AtomicFile, TckAndRadiusFileAreReplacedAsAPair)
{
  // A .tck and its .radius.tsf: when the .tsf cannot be written, the old .tck must stay (it used
  // to be replaced first, leaving a .tck whose radius file no longer matched: the pair did not
  // read). The failure is provoked with a directory in the .tsf's place.
  TempDir dir;
  const std::string tck = dir.path + "/model.tck";
  FiberModel oldModel;
  Fiber f;
  f.points = { { 0, 0, 0 }, { 1, 0, 0 } };
  f.radii = { 1, 1 };
  oldModel.fibers = { f };
  ASSERT_EQ(writeFiberFile(tck, oldModel), "");
  const std::string oldTck = slurp(tck);
  const std::string oldTsf = slurp(tckRadiusPath(tck));

  FiberModel newModel = oldModel;
  newModel.fibers.push_back(f);
  newModel.fibers[1].radii = { 2, 2 };
  ASSERT_EQ(::unlink(tckRadiusPath(tck).c_str()), 0);
  ASSERT_EQ(::mkdir(tckRadiusPath(tck).c_str(), 0755), 0);
  const std::string err = writeFiberFile(tck, newModel);
  EXPECT_NE(err.find(tckRadiusPath(tck)), std::string::npos) << err;
  EXPECT_EQ(slurp(tck), oldTck) << "the .tck was replaced although its radius file was not";
  EXPECT_EQ(dir.entries().size(), 2u) << "temporary file left behind";
  ASSERT_EQ(::rmdir(tckRadiusPath(tck).c_str()), 0);

  // Written together, the new pair reads back with its own radii.
  spit(tckRadiusPath(tck), oldTsf);
  ASSERT_EQ(writeFiberFile(tck, newModel), "");
  const FiberReadResult back = readFiberFile(tck, 1.0);
  ASSERT_TRUE(back.ok()) << back.error;
  ASSERT_EQ(back.model.fibers.size(), 2u);
  EXPECT_EQ(back.model.fibers[1].radii[0], 2.0);
}

TEST(AtomicFile, ReadersRefuseAFifoWithoutBlocking)
{
  // Opening a FIFO for reading blocks until a writer comes: FileName on one used to hang.
  TempDir dir;
  for (const std::string name : { "pipe.dat", "pipe.tck", "pipe.trk" })
  {
    const std::string fifo = dir.path + "/" + name;
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_FALSE(canReadFiberFile(fifo));
    const FiberReadResult r = readFiberFile(fifo, 1.0); // blocks forever without the check
    EXPECT_NE(r.error.find(fifo + " is a FIFO (named pipe), not a regular file"), std::string::npos)
      << r.error;
  }
  // A .tck whose radius file is a FIFO.
  const std::string tck = dir.path + "/model.tck";
  FiberModel m;
  Fiber f;
  f.points = { { 0, 0, 0 }, { 1, 0, 0 } };
  f.radii = { 1, 1 };
  m.fibers = { f };
  ASSERT_EQ(writeFiberFile(tck, m), "");
  ASSERT_EQ(::unlink(tckRadiusPath(tck).c_str()), 0);
  ASSERT_EQ(::mkfifo(tckRadiusPath(tck).c_str(), 0600), 0);
  const FiberReadResult r = readFiberFile(tck, 1.0);
  EXPECT_NE(r.error.find("FIFO"), std::string::npos) << r.error;
}
