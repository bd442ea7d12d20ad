// SPDX-License-Identifier: BSD-3-Clause
// Fuzzing helpers for the reader tests: variants of a file (truncations, mutated header fields),
// each read in a child process so that a crash, a hang or an absurd allocation is seen and
// counted instead of ending the test, and a table of the outcomes per format.
#ifndef SplatFuzzTestUtilities_h
#define SplatFuzzTestUtilities_h

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStringOutputWindow.h"

#include <algorithm>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <map>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace splatfuzz
{
using Bytes = std::string;

inline Bytes ReadFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void WriteFile(const std::string& path, const Bytes& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

/// One variant of a file: its bytes, what was done to it, and whether it is a truncation (a
/// truncated file read successfully must give the whole original data, or with `prefixOk` a
/// prefix of its points: a line format cut at a line end).
struct Variant
{
  std::string what;
  Bytes bytes;
  bool truncated = false;
};

/// Truncations at 0 bytes, at every byte of [0, headerEnd) up to `everyByte` bytes, every 7th
/// byte of the rest of the header, `bodyCuts` offsets spread through the body, and size - 1.
inline std::vector<Variant> Truncations(
  const Bytes& file, std::size_t headerEnd, std::size_t everyByte = 512, int bodyCuts = 40)
{
  headerEnd = std::min(headerEnd, file.size());
  std::vector<std::size_t> cuts;
  for (std::size_t i = 0; i < headerEnd; i += (i < everyByte ? 1 : 7))
  {
    cuts.push_back(i);
  }
  const std::size_t body = file.size() - headerEnd;
  for (int k = 0; k < bodyCuts && body > 0; ++k)
  {
    cuts.push_back(headerEnd + body * k / bodyCuts);
  }
  cuts.push_back(file.size() - 1);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<Variant> variants;
  for (std::size_t cut : cuts)
  {
    if (cut < file.size())
    {
      variants.push_back({ "truncated at " + std::to_string(cut), file.substr(0, cut), true });
    }
  }
  return variants;
}

/// Replacements tried for a number in a header: zero, negative, off by one, huge, not a number.
inline std::vector<std::string> NumberReplacements(const std::string& number)
{
  std::vector<std::string> values = { "0", "-1", "-2147483649", "2147483647", "4294967296",
    "1000000000000", "99999999999999999999", "1e308", "nan", "x" };
  char* end = nullptr;
  const long long n = std::strtoll(number.c_str(), &end, 10);
  if (*end == '\0')
  {
    values.push_back(std::to_string(n + 1));
    values.push_back(std::to_string(n - 1));
    values.push_back(std::to_string(n * 1000));
  }
  return values;
}

inline bool IsTokenCharacter(char c)
{
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-' ||
    c == '+';
}

/// Variants of a text header: every token in [begin, end) for which `select(file, position)`
/// holds is replaced in turn, numbers by NumberReplacements and words by `words` (type names
/// and keywords of the format) plus garbage and the empty string.
inline std::vector<Variant> TokenMutations(const Bytes& file, std::size_t begin, std::size_t end,
  const std::vector<std::string>& words,
  const std::function<bool(const Bytes&, std::size_t)>& select = nullptr)
{
  std::vector<Variant> variants;
  end = std::min(end, file.size());
  for (std::size_t i = begin; i < end;)
  {
    if (!IsTokenCharacter(file[i]))
    {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < end && IsTokenCharacter(file[j]))
    {
      ++j;
    }
    const std::string token = file.substr(i, j - i);
    if (!select || select(file, i))
    {
      char* numberEnd = nullptr;
      std::strtod(token.c_str(), &numberEnd);
      std::vector<std::string> replacements;
      if (*numberEnd == '\0')
      {
        replacements = NumberReplacements(token);
      }
      else
      {
        replacements = words;
        replacements.push_back("garbage");
        replacements.push_back("");
      }
      for (const auto& replacement : replacements)
      {
        if (replacement != token)
        {
          variants.push_back({ "'" + token + "' at " + std::to_string(i) + " -> '" + replacement +
              "'",
            file.substr(0, i) + replacement + file.substr(j) });
        }
      }
    }
    i = j;
  }
  return variants;
}

/// Variants with the `width`-byte little- or big-endian integer at `offset` set to each value.
inline std::vector<Variant> FieldMutations(const Bytes& file, const std::string& name,
  std::size_t offset, int width, const std::vector<long long>& values, bool bigEndian = false)
{
  std::vector<Variant> variants;
  if (offset + width > file.size())
  {
    return variants;
  }
  for (long long value : values)
  {
    Bytes bytes = file;
    for (int b = 0; b < width; ++b)
    {
      const int shift = 8 * (bigEndian ? width - 1 - b : b);
      bytes[offset + b] = static_cast<char>((static_cast<unsigned long long>(value) >> shift) & 255);
    }
    variants.push_back({ name + " = " + std::to_string(value), bytes });
  }
  return variants;
}

/// Values tried for an integer field that holds `n`: zero, negative, off by one, huge.
inline std::vector<long long> IntegerValues(long long n)
{
  return { 0, -1, n - 1, n + 1, n * 1000, 0x7fff, 0x7fffffff, 0xffffffffLL, 1LL << 40,
    0x7fffffffffffffffLL };
}

// Whether every point-data array has one tuple per point and every cell's point ids are in
// range: what the mappers rely on in a dataset a reader hands over.
inline bool Consistent(vtkDataObject* data, std::string& why)
{
  auto* image = vtkImageData::SafeDownCast(data);
  auto* poly = vtkPolyData::SafeDownCast(data);
  auto* points = image ? static_cast<vtkDataSet*>(image) : poly;
  if (!points)
  {
    why = "no image data or polydata";
    return false;
  }
  const vtkIdType n = points->GetNumberOfPoints();
  vtkPointData* pd = points->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    if (array && array->GetNumberOfTuples() != n)
    {
      why = "array '" + std::string(array->GetName() ? array->GetName() : "") + "' has " +
        std::to_string(array->GetNumberOfTuples()) + " tuples for " + std::to_string(n) +
        " points";
      return false;
    }
  }
  if (image && !image->GetPointData()->GetScalars())
  {
    why = "image without point scalars";
    return false;
  }
  if (poly)
  {
    for (vtkCellArray* cells : { poly->GetVerts(), poly->GetLines(), poly->GetPolys(),
           poly->GetStrips() })
    {
      if (!cells)
      {
        continue;
      }
      vtkDataArray* ids = cells->GetConnectivityArray();
      for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
      {
        const double id = ids->GetTuple1(i);
        if (id < 0 || id >= n)
        {
          why = "cell point id " + std::to_string(id) + " out of range";
          return false;
        }
      }
    }
  }
  return true;
}

/// Whether `a` holds the same values as the first tuples of `b` (NaN equal to NaN).
inline bool SameValues(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetNumberOfComponents() != b->GetNumberOfComponents() ||
    a->GetNumberOfTuples() > b->GetNumberOfTuples())
  {
    return a == b;
  }
  const vtkIdType n = a->GetNumberOfTuples() * a->GetNumberOfComponents();
  const int c = a->GetNumberOfComponents();
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double x = a->GetComponent(i / c, i % c), y = b->GetComponent(i / c, i % c);
    if (x != y && !(vtkMath::IsNan(x) && vtkMath::IsNan(y)))
    {
      return false;
    }
  }
  return true;
}

/// Whether `data` holds all of `reference`'s points and point scalars (or with `prefixOk` the
/// first of them): the file's own data, not a half-built output.
inline bool Intact(vtkDataObject* data, vtkDataObject* reference, bool prefixOk)
{
  auto* ds = vtkDataSet::SafeDownCast(data);
  auto* ref = vtkDataSet::SafeDownCast(reference);
  if (!ds || !ref || ds->GetNumberOfPoints() > ref->GetNumberOfPoints() ||
    (!prefixOk && ds->GetNumberOfPoints() != ref->GetNumberOfPoints()))
  {
    return false;
  }
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    auto* refPoly = vtkPolyData::SafeDownCast(reference);
    if (!refPoly || !SameValues(poly->GetPoints()->GetData(), refPoly->GetPoints()->GetData()) ||
      (!prefixOk && poly->GetNumberOfCells() != refPoly->GetNumberOfCells()))
    {
      return false;
    }
  }
  auto* image = vtkImageData::SafeDownCast(data);
  auto* refImage = vtkImageData::SafeDownCast(reference);
  if (image && (!refImage || !std::equal(image->GetDimensions(), image->GetDimensions() + 3,
                               refImage->GetDimensions())))
  {
    return false;
  }
  vtkDataArray* scalars = ds->GetPointData()->GetScalars();
  vtkDataArray* refScalars = ref->GetPointData()->GetScalars();
  return !refScalars || SameValues(scalars, refScalars);
}

/// How one read of one variant ended.
enum Outcome
{
  ReadOk = 0,       // a consistent dataset (for a truncation: the original data)
  CleanError,       // a std::runtime_error naming the file
  UnclearError,     // an exception that does not name the file
  HalfBuilt,        // a dataset that is inconsistent, or a truncation read as if whole
  AbsurdAllocation, // std::bad_alloc, VTK's "Unable to allocate", or 1 GiB more resident
  Crash,            // a signal other than the watchdogs'
  Hang,             // the CPU-time or wall-clock watchdog
  NumberOfOutcomes
};

inline const char* OutcomeName(int outcome)
{
  static const char* names[] = { "read", "error", "UNCLEAR ERROR", "HALF-BUILT OUTPUT",
    "ABSURD ALLOCATION", "CRASH", "HANG" };
  return names[outcome];
}

/// Reads `path`, returning the dataset or throwing (the entry point splat_render uses).
using Reader = std::function<vtkSmartPointer<vtkDataObject>(const std::string& path)>;

// A read that spins is stopped by its CPU time, which a loaded machine does not inflate; one
// that blocks, by the wall clock.
constexpr unsigned WatchdogCPUSeconds = 10;
constexpr unsigned WatchdogSeconds = 60;
constexpr long MaxResidentKiB = 1L << 20; // 1 GiB

/// The resident set of this process now, in KiB (a child starts with its parent's).
inline long ResidentKiB()
{
  long pages = 0, resident = 0;
  std::ifstream statm("/proc/self/statm");
  statm >> pages >> resident;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

/// Reads `path` in a child process with a watchdog; the child checks the result against
/// `reference` and reports through its exit status. VTK's messages go to a string window in the
/// child and are printed, with the exception's message, only when the outcome is a failure.
inline Outcome ReadInChild(const Reader& reader, const std::string& path,
  vtkDataObject* reference, bool truncated, bool prefixOk, std::string& detail)
{
  int pipeFds[2];
  if (pipe(pipeFds) != 0)
  {
    throw std::runtime_error("pipe failed");
  }
  std::fflush(nullptr);
  const long inherited = ResidentKiB();
  const pid_t pid = fork();
  if (pid == 0)
  {
    close(pipeFds[0]);
    const rlimit cpu{ WatchdogCPUSeconds, WatchdogCPUSeconds + 5 };
    setrlimit(RLIMIT_CPU, &cpu);
    alarm(WatchdogSeconds);
    // A fork copies only the calling thread: TBB's workers stay behind, and a child whose
    // reader runs vtkSMPTools on TBB can wait for them forever (CI's Debian 13 leg: VTK 9.3's
    // XML reader on the unchanged .vtp, stopped by the wall-clock alarm with no CPU used).
    vtkSMPTools::SetBackend("Sequential");
    vtkNew<vtkStringOutputWindow> messages;
    vtkOutputWindow::SetInstance(messages);
    Outcome outcome;
    std::string why;
    try
    {
      vtkSmartPointer<vtkDataObject> data = reader(path);
      if (!Consistent(data, why))
      {
        outcome = HalfBuilt;
      }
      else if (truncated && !Intact(data, reference, prefixOk))
      {
        why = "a truncated file read without an error";
        outcome = HalfBuilt;
      }
      else
      {
        outcome = ReadOk;
      }
    }
    catch (const std::bad_alloc&)
    {
      why = "std::bad_alloc";
      outcome = AbsurdAllocation;
    }
    catch (const std::exception& e)
    {
      why = e.what();
      const std::string name = path.substr(path.find_last_of('/') + 1);
      outcome = why.find(name) != std::string::npos ? CleanError : UnclearError;
    }
    const std::string vtkText = messages->GetOutput();
    if (vtkText.find("nable to allocate") != std::string::npos)
    {
      outcome = AbsurdAllocation;
    }
    const std::string report = why + "\n" + vtkText;
    ssize_t written = write(pipeFds[1], report.data(), std::min<std::size_t>(report.size(), 4000));
    (void)written;
    _exit(outcome);
  }
  close(pipeFds[1]);
  std::string report;
  char buffer[4096];
  for (ssize_t n; (n = read(pipeFds[0], buffer, sizeof(buffer))) > 0;)
  {
    report.append(buffer, n);
  }
  close(pipeFds[0]);
  int status = 0;
  struct rusage usage;
  wait4(pid, &status, 0, &usage);
  detail = report;
  if (WIFSIGNALED(status))
  {
    detail = std::string("signal ") + strsignal(WTERMSIG(status)) + "\n" + report;
    const int signal = WTERMSIG(status);
    return signal == SIGALRM || signal == SIGXCPU ? Hang : Crash;
  }
  if (usage.ru_maxrss - inherited > MaxResidentKiB)
  {
    detail = "resident set " + std::to_string(usage.ru_maxrss / 1024) + " MiB, " +
      std::to_string(inherited / 1024) + " MiB of it inherited\n" + report;
    return AbsurdAllocation;
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : Crash;
  return code < NumberOfOutcomes ? static_cast<Outcome>(code) : Crash;
}

/// The fuzz tests' "-read FILE" mode, for a debugger or a sanitizer: reads `path` in this
/// process and prints its point count or the error.
inline int ReadOne(const Reader& reader, const std::string& path)
{
  try
  {
    vtkSmartPointer<vtkDataObject> data = reader(path);
    std::cout << path << ": " << vtkDataSet::SafeDownCast(data)->GetNumberOfPoints()
              << " points\n";
    return EXIT_SUCCESS;
  }
  catch (const std::exception& e)
  {
    std::cout << e.what() << "\n";
    return EXIT_FAILURE;
  }
}

/// Outcome counts per format, and the failures with what caused them.
class Tally
{
public:
  /// The filters from the command line: -only FORMAT_PART, -stride N (default `stride`).
  Tally(int argc, char* argv[], int stride)
  {
    for (int i = 1; i + 1 < argc; ++i)
    {
      if (std::strcmp(argv[i], "-only") == 0)
      {
        this->Only = argv[i + 1];
      }
      else if (std::strcmp(argv[i], "-stride") == 0)
      {
        stride = std::atoi(argv[i + 1]);
      }
    }
    this->Stride = std::max(stride, 1);
  }

  /// Writes each (Stride-th) variant to `path`, reads it in a child process and counts the
  /// outcome; returns the number of failures (outcomes after CleanError).
  /// `readPath`, when given, is the file read instead (a .mhd whose .raw `path` is).
  int Run(const std::string& format, const Reader& reader, const std::string& path,
    const std::vector<Variant>& variants, vtkDataObject* reference, bool prefixOk = false,
    const std::string& readPath = std::string())
  {
    int failures = 0;
    if (format.find(this->Only) == std::string::npos)
    {
      return 0;
    }
    auto& counts = this->Counts[format];
    counts.resize(NumberOfOutcomes);
    for (const auto& variant : variants)
    {
      if (this->Seen++ % this->Stride != 0)
      {
        continue;
      }
      WriteFile(path, variant.bytes);
      std::string detail;
      const Outcome outcome =
        ReadInChild(reader, readPath.empty() ? path : readPath, reference,
          variant.truncated, prefixOk, detail);
      ++counts[outcome];
      if (outcome > CleanError)
      {
        ++failures;
        std::cerr << format << " (" << variant.what << "): " << OutcomeName(outcome) << ": "
                  << detail.substr(0, 600) << "\n";
      }
    }
    return failures;
  }

  /// Reads `path` as it is (no variant); it must read and match `reference`.
  bool ReadsIntact(const std::string& format, const Reader& reader, const std::string& path,
    vtkDataObject* reference)
  {
    std::string detail;
    if (format.find(this->Only) == std::string::npos)
    {
      return true;
    }
    const Outcome outcome = ReadInChild(reader, path, reference, true, false, detail);
    if (outcome != ReadOk)
    {
      std::cerr << format << ": the unchanged file '" << path << "' gave "
                << OutcomeName(outcome) << ": " << detail << "\n";
    }
    return outcome == ReadOk;
  }

  /// Prints the table and the number of failures; returns the test's exit status.
  int Report(std::ostream& os, int failures) const
  {
    this->Print(os);
    os << failures << " failures\n";
    return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
  }

  void Print(std::ostream& os) const
  {
    if (this->Stride > 1)
    {
      os << "every " << this->Stride << "th variant read (-stride 1 reads all of them)\n";
    }
    os << "format                     variants   errors    reads  failures\n";
    for (const auto& [format, counts] : this->Counts)
    {
      int total = 0, failures = 0;
      for (int o = 0; o < NumberOfOutcomes; ++o)
      {
        total += counts[o];
        failures += o > CleanError ? counts[o] : 0;
      }
      char row[160];
      std::snprintf(row, sizeof(row), "%-26s %8d %8d %8d %9d\n", format.c_str(), total,
        counts[CleanError], counts[ReadOk], failures);
      os << row;
    }
  }

private:
  // Only the formats whose name contains `Only` run (a filter for debugging); every
  // `Stride`th variant is read, counted across formats so that each format's list starts at
  // a different phase.
  std::string Only;
  int Stride = 1;
  long long Seen = 0;
  std::map<std::string, std::vector<int>> Counts;
};
}

#endif
