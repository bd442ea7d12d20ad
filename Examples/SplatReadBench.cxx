// SPDX-License-Identifier: BSD-3-Clause
// splat_read_bench: reading time and peak memory of vtkGaussianSplatReader per capture format.
//
//   splat_read_bench --write FILE.ply [--count N] [--degree D]
//       writes the bench's synthetic capture (the torus of splat_bench's 3dgs scene) with
//       vtkGaussianSplatWriter, to be converted into the other formats (splat-transform, ...);
//   splat_read_bench [--rounds R] FILE...
//       reads each file R times (default 3), each read in a child process of its own, and prints
//       a CSV row per file: format (the extension), Gaussians, file bytes per Gaussian, the
//       median read time, Gaussians read per second, the peak resident memory the read added
//       per Gaussian, and the time against the first file's (the .ply, as a ratio).
#include "SplatCaptureScene.h"

#include "vtkGaussianSplatReader.h"
#include "vtkGaussianSplatWriter.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <vtksys/Directory.hxx>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
struct Read
{
  double Seconds = 0.0;
  long long Gaussians = 0;
  long PeakKiB = 0;
};

// Reads `path` in a child process: its time, count and peak resident set.
Read ReadInChild(const std::string& path)
{
  int fds[2];
  if (pipe(fds) != 0)
  {
    return {};
  }
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0)
  {
    close(fds[0]);
    Read r;
    if (!path.empty()) // an empty path measures the child's own start
    {
      const auto start = std::chrono::steady_clock::now();
      vtkNew<vtkGaussianSplatReader> reader;
      reader->SetFileName(path.c_str());
      reader->Update();
      r.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      r.Gaussians = reader->GetOutput()->GetNumberOfPoints();
    }
    ssize_t written = write(fds[1], &r, sizeof(r));
    (void)written;
    _exit(0);
  }
  close(fds[1]);
  Read r;
  if (read(fds[0], &r, sizeof(r)) != static_cast<ssize_t>(sizeof(r)))
  {
    r = {};
  }
  close(fds[0]);
  int status = 0;
  struct rusage usage;
  wait4(pid, &status, 0, &usage);
  r.PeakKiB = usage.ru_maxrss;
  return r;
}

std::string Format(const std::string& path)
{
  const std::string name = vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameName(path));
  const std::size_t dot = name.find('.');
  return dot == std::string::npos ? name : name.substr(dot + 1);
}

// The file's size; for a SOG's meta.json, the size of its whole folder.
unsigned long FileBytes(const std::string& path)
{
  if (Format(path) != "json")
  {
    return vtksys::SystemTools::FileLength(path);
  }
  vtksys::Directory folder;
  const std::string dir = vtksys::SystemTools::GetFilenamePath(path);
  folder.Load(dir.empty() ? "." : dir);
  unsigned long total = 0;
  for (unsigned long i = 0; i < folder.GetNumberOfFiles(); ++i)
  {
    const std::string name = (dir.empty() ? "." : dir) + "/" + folder.GetFile(i);
    total += vtksys::SystemTools::FileIsDirectory(name) ? 0 : vtksys::SystemTools::FileLength(name);
  }
  return total;
}

}

int main(int argc, char* argv[])
{
  std::vector<std::string> files;
  std::string write;
  long long count = 1000000;
  int degree = 3, rounds = 3;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool value = i + 1 < argc;
    if (arg == "--write" && value)
    {
      write = argv[++i];
    }
    else if (arg == "--count" && value)
    {
      count = std::atoll(argv[++i]);
    }
    else if (arg == "--degree" && value)
    {
      degree = std::atoi(argv[++i]);
    }
    else if (arg == "--rounds" && value)
    {
      rounds = std::max(1, std::atoi(argv[++i]));
    }
    else if (arg == "--help" || arg == "-h")
    {
      std::printf("usage: splat_read_bench --write FILE.ply [--count N] [--degree D]\n"
                  "       splat_read_bench [--rounds R] FILE...\n");
      return 0;
    }
    else
    {
      files.push_back(arg);
    }
  }
  if (!write.empty())
  {
    vtkNew<vtkGaussianSplatWriter> writer;
    writer->SetInputData(splatexample::SyntheticCapture(count, degree));
    writer->SetFileName(write.c_str());
    return writer->Write() ? 0 : 1;
  }
  // The resident set of a child that reads nothing: what every child starts with.
  const long baseline = ReadInChild("").PeakKiB;
  std::printf("format,gaussians,file_bytes_per_gaussian,read_ms,gaussians_per_s,"
              "peak_bytes_per_gaussian,time_vs_first,threads\n");
  double first = 0.0;
  for (const std::string& file : files)
  {
    std::vector<double> times;
    Read r;
    long peak = 0;
    for (int k = 0; k < rounds; ++k)
    {
      r = ReadInChild(file);
      times.push_back(r.Seconds);
      peak = std::max(peak, r.PeakKiB);
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    first = first > 0.0 ? first : median;
    const double n = static_cast<double>(std::max(r.Gaussians, 1LL));
    const double bytes = static_cast<double>(FileBytes(file)) / n;
    std::printf("%s,%lld,%.1f,%.1f,%.3g,%.1f,%.2f,%d\n", Format(file).c_str(), r.Gaussians, bytes,
      1e3 * median, r.Gaussians / std::max(median, 1e-9), 1024.0 * (peak - baseline) / n,
      median / first, vtkSMPTools::GetEstimatedNumberOfThreads());
  }
  return 0;
}
