// SPDX-License-Identifier: BSD-3-Clause
// splat_bench: a benchmark, not a test. Renders the same points with vtkSurfaceSplatMapper (on
// each backend) and with its peer vtkPointGaussianMapper, in the same run, and prints one CSV row
// per case: milliseconds per frame (median), splats per second, the process's peak memory so
// far, what our mapper culled and skipped, and the memory per splat that the case added.
// Run `splat_bench --help` for the options.
#include "SplatCommandLine.h"
#include "SplatExampleUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"
#include "vtkSurfelSphereSource.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSmartPointer.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/resource.h> // getrusage
#include <unistd.h>       // sysconf

#ifdef __GLIBC__
#include <malloc.h> // malloc_trim
#endif

namespace
{
using splatexample::ParseCount;
using splatexample::SplitList;
using splatexample::UsageError;

const char* const Usage = R"(Usage: splat_bench [OPTIONS]

Renders points on a unit sphere (Fibonacci sampling, radial normals, radius = sampling spacing)
and the Stanford bunny (vertices through vtkSurfelGenerator) with vtkSurfaceSplatMapper and with
vtkPointGaussianMapper (opaque disks of the same radius, emissive off), offscreen, and
prints CSV rows:
  scene,mapper,backend,setting,points,width,height,ms_per_frame,splats_per_s,peak_rss_mb,
  rendered,frustum_culled,backface_culled,negligible,skipped,bytes_per_splat
Settings: vtkSurfaceSplatMapper runs on each backend (the CPU rasterizer, then OpenGL) as
"default" (exact EWA) on every scene and, on the sphere (closed, outward normals), also as
"backface" (the actor's BackfaceCulling on); its OpenGL backend also as "approximate" (the
APPROXIMATE filter mode); vtkPointGaussianMapper runs as "disk". Under a software OpenGL
renderer (Mesa's llvmpipe) the OpenGL rows measure that renderer, not a GPU.
ms_per_frame is the median over the timed frames after one warm-up frame; peak_rss_mb is the
peak resident memory of the whole process so far (cases run from small to large).
rendered .. skipped are vtkSurfaceSplatMapper's counts for the last frame (splats drawn, culled
outside the frustum, culled as back faces, left out as negligible, input points skipped as
invalid); the OpenGL backend culls in its vertex shader without counting, so its splat counts
are -1; empty for vtkPointGaussianMapper, which does not report them.
bytes_per_splat is the resident memory the case added (its data, mapper and frames) per point:
the current resident set size (/proc/self/statm) after the case's frames minus the one before
its data was built, divided by the number of points. A one-line summary per case goes to stderr.

Options (a value follows as --name VALUE or --name=VALUE; lists are comma-separated):
  --scenes LIST        sphere, bunny (default sphere,bunny; bunny is skipped when absent)
  --points LIST        sphere point counts (default 100000,1000000,5000000)
  --sizes LIST         square image sizes in pixels (default 512,1024)
  --mappers LIST       splat (vtkSurfaceSplatMapper), pointgaussian (vtkPointGaussianMapper)
                       (default splat,pointgaussian)
  --backends LIST      vtkSurfaceSplatMapper's backends: cpu, opengl (default cpu,opengl)
  --frames N           at most N timed frames per case (default 10)
  --budget SECONDS     time a case's frames within this many seconds: after the first timed
                       frame, another is timed only while the elapsed time plus the last
                       frame's stays within the budget (default 10)
  --quick              smoke run: 20000 sphere points, 256x256, 2 frames
  --output FILE        CSV file, also written to stdout (default output/bench/bench.csv)
  --image-dir DIR      also write each case's last frame as a PNG into DIR
  --help               print this help

Environment: SPLAT_DATA_DIR, the folder holding bunny.ply (default: ../shared/data next to the
source tree).
)";

struct Options
{
  std::vector<std::string> Scenes = { "sphere", "bunny" };
  std::vector<long long> Points = { 100000, 1000000, 5000000 };
  std::vector<long long> Sizes = { 512, 1024 };
  std::vector<std::string> Mappers = { "splat", "pointgaussian" };
  std::vector<std::string> Backends = { "cpu", "opengl" };
  int Frames = 10;
  double Budget = 10.0;
  std::string Output = "output/bench/bench.csv";
  std::string ImageDir;
};

std::vector<long long> ParseCounts(
  const std::string& option, const std::string& text, long long low, long long high)
{
  std::vector<long long> values;
  std::istringstream fields(text);
  std::string item;
  while (std::getline(fields, item, ','))
  {
    values.push_back(ParseCount(option, item, low, high));
  }
  if (values.empty())
  {
    throw UsageError(option + ": the list is empty");
  }
  std::sort(values.begin(), values.end());
  return values;
}

Options ParseCommandLine(int argc, char* argv[])
{
  Options options;
  const std::map<std::string, splatexample::OptionHandler> handlers = {
    { "--scenes",
      [&](const std::string& name, const std::string& value) {
        options.Scenes = SplitList(name, value, { "sphere", "bunny" });
      } },
    { "--points",
      [&](const std::string& name, const std::string& value)
      { options.Points = ParseCounts(name, value, 1, 100000000); } },
    { "--sizes",
      [&](const std::string& name, const std::string& value)
      { options.Sizes = ParseCounts(name, value, 1, 16384); } },
    { "--mappers",
      [&](const std::string& name, const std::string& value) {
        options.Mappers = SplitList(name, value, { "splat", "pointgaussian" });
      } },
    { "--backends",
      [&](const std::string& name, const std::string& value) {
        options.Backends = SplitList(name, value, { "cpu", "opengl" });
      } },
    { "--frames",
      [&](const std::string& name, const std::string& value)
      { options.Frames = static_cast<int>(ParseCount(name, value, 1, 100000)); } },
    { "--budget",
      [&](const std::string& name, const std::string& value)
      { options.Budget = static_cast<double>(ParseCount(name, value, 0, 86400)); } },
    { "--output", [&](const std::string&, const std::string& value) { options.Output = value; } },
    { "--image-dir",
      [&](const std::string&, const std::string& value) { options.ImageDir = value; } },
  };

  const std::map<std::string, std::function<void()>> flags = {
    { "--quick",
      [&]
      {
        options.Points = { 20000 };
        options.Sizes = { 256 };
        options.Frames = 2;
      } },
  };
  splatexample::ParseArguments(argc, argv, Usage, handlers, flags);
  return options;
}

// n points uniformly spread on the unit sphere with radial normals and the radius of the
// sampling spacing, at which the splats just cover the sphere.
vtkSmartPointer<vtkPolyData> UnitSphere(vtkIdType n)
{
  vtkNew<vtkSurfelSphereSource> sphere;
  sphere->SetNumberOfPoints(n);
  sphere->SetRadius(1.0);
  sphere->Update();
  return sphere->GetOutput();
}

// The bunny's vertices as surfels.
vtkSmartPointer<vtkPolyData> BunnySurfels(const std::string& file)
{
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(file.c_str());
  vtkNew<vtkSurfelGenerator> surfels;
  surfels->SetInputConnection(reader->GetOutputPort());
  surfels->Update();
  return surfels->GetOutput();
}

struct MapperKind
{
  std::string Name;    // the --mappers name
  std::string Class;   // the VTK class (vtkPointGaussianMapper::New gives an OpenGL subclass)
  std::string Backend; // what draws the splats
  std::string Setting;
  bool BackfaceCulling = false;             // the actor property's BackfaceCulling
  bool ClosedOnly = false;                  // only for closed, outward-oriented scenes (the sphere)
  int SplatBackend = vtkSplatBackend::AUTO; // vtkSurfaceSplatMapper's SetBackend
  int FilterMode = vtkSurfaceSplatMapper::EWA;
};

// Cases per size, in this order, for the mappers and backends chosen with --mappers and
// --backends: vtkSurfaceSplatMapper's settings on each backend, then the peer.
std::vector<MapperKind> Kinds(const Options& options)
{
  const auto chosen = [](const std::vector<std::string>& list, const std::string& name)
  { return std::find(list.begin(), list.end(), name) != list.end(); };
  std::vector<MapperKind> kinds;
  if (chosen(options.Mappers, "splat"))
  {
    for (int backend : { vtkSplatBackend::CPU, vtkSplatBackend::OPENGL })
    {
      const std::string name = vtkSplatBackend::GetBackendAsString(backend);
      if (!chosen(options.Backends, vtksys::SystemTools::LowerCase(name)))
      {
        continue;
      }
      const MapperKind splat{ "splat", "vtkSurfaceSplatMapper", name, "default", false, false,
        backend, vtkSurfaceSplatMapper::EWA };
      kinds.push_back(splat);
      // APPROXIMATE is OpenGL only: the CPU would draw EWA again.
      if (backend == vtkSplatBackend::OPENGL)
      {
        MapperKind approximate = splat;
        approximate.Setting = "approximate";
        approximate.FilterMode = vtkSurfaceSplatMapper::APPROXIMATE;
        kinds.push_back(approximate);
      }
      MapperKind backface = splat;
      backface.Setting = "backface";
      backface.BackfaceCulling = backface.ClosedOnly = true;
      kinds.push_back(backface);
    }
  }
  if (chosen(options.Mappers, "pointgaussian"))
  {
    kinds.push_back({ "pointgaussian", "vtkPointGaussianMapper", "OpenGL", "disk" });
  }
  return kinds;
}

vtkSmartPointer<vtkMapper> MakeMapper(const MapperKind& kind, vtkPolyData* surfels)
{
  if (kind.Name == "splat")
  {
    vtkNew<vtkSurfaceSplatMapper> mapper;
    mapper->SetInputData(surfels);
    mapper->SetBackend(kind.SplatBackend);
    mapper->SetFilterMode(kind.FilterMode);
    return mapper;
  }
  return splatexample::PointGaussianDisks(surfels);
}

double PeakResidentMegabytes()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0; // kilobytes on Linux
}

// The process's current resident set size in bytes: the second field of /proc/self/statm, in
// pages. -1 where it cannot be read (not Linux).
long long CurrentResidentBytes()
{
  std::ifstream statm("/proc/self/statm");
  long long sizePages = 0;
  long long residentPages = 0;
  if (!(statm >> sizePages >> residentPages))
  {
    return -1;
  }
  return residentPages * static_cast<long long>(sysconf(_SC_PAGESIZE));
}

// Hands the heap's free memory back to the system, so the resident set is the memory in use:
// without it, what an earlier case freed stays resident (glibc keeps freed heap pages and raises
// its mmap threshold after large frees) and the next case reuses it without growing the RSS.
void ReleaseFreeHeapMemory()
{
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

// Median milliseconds per frame after a warm-up frame (surfel build, buffer upload, shader
// compilation): at least one frame, at most Frames, and after the first only while the elapsed
// time plus the last frame's stays within the budget (so that slow cases, such as
// vtkPointGaussianMapper on millions of points under llvmpipe, keep to it). `frames` gets the
// number of timed frames.
double MillisecondsPerFrame(vtkRenderWindow* window, const Options& options, int& frames)
{
  using Clock = std::chrono::steady_clock;
  window->Render();
  window->WaitForCompletion();
  std::vector<double> ms;
  const auto start = Clock::now();
  while (static_cast<int>(ms.size()) < options.Frames &&
    (ms.empty() ||
      std::chrono::duration<double>(Clock::now() - start).count() + ms.back() * 1e-3 <=
        options.Budget))
  {
    const auto frameStart = Clock::now();
    window->Render();
    // OpenGL runs asynchronously: the frame is done when the GL queue is.
    window->WaitForCompletion();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - frameStart).count());
  }
  frames = static_cast<int>(ms.size());
  return splatexample::Median(ms);
}

// What one case measured.
struct CaseResult
{
  vtkIdType Points = 0;
  double Milliseconds = 0.0;
  int Frames = 0;
  bool HasCounts = false; // vtkSurfaceSplatMapper's statistics of the last frame
  vtkIdType Rendered = 0;
  vtkIdType FrustumCulled = 0;
  vtkIdType BackfaceCulled = 0;
  vtkIdType Negligible = 0;
  vtkIdType Skipped = 0;
  long long ResidentGrowth = 0; // bytes; see MeasureCase
  bool HasResidentGrowth = false;
};

// Builds one case's data (makeData) and mapper, renders it in `window` and returns what it
// measured; the case's actor, mapper and data are released on return.
//
// Memory per splat: the current resident set size (/proc/self/statm) is read twice, once
// before the case's data and mapper are built and once after its timed frames, while they are
// all still alive; the difference is what the case holds (points, normals and radii, the
// mapper's surfel arrays and frame buffers, or vtkPointGaussianMapper's buffers and, on Mesa's
// llvmpipe, its driver-side copies), and bytes_per_splat is that difference divided by the
// number of points. So that both readings are the memory in use, the heap's free pages are
// handed back (malloc_trim) before each: freed temporaries (the surfel generator's neighbor
// search, vtkPointGaussianMapper's staging arrays) would otherwise stay resident and count. The
// previous case is released before the first reading, and the window has already been rendered
// once, empty, at the case's size (its own buffers are not the case's). It is the growth at the
// end of the case, not a peak: transient allocations freed before the last frame are not in
// it. Shared one-time costs (shader compilation, the driver's first-use allocations) land on the
// first case that triggers them. At small point counts the per-pixel buffers (the rasterizer's
// fragments at the case's image size) dominate.
CaseResult MeasureCase(vtkRenderWindow* window, const MapperKind& kind,
  const std::function<vtkSmartPointer<vtkPolyData>()>& makeData, const Options& options,
  const std::string& scene, long long size)
{
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  CaseResult result;
  ReleaseFreeHeapMemory();
  const long long before = CurrentResidentBytes();
  {
    vtkSmartPointer<vtkPolyData> surfels = makeData();
    result.Points = surfels->GetNumberOfPoints();
    vtkSmartPointer<vtkMapper> mapper = MakeMapper(kind, surfels);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.85, 0.75, 0.6);
    actor->GetProperty()->SetBackfaceCulling(kind.BackfaceCulling);
    renderer->AddActor(actor);
    // The same view for both mappers: their bounds differ (ours include the splat radii).
    renderer->ResetCamera(surfels->GetBounds());

    result.Milliseconds = MillisecondsPerFrame(window, options, result.Frames);
    ReleaseFreeHeapMemory();
    const long long after = CurrentResidentBytes();
    if (before >= 0 && after >= 0)
    {
      result.ResidentGrowth = after - before;
      result.HasResidentGrowth = true;
    }
    if (auto* splat = vtkSurfaceSplatMapper::SafeDownCast(mapper))
    {
      result.HasCounts = true;
      result.Rendered = splat->GetNumberOfRenderedSplats();
      result.FrustumCulled = splat->GetNumberOfFrustumCulledSplats();
      result.BackfaceCulled = splat->GetNumberOfBackfaceCulledSplats();
      result.Negligible = splat->GetNumberOfNegligibleSplats();
      result.Skipped = splat->GetNumberOfSkippedPoints();
    }
    if (!options.ImageDir.empty())
    {
      splatexample::WritePNG(window,
        options.ImageDir + "/" + scene + "-" + std::to_string(result.Points) + "-" +
          std::to_string(size) + "-" + kind.Name + "-" +
          vtksys::SystemTools::LowerCase(kind.Backend) + "-" + kind.Setting + ".png");
    }
    // Releases the case's graphics resources; the actor, mapper and data go with this scope.
    renderer->RemoveAllViewProps();
  }
  return result;
}

// Renders one scene (made afresh for every case by makeData) at every size with every chosen
// mapper setting into `window` and emits a CSV row per case; returns the number of rows.
int MeasureScene(vtkRenderWindow* window, const std::string& scene, bool closed,
  const std::function<vtkSmartPointer<vtkPolyData>()>& makeData, const Options& options,
  std::ostream& csv)
{
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  int rows = 0;
  for (long long size : options.Sizes)
  {
    // The window's own buffers at this size, before any case's memory is measured.
    renderer->RemoveAllViewProps();
    window->SetSize(static_cast<int>(size), static_cast<int>(size));
    window->Render();
    window->WaitForCompletion();
    for (const MapperKind& kind : Kinds(options))
    {
      if (kind.ClosedOnly && !closed)
      {
        continue;
      }
      std::cerr << "splat_bench: " << scene << ", " << size << "x" << size << ", " << kind.Class
                << " (" << kind.Backend << ", " << kind.Setting << ") ...\n";
      const CaseResult r = MeasureCase(window, kind, makeData, options, scene, size);

      std::ostringstream row;
      row << scene << "," << kind.Class << "," << kind.Backend << "," << kind.Setting << ","
          << r.Points << "," << size << "," << size << "," << std::fixed << std::setprecision(2)
          << r.Milliseconds << "," << std::setprecision(0) << r.Points / (r.Milliseconds * 1e-3)
          << "," << std::setprecision(1) << PeakResidentMegabytes() << ",";
      if (r.HasCounts)
      {
        row << r.Rendered << "," << r.FrustumCulled << "," << r.BackfaceCulled << ","
            << r.Negligible << "," << r.Skipped << ",";
      }
      else
      {
        row << ",,,,,";
      }
      if (r.HasResidentGrowth && r.Points > 0)
      {
        row << std::setprecision(1) << static_cast<double>(r.ResidentGrowth) / r.Points;
      }
      row << "\n";
      std::cout << row.str() << std::flush;
      csv << row.str() << std::flush;
      ++rows;

      std::ostringstream summary;
      summary << "splat_bench: " << scene << " " << r.Points << " points " << size << "x" << size
              << " " << kind.Class << " " << kind.Backend << " " << kind.Setting << ": "
              << std::fixed << std::setprecision(2) << r.Milliseconds << " ms/frame (median of "
              << r.Frames << ")";
      if (r.HasCounts)
      {
        summary << "; rendered " << r.Rendered << ", frustum culled " << r.FrustumCulled
                << ", backface culled " << r.BackfaceCulled << ", negligible " << r.Negligible
                << ", skipped " << r.Skipped;
      }
      if (r.HasResidentGrowth)
      {
        summary << "; RSS +" << std::setprecision(1) << r.ResidentGrowth / (1024.0 * 1024.0)
                << " MB";
        if (r.Points > 0)
        {
          summary << " (" << static_cast<double>(r.ResidentGrowth) / r.Points << " B/splat)";
        }
      }
      std::cerr << summary.str() << "\n";
    }
  }
  return rows;
}

int Run(const Options& options)
{
  splatexample::MakeFolder(vtksys::SystemTools::GetFilenamePath(options.Output));
  splatexample::MakeFolder(options.ImageDir);
  std::ofstream csv(options.Output);
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + options.Output + "'");
  }
  // The required columns first, then the culling counts and the memory per splat.
  const char* const header =
    "scene,mapper,backend,setting,points,width,height,ms_per_frame,splats_per_s,peak_rss_mb,"
    "rendered,frustum_culled,backface_culled,negligible,skipped,bytes_per_splat\n";
  std::cout << header << std::flush;
  csv << header << std::flush;

  // One window for every case (see splatexample::MakeOffscreenWindow); each scene sets its size.
  vtkSmartPointer<vtkRenderWindow> window = splatexample::MakeOffscreenWindow();
  window->GetRenderers()->GetFirstRenderer()->SetBackground(0.1, 0.1, 0.15);

  // The process's peak memory only grows: the small bunny first, then the spheres by size.
  const auto wants = [&](const char* scene) {
    return std::find(options.Scenes.begin(), options.Scenes.end(), scene) != options.Scenes.end();
  };
  int rows = 0;
  if (wants("bunny"))
  {
    const std::string bunny = splatexample::BunnyFile();
    if (vtkPLYReader::CanReadFile(bunny.c_str()))
    {
      // The bunny has holes (its base): no backface setting.
      rows += MeasureScene(
        window, "bunny", false, [&]() { return BunnySurfels(bunny); }, options, csv);
    }
    else
    {
      std::cerr << "splat_bench: bunny skipped: " << bunny << " is absent or unreadable\n";
    }
  }
  if (wants("sphere"))
  {
    for (long long n : options.Points)
    {
      rows += MeasureScene(
        window, "sphere", true, [n]() { return UnitSphere(static_cast<vtkIdType>(n)); }, options,
        csv);
    }
  }
  std::cerr << "splat_bench: " << rows << " rows; CSV written to "
            << vtksys::SystemTools::CollapseFullPath(options.Output) << "\n";
  return rows > 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
}

int main(int argc, char* argv[])
{
  return splatexample::RunProgram("splat_bench", [&] { return Run(ParseCommandLine(argc, argv)); });
}
