// Fuzz test of the Core/IO readers (docs/architecture.md §6: "never a crash"): the sample files are
// mutated (bit flips, truncations, inserted garbage, huge numbers, chunk deletion/duplication)
// with a fixed seed and fed to every reader and sniffer. Built with ASan/UBSan over the IO
// sources directly; any sanitizer report aborts the run. Beyond "no crash", a successful read must
// satisfy the data contract (validateModel), which the readers promise.
#include "IO/CactusFormat.h"
#include "IO/CaterpillarFormat.h"
#include "IO/DatFormat.h"
#include "IO/TckFormat.h"
#include "IO/TrkFormat.h"
#include "IO/TsfFormat.h"
#include "Util/Random.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace fiberpli;

namespace
{

std::string slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t pick(RandomStream& rng, std::size_t n)
{
  return n == 0 ? 0 : static_cast<std::size_t>(rng.uniform() * static_cast<double>(n));
}

std::string mutate(std::string s, RandomStream& rng)
{
  static const char* textTokens[] = { "1e999", "nan", "-inf", "99999999999999999999999", "-0",
    "\n\n\n", "#", "\r", "0x1p3", "1e-400", "+", "-", ".", "\t", "  ", "\0" };
  static const std::uint32_t hugeInts[] = { 0x7fffffffu, 0xffffffffu, 0x80000000u, 0x7fc00000u,
    0x7f800000u, 0xff800000u, 0x00000001u, 0x7f7fffffu };
  const int edits = 1 + static_cast<int>(pick(rng, 4));
  for (int e = 0; e < edits; ++e)
  {
    switch (pick(rng, 7))
    {
      case 0: // bit flips
        for (int k = 0, n = 1 + static_cast<int>(pick(rng, 8)); k < n && !s.empty(); ++k)
        {
          s[pick(rng, s.size())] ^= static_cast<char>(1u << pick(rng, 8));
        }
        break;
      case 1: // truncation
        s.resize(pick(rng, s.size() + 1));
        break;
      case 2: // inserted garbage
      {
        std::string g(1 + pick(rng, 16), '\0');
        for (char& c : g)
        {
          c = static_cast<char>(rng.next() & 0xff);
        }
        s.insert(pick(rng, s.size() + 1), g);
        break;
      }
      case 3: // huge binary numbers at a 4-byte aligned or random position
      {
        if (s.size() < 4)
        {
          break;
        }
        std::size_t at = pick(rng, s.size() - 3);
        if (rng.uniform() < 0.5)
        {
          at &= ~std::size_t(3);
        }
        const std::uint32_t v = hugeInts[pick(rng, sizeof hugeInts / sizeof hugeInts[0])];
        for (int b = 0; b < 4; ++b)
        {
          s[at + static_cast<std::size_t>(b)] =
            static_cast<char>(v >> (8 * (rng.uniform() < 0.5 ? b : 3 - b)));
        }
        break;
      }
      case 4: // text tokens
      {
        const char* t = textTokens[pick(rng, sizeof textTokens / sizeof textTokens[0])];
        s.insert(
          pick(rng, s.size() + 1), std::string(t, t[0] ? std::char_traits<char>::length(t) : 1));
        break;
      }
      case 5: // delete a chunk
      {
        const std::size_t at = pick(rng, s.size() + 1);
        s.erase(at, pick(rng, 64));
        break;
      }
      default: // duplicate a chunk
      {
        const std::size_t at = pick(rng, s.size() + 1);
        const std::string chunk = s.substr(at, pick(rng, 256));
        s.insert(pick(rng, s.size() + 1), chunk);
        break;
      }
    }
  }
  return s;
}

int failures = 0;

void check(const FiberReadResult& r, const char* reader, int sample, int i)
{
  if (r.ok() && !validateModel(r.model).empty())
  {
    std::fprintf(stderr, "FAIL %s sample %d mutation %d: read ok but %s\n", reader, sample, i,
      validateModel(r.model).c_str());
    ++failures;
  }
  if (!r.ok() && (r.error.find("fuzz.in") == std::string::npos || !r.model.fibers.empty()))
  {
    std::fprintf(stderr,
      "FAIL %s sample %d mutation %d: error without file name or with data: %s\n", reader, sample,
      i, r.error.c_str());
    ++failures;
  }
}

/// readTsf's promises (TsfFormat.h): offsets for every streamline, only finite values, and on
/// failure an error naming the file and no data.
void checkTsf(const TsfReadResult& r, int sample, int i)
{
  bool good = r.values.size() == r.firstValueOffsets.size();
  for (const std::vector<double>& s : r.values)
  {
    for (double v : s)
    {
      good = good && std::isfinite(v);
    }
  }
  if (r.ok() && !good)
  {
    std::fprintf(stderr,
      "FAIL tsf sample %d mutation %d: read ok but offsets missing or a value not finite\n", sample,
      i);
    ++failures;
  }
  if (!r.ok() && (r.error.find("fuzz.in") == std::string::npos || !r.values.empty()))
  {
    std::fprintf(stderr,
      "FAIL tsf sample %d mutation %d: error without file name or with data: %s\n", sample, i,
      r.error.c_str());
    ++failures;
  }
}

} // namespace

int main()
{
  const std::string dir = FIBERPLI_TEST_DATA_DIR;
  std::vector<std::string> samples = { slurp(dir + "/fastpli/fastpli.dat"),
    slurp(dir + "/tracks/sample.tck"), slurp(dir + "/tracks/sample.trk"),
    slurp(dir + "/tracks/sample.radius.tsf") };
  samples.push_back(slurp(dir + "/fastpli/cube.dat").substr(0, 4000)); // a few fibers of the cube
  samples.push_back(slurp(dir + "/substrates/voxel.csv"));             // CATERPillar
  samples.push_back(slurp(dir + "/substrates/strands.txt"));           // CACTUS
  for (const std::string& s : samples)
  {
    if (s.empty())
    {
      std::fprintf(stderr, "FAIL: missing sample file under %s\n", dir.c_str());
      return 1;
    }
  }
  const int mutationsPerSample = 8000; // x 4 readers: a few thousand runs per reader
  const double budgetSeconds = 20.0;
  const auto start = std::chrono::steady_clock::now();
  int runs = 0;
  int accepted = 0;
  for (int sample = 0; sample < static_cast<int>(samples.size()); ++sample)
  {
    for (int i = 0; i < mutationsPerSample; ++i)
    {
      RandomStream rng(20240611, static_cast<std::uint64_t>(sample), static_cast<std::uint64_t>(i));
      const std::string input = mutate(samples[static_cast<std::size_t>(sample)], rng);
      {
        std::istringstream in(input);
        looksLikeFastPliDat(in);
        looksLikeTck(in);
        looksLikeTrk(in);
        const FiberReadResult r = readFastPliDat(in, "fuzz.in");
        check(r, "dat", sample, i);
        accepted += r.ok();
      }
      {
        std::istringstream in(input);
        const FiberReadResult r = readTck(in, "fuzz.in", 0.5);
        check(r, "tck", sample, i);
        accepted += r.ok();
      }
      {
        std::istringstream in(input);
        const FiberReadResult r = readTrk(in, "fuzz.in", 0.5);
        check(r, "trk", sample, i);
        accepted += r.ok();
      }
      {
        std::istringstream in(input);
        const TsfReadResult r = readTsf(in, "fuzz.in");
        checkTsf(r, sample, i);
        accepted += r.ok();
      }
      {
        std::istringstream in(input);
        looksLikeCaterpillarCsv(in);
        looksLikeCactusStrands(in);
        const FiberReadResult r = readCaterpillarCsv(in, "fuzz.in");
        check(r, "csv", sample, i);
        accepted += r.ok();
      }
      {
        std::istringstream in(input);
        // The size the file would have: counts are checked against it.
        const CactusReadResult r = readCactusStrands(in, "fuzz.in", input.size());
        check(r, "cactus", sample, i);
        accepted += r.ok();
      }
      runs += 6;
      if ((i & 63) == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
          budgetSeconds)
      {
        std::printf("time budget reached after sample %d mutation %d\n", sample, i);
        sample = static_cast<int>(samples.size());
        break;
      }
    }
  }
  std::printf("%d reader runs, %d accepted inputs, %d failures\n", runs, accepted, failures);
  return failures == 0 ? 0 : 1;
}
