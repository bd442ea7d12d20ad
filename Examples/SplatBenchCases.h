// SPDX-License-Identifier: BSD-3-Clause
// splat_bench's cases and how each is measured: the command line's settings, what a case draws
// (a prop, its mapper and data) and a scene's cases, the frame timing, the memory readings and
// the CSV row and summary of a case. The scenes themselves and the command line are in
// SplatBench.cxx.
#ifndef SplatBenchCases_h
#define SplatBenchCases_h

#include "SplatExampleUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataSet.h"
#include "vtkProp3D.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <array>
#include <chrono>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>


namespace splatbench
{
struct Options
{
  std::vector<std::string> Scenes = { "sphere", "bunny", "mri", "gaussians", "3dgs", "vdb" };
  std::vector<long long> Points = { 100000, 1000000, 5000000 };
  long long Kernels = 1000000;
  long long Grid = 256;
  long long Voxels = 1000000; // of the vdb scene
  int MriShrink = 1;
  std::vector<long long> Sizes = { 512, 1024 };
  std::vector<std::string> Mappers = { "splat", "pointgaussian", "fixedpoint", "gpuraycast" };
  std::vector<std::string> Backends = { "cpu", "opengl" };
  std::vector<std::string> VolumeBackends = { "cpu" }; // --backends sets both
  std::vector<std::string> Orderings = { "blended", "clipped", "single-axis", "depth-sorted",
    "blended-exact", "depth-sorted-antialiased", "depth-sorted-low-pass" };
  int Frames = 0; // --frames: at most this many timed frames per case (0: the scene's)
  double Budget = 10.0;
  std::string Output = "output/bench/bench.csv";
  std::string ImageDir;
  int Case = -1; // --case: run only this case of the one scene and size, in this process
  bool GpuTimings = false; // --gpu-timings
};

struct MapperKind
{
  std::string Name;    // the --mappers name
  std::string Class;   // the VTK class (vtkPointGaussianMapper::New gives an OpenGL subclass)
  std::string Backend; // what draws the splats
  std::string Setting;
  bool BackfaceCulling = false;             // the actor property's BackfaceCulling
  bool ClosedOnly = false;                  // only for closed, outward-oriented scenes (the sphere)
  int SplatBackend = vtkSplatBackend::AUTO; // the splat mappers' SetBackend
  int FilterMode = vtkSurfaceSplatMapper::EWA;
  int Ordering = vtkVolumeSplatMapper::BLENDED; // vtkVolumeSplatMapper's SetOrderingMode
  int FootprintFilter = vtkVolumeSplatMapper::AUTOMATIC_FILTER; // and its SetFootprintFilter
  bool ExactKernels = false; // vtkSurfaceSplatMapper's SetMinifiedVariance(0), and
                             // vtkVolumeSplatMapper's SetSheetResampling(false)
  bool LevelOfDetail = true; // vtkSurfaceSplatMapper's SetLevelOfDetail
};

// What a case draws: a prop (an actor or a volume) with its mapper, and the mapper's input.
struct Stage
{
  vtkSmartPointer<vtkProp3D> Prop;
  vtkSmartPointer<vtkDataSet> Data;
};

// A scene: its cases, how to make each case's prop and where to put the camera.
struct Scene
{
  std::string Name;
  std::vector<MapperKind> Kinds;
  std::function<Stage(const MapperKind&)> Make;
  std::function<void(vtkRenderer*, const Stage&)> Place;
  int Frames = 10; // at most this many timed frames per case, unless --frames says
};

// A memory field of /proc/self/status in bytes: "VmRSS" (resident now) or "VmHWM" (the peak
// resident set of this process image: a fresh one per case, see RunCases). -1 where it cannot be
// read (not Linux).
inline long long ProcessStatusBytes(const std::string& field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.compare(0, field.size() + 1, field + ":") == 0)
    {
      return std::stoll(line.substr(field.size() + 1)) * 1024; // in kB
    }
  }
  return -1;
}

// Median milliseconds per frame after a warm-up frame (surfel or kernel build, buffer upload,
// shader compilation): at least one frame, at most `maxFrames`, and after the first only while
// the elapsed time plus the last frame's stays within the budget (so that slow cases, such as
// vtkPointGaussianMapper on millions of points under llvmpipe, keep to it). Before each timed
// frame of a volume, the volume is marked modified, as in TestVolumeSplatCrossRenderer, and the
// camera turns by half a degree (the transfer function unchanged): a later frame of an
// interaction. `frames` gets the number of timed frames and `firstMilliseconds` the warm-up
// frame's time.
inline double MillisecondsPerFrame(vtkRenderWindow* window, const Options& options, int maxFrames,
  vtkVolume* volume, int& frames, double& firstMilliseconds)
{
  using Clock = std::chrono::steady_clock;
  const auto firstStart = Clock::now();
  window->Render();
  window->WaitForCompletion();
  firstMilliseconds = std::chrono::duration<double, std::milli>(Clock::now() - firstStart).count();
  vtkRenderTimerLog* timer = window->GetRenderTimer();
  timer->SetLoggingEnabled(options.GpuTimings && timer->IsSupported());
  std::vector<double> ms;
  const auto start = Clock::now();
  while (static_cast<int>(ms.size()) < maxFrames &&
    (ms.empty() ||
      std::chrono::duration<double>(Clock::now() - start).count() + ms.back() * 1e-3 <=
        options.Budget))
  {
    if (volume)
    {
      volume->Modified();
      window->GetRenderers()->GetFirstRenderer()->GetActiveCamera()->Azimuth(0.5);
    }
    const auto frameStart = Clock::now();
    window->Render();
    // OpenGL runs asynchronously: the frame is done when the GL queue is.
    window->WaitForCompletion();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - frameStart).count());
  }
  frames = static_cast<int>(ms.size());
  if (timer->GetLoggingEnabled())
  {
    // The GPU time of each pass of the last timed frame (OpenGL timer queries).
    timer->MarkFrame();
    window->WaitForCompletion();
    vtkRenderTimerLog::Frame last;
    while (timer->FrameReady())
    {
      last = timer->PopFirstReadyFrame();
    }
    std::cerr << "GPU times of the last frame, ms:\n";
    last.Print(std::cerr);
    timer->LoggingEnabledOff();
  }
  return splatexample::Median(ms);
}

// What one case measured.
struct CaseResult
{
  const MapperKind* Kind = nullptr;
  vtkIdType Points = 0;
  double Milliseconds = 0.0;
  double FirstMilliseconds = 0.0; // the warm-up frame
  int Frames = 0;
  bool HasCounts = false; // the splat mapper's statistics of the last frame
  // rendered, frustum_culled, backface_culled, negligible, skipped (see the usage)
  std::array<std::string, 5> Counts;
  std::string DrawnBy; // the splat mappers' GetLastBackend
  long long PeakResident = -1; // bytes; see MeasureCase
  long long ResidentGrowth = -1;
};

// The splat mappers' statistics of the last frame, in the columns rendered .. skipped (see the
// usage for what they mean for volumes), and the backend that drew it.
inline void CollectCounts(vtkProp3D* prop, CaseResult& result)
{
  if (auto* actor = vtkActor::SafeDownCast(prop))
  {
    if (auto* splat = vtkSurfaceSplatMapper::SafeDownCast(actor->GetMapper()))
    {
      result.HasCounts = true;
      result.Counts = { std::to_string(splat->GetNumberOfRenderedSplats()),
        std::to_string(splat->GetNumberOfFrustumCulledSplats()),
        std::to_string(splat->GetNumberOfBackfaceCulledSplats()),
        std::to_string(splat->GetNumberOfNegligibleSplats()),
        std::to_string(splat->GetNumberOfSkippedPoints()) };
      result.DrawnBy = vtkSplatBackend::GetBackendAsString(splat->GetLastBackend());
    }
  }
  else if (auto* volume = vtkVolume::SafeDownCast(prop))
  {
    if (auto* splat = vtkVolumeSplatMapper::SafeDownCast(volume->GetMapper()))
    {
      result.Points = splat->GetNumberOfKernels();
      result.HasCounts = true;
      result.Counts = { std::to_string(splat->GetNumberOfProjectedKernels()),
        std::to_string(splat->GetNumberOfFrustumCulledKernels()), "",
        std::to_string(splat->GetNumberOfTransparentKernels()),
        std::to_string(
          splat->GetNumberOfInvalidKernels() + splat->GetNumberOfNearPlaneKernels()) };
      result.DrawnBy = vtkSplatBackend::GetBackendAsString(splat->GetLastBackend());
    }
  }
}

// Makes one case's prop (scene.Make), renders it in `window` and returns what it measured. The
// points are the input's, or vtkVolumeSplatMapper's kernels (its lists, transparent voxels left
// out).
//
// Memory: this process runs this one case (RunCases starts a fresh process per case), so its
// peak resident set (VmHWM) after the timed frames is the case's peak, transient allocations
// included; `baselineBytes` is the resident set of the same process before the case's data was
// made (the window already rendered once, empty, at the case's size: its own buffers are not
// the case's). The growth (peak minus baseline) counts the data (points and arrays, or the
// volume's kernels or image), the mapper's arrays and frame buffers, vtkPointGaussianMapper's
// buffers and, on Mesa's llvmpipe, its driver-side copies, and the one-time costs (shader
// compilation, the driver's first-use allocations); for the ray casters it includes the grid
// they draw and, for gaussians, its resampling.
inline CaseResult MeasureCase(vtkRenderWindow* window, const MapperKind& kind, const Scene& scene,
  const Options& options, long long size, long long baselineBytes)
{
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  CaseResult result;
  result.Kind = &kind;
  const Stage stage = scene.Make(kind);
  result.Points = stage.Data->GetNumberOfPoints();
  renderer->AddViewProp(stage.Prop);
  scene.Place(renderer, stage);

  result.Milliseconds = MillisecondsPerFrame(window, options,
    options.Frames > 0 ? options.Frames : scene.Frames,
    vtkVolume::SafeDownCast(stage.Prop), result.Frames, result.FirstMilliseconds);
  result.PeakResident = ProcessStatusBytes("VmHWM");
  if (baselineBytes >= 0 && result.PeakResident >= 0)
  {
    result.ResidentGrowth = result.PeakResident - baselineBytes;
  }
  CollectCounts(stage.Prop, result);
  if (!options.ImageDir.empty())
  {
    std::string setting = kind.Setting;
    std::replace(setting.begin(), setting.end(), ' ', '-');
    splatexample::WritePNG(window,
      options.ImageDir + "/" + scene.Name + "-" + std::to_string(result.Points) + "-" +
        std::to_string(size) + "-" + kind.Name + "-" +
        vtksys::SystemTools::LowerCase(kind.Backend) + "-" + setting + ".png");
  }
  renderer->RemoveAllViewProps();
  return result;
}

// The CSV row of a case, its peer_ratio empty (RunCases fills it in once the peer has run).
inline std::string CsvRow(const std::string& scene, long long size, const CaseResult& r)
{
  const MapperKind& kind = *r.Kind;
  std::ostringstream row;
  row << scene << "," << kind.Class << "," << kind.Backend << "," << kind.Setting << ","
      << r.Points << "," << size << "," << size << "," << std::fixed << std::setprecision(2)
      << r.Milliseconds << "," << std::setprecision(0) << r.Points / (r.Milliseconds * 1e-3)
      << "," << std::setprecision(1) << r.PeakResident / (1024.0 * 1024.0) << ",";
  for (const std::string& count : r.Counts)
  {
    row << count << ",";
  }
  if (r.ResidentGrowth >= 0 && r.Points > 0)
  {
    row << std::setprecision(1) << static_cast<double>(r.ResidentGrowth) / r.Points;
  }
  row << ",," << r.DrawnBy << "," << std::setprecision(2) << r.FirstMilliseconds << "\n";
  return row.str();
}

// The one-line summary of a case on stderr.
inline std::string Summary(const std::string& scene, long long size, const CaseResult& r)
{
  const MapperKind& kind = *r.Kind;
  const bool volume =
    kind.Class != "vtkSurfaceSplatMapper" && kind.Class != "vtkPointGaussianMapper";
  std::ostringstream summary;
  summary << "splat_bench: " << scene << " " << r.Points << (volume ? " kernels " : " points ")
          << size << "x" << size << " " << kind.Class << " " << kind.Backend << " "
          << kind.Setting << ": " << std::fixed << std::setprecision(2) << r.Milliseconds
          << " ms/frame (median of " << r.Frames << "; first frame " << r.FirstMilliseconds
          << " ms), " << std::setprecision(0)
          << r.Points / (r.Milliseconds * 1e-3) << (volume ? " kernels/s" : " splats/s");
  if (!r.DrawnBy.empty())
  {
    summary << ", drawn by " << r.DrawnBy;
  }
  if (r.HasCounts)
  {
    summary << (volume ? "; projected " : "; rendered ") << r.Counts[0] << ", frustum culled "
            << r.Counts[1];
    if (!volume)
    {
      summary << ", backface culled " << r.Counts[2] << ", negligible " << r.Counts[3]
              << ", skipped " << r.Counts[4];
    }
    else
    {
      summary << ", transparent " << r.Counts[3] << ", invalid or at the near plane "
              << r.Counts[4];
    }
  }
  if (r.ResidentGrowth >= 0)
  {
    summary << "; peak RSS " << std::setprecision(1) << r.PeakResident / (1024.0 * 1024.0)
            << " MB, +" << r.ResidentGrowth / (1024.0 * 1024.0) << " MB";
    if (r.Points > 0)
    {
      summary << " (" << static_cast<double>(r.ResidentGrowth) / r.Points << " B/splat)";
    }
  }
  return summary.str();
}

// Runs case options.Case of `scene` at the one size of options.Sizes in `window` and writes its
// CSV row to `csv`; `baselineBytes` is this process's resident set before the scene's data.
inline void MeasureOneCase(vtkRenderWindow* window, const Scene& scene, const Options& options,
  std::ostream& csv, long long baselineBytes)
{
  if (options.Case >= static_cast<int>(scene.Kinds.size()))
  {
    throw std::runtime_error(scene.Name + " has no case " + std::to_string(options.Case));
  }
  const MapperKind& kind = scene.Kinds[options.Case];
  const long long size = options.Sizes.front();
  std::cerr << "splat_bench: " << scene.Name << ", " << size << "x" << size << ", " << kind.Class
            << " (" << kind.Backend << ", " << kind.Setting << ") ...\n";
  const CaseResult result = MeasureCase(window, kind, scene, options, size, baselineBytes);
  std::cerr << Summary(scene.Name, size, result) << "\n";
  csv << CsvRow(scene.Name, size, result) << std::flush;
}
}

#endif
