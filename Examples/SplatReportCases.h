// SPDX-License-Identifier: BSD-3-Clause
// splat_report's settings and cases: the quality settings of vtkSurfaceSplatMapper changed one at
// a time from its default on each backend, its peer vtkPointGaussianMapper, and the volume
// cases (vtkVolumeSplatMapper's orderings and cutoffs, VTK's ray casters).
#ifndef SplatReportCases_h
#define SplatReportCases_h

#include "SplatVolumeScenes.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkMapper.h"
#include "vtkNew.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkVolumeProperty.h"

#include <vtksys/SystemTools.hxx>

#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace splatreport
{
/// The command line's settings (see the usage in SplatReport.cxx).
struct Options
{
  std::string OutputDir;
  std::vector<std::string> Scenes = { "checkerboard", "textured-plane", "bunny", "bunny-closeup",
    "armadillo", "armadillo-closeup", "armadillo-points", "sphere", "mri", "gaussians", "vdb",
    "stability", "captures" };
  std::vector<std::string> Backends = { "cpu", "opengl" };
  std::vector<std::string> VolumeBackends = { "cpu" }; // --backends sets both
  int VolumeSize = 256;
  int MriShrink = 2;
  long long Kernels = 2000;
  long long Voxels = 100000;
  int Grid = 128;
  int Width = 512;
  int Height = 384;
  int Rounds = 4;
  int Frames = 3;
  double Budget = 3.0;
  long long Points = 1000000;
  int Samples = 16;
};

// A number with `digits` decimals.
inline std::string Fixed(double value, int digits)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(digits) << value;
  return text.str();
}

// vtkSMPTools' thread count before any change: all cores, or VTK_SMP_MAX_THREADS.
inline int AllThreads()
{
  static const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  return threads;
}

// Sets the SMP thread count (0: AllThreads()); returns the count in effect afterwards. Always
// explicit: VTK 9.1's TBB backend re-initializes its task arena for any new positive count, but
// Initialize(0) leaves the last count in place instead of going back to all cores.
inline int UseThreads(int threads)
{
  vtkSMPTools::Initialize(threads > 0 ? threads : AllThreads());
  return vtkSMPTools::GetEstimatedNumberOfThreads();
}

//------------------------------------------------------------------------------------------------
inline const char* FilterModeName(int mode)
{
  switch (mode)
  {
    case vtkSurfaceSplatMapper::EWA:
      return "EWA";
    case vtkSurfaceSplatMapper::CIRCULAR:
      return "circular";
    case vtkSurfaceSplatMapper::UNFILTERED:
      return "unfiltered";
    default:
      return "?";
  }
}

// The default mapper's settings in words, e.g. "EWA, cutoff automatic (0.5 to 4), layers
// automatic (5 or 3), edge AA on".
inline std::string DefaultSettingDescription()
{
  vtkNew<vtkSurfaceSplatMapper> mapper;
  std::ostringstream text;
  const int layers = mapper->GetNumberOfLayers();
  text << FilterModeName(mapper->GetFilterMode()) << ", cutoff "
       << (mapper->GetCutoff() > 0.0 ? Fixed(mapper->GetCutoff(), 1) : "automatic (0.5 to 4)") << ", "
       << "low-pass "
       << (mapper->GetMagnifiedLowPassVariance() > 0.0
              ? Fixed(mapper->GetMagnifiedLowPassVariance(), 2) + " magnified"
              : "automatic (1/12 or 1)")
       << ", "
       << (layers > 0 ? std::to_string(layers) + (layers == 1 ? " layer" : " layers")
                      : "layers automatic (5 or 3)")
       << ", edge AA "
       << (mapper->GetEdgeAntialiasing() ? "on" : "off") << ", coverage threshold "
       << (mapper->GetCoverageThreshold() > 0.0 ? Fixed(mapper->GetCoverageThreshold(), 2)
                                                : "automatic (0.4 or 0.8)")
       << ", minified variance "
       << mapper->GetMinifiedVariance() << ", level of detail "
       << (mapper->GetLevelOfDetail() ? "on" : "off") << " (CPU)";
  return text.str();
}

// One quality setting of vtkSurfaceSplatMapper, changed from the default: adding a setting to
// the report is one entry of SplatSettings().
struct SplatSetting
{
  std::string Family; // the plot's series
  std::string Name;   // the table's setting column
  std::function<void(vtkSurfaceSplatMapper*)> Apply;
  bool OpenGLOnly = false; // the CPU backend would draw its default instead
  bool CPUOnly = false;    // the OpenGL backend would draw its default instead
};

inline std::vector<SplatSetting> SplatSettings()
{
  std::vector<SplatSetting> settings = {
    { "cutoff", "cutoff=0.5", [](vtkSurfaceSplatMapper* m) { m->SetCutoff(0.5); } },
    { "cutoff", "cutoff=1 (paper)", [](vtkSurfaceSplatMapper* m) { m->SetCutoffToPaper(); } },
    { "cutoff", "cutoff=2", [](vtkSurfaceSplatMapper* m) { m->SetCutoff(2.0); } },
    { "cutoff", "cutoff=4", [](vtkSurfaceSplatMapper* m) { m->SetCutoff(4.0); } },
    { "low-pass", "low-pass=1 (paper)",
      [](vtkSurfaceSplatMapper* m) { m->SetMagnifiedLowPassVarianceToPaper(); } },
    { "filter mode", "filter=circular",
      [](vtkSurfaceSplatMapper* m) { m->SetFilterMode(vtkSurfaceSplatMapper::CIRCULAR); } },
    { "filter mode", "filter=unfiltered",
      [](vtkSurfaceSplatMapper* m) { m->SetFilterMode(vtkSurfaceSplatMapper::UNFILTERED); } },
    { "approximate", "filter=approximate",
      [](vtkSurfaceSplatMapper* m) { m->SetFilterMode(vtkSurfaceSplatMapper::APPROXIMATE); },
      true },
    { "layers", "layers=1", [](vtkSurfaceSplatMapper* m) { m->SetNumberOfLayers(1); } },
    { "layers", "layers=3 (paper)",
      [](vtkSurfaceSplatMapper* m) { m->SetNumberOfLayersToPaper(); } },
    { "layers", "layers=5", [](vtkSurfaceSplatMapper* m) { m->SetNumberOfLayers(5); } },
    { "minified", "minified=0 (exact)",
      [](vtkSurfaceSplatMapper* m) { m->SetMinifiedVariance(0.0); }, false, true },
    { "minified", "minified=0.25",
      [](vtkSurfaceSplatMapper* m) { m->SetMinifiedVariance(0.25); }, false, true },
    { "level of detail", "level-of-detail=off",
      [](vtkSurfaceSplatMapper* m) { m->SetLevelOfDetail(false); }, false, true },
  };
  // Edge antialiasing: the opposite of the default.
  vtkNew<vtkSurfaceSplatMapper> probe;
  const bool flipped = !probe->GetEdgeAntialiasing();
  settings.push_back({ "edge AA", flipped ? "edge-aa=on" : "edge-aa=off",
    [flipped](vtkSurfaceSplatMapper* m) { m->SetEdgeAntialiasing(flipped); } });
  return settings;
}

// One rendering to measure.
// The inputs of a volume scene: vtkVolumeSplatMapper's kernels (image data or a point set) and
// property, and the ray casters' image data and property.
struct VolumeInputs
{
  vtkDataSet* Kernels;
  vtkVolumeProperty* Property;
  vtkImageData* Grid;
  vtkVolumeProperty* GridProperty;
  vtkMatrix4x4* GridMatrix; // the ray casters' volume matrix (null: identity)
};

struct Case
{
  std::string Mapper;  // the VTK class
  std::string Backend; // what draws it
  std::string Family;  // the plot's series (per backend, see SeriesOf)
  std::string Setting; // the table's setting column
  int Threads = 0;     // vtkSMPTools threads; 0 for OpenGL (the driver's own)
  bool IsDefault = false;
  // Makes the mapper for the surfels (surface scenes).
  std::function<vtkSmartPointer<vtkMapper>(vtkPolyData*)> Make;
  bool Defaults = false; // the mapper's default settings (a thread count or a backend aside)
  // Makes the mapper for a volume scene's inputs (volume scenes).
  std::function<vtkSmartPointer<vtkAbstractVolumeMapper>(const VolumeInputs&)> MakeVolume;
};

// One of our splat mappers (the other rows are peers).
inline bool IsOurs(const Case& c)
{
  return c.Mapper == "vtkSurfaceSplatMapper" || c.Mapper == "vtkVolumeSplatMapper";
}

// Our mapper on a backend other than the CPU (whose rows came first and keep their names).
inline bool OnOtherBackend(const Case& c)
{
  return IsOurs(c) && c.Backend != "CPU";
}

// The images' name of the mapper: "splat", "splat-opengl", "pointgaussian", "fixedpoint",
// "gpuraycast" (the CPU backend's names as before the OpenGL backend).
inline std::string MapperSlug(const Case& c)
{
  if (IsOurs(c))
  {
    return OnOtherBackend(c) ? "splat-" + vtksys::SystemTools::LowerCase(c.Backend) : "splat";
  }
  return c.Mapper == "vtkPointGaussianMapper" ? "pointgaussian"
    : c.Mapper == "vtkFixedPointVolumeRayCastMapper" ? "fixedpoint"
                                                     : "gpuraycast";
}

// The plot's series of a case: its family of settings, named with the backend when not the CPU.
inline std::string SeriesOf(const Case& c)
{
  const std::string family = c.Family != "default" ? c.Family
    : c.Mapper == "vtkVolumeSplatMapper"             ? "default (blended)"
                                                     : "default (EWA)";
  return OnOtherBackend(c) ? c.Backend + " " + family : family;
}

inline std::vector<Case> Cases(
  const std::vector<int>& threadCounts, const std::vector<std::string>& backends)
{
  const int allThreads = threadCounts.back();
  const auto splat = [](int backend, const std::function<void(vtkSurfaceSplatMapper*)>& apply) {
    return [backend, apply](vtkPolyData* surfels) -> vtkSmartPointer<vtkMapper> {
      vtkNew<vtkSurfaceSplatMapper> mapper;
      mapper->SetInputData(surfels);
      mapper->SetRadiusArrayName("Radius");
      mapper->SetBackend(backend);
      if (apply)
      {
        apply(mapper);
      }
      return mapper;
    };
  };
  std::vector<Case> cases;
  const std::string defaults = "default (" + DefaultSettingDescription() + ")";
  // The same settings on both backends. The CPU's default row is the report's default and its
  // thread counts are settings; OpenGL's rows run on the driver's threads (0).
  for (int backend : splatexample::ChosenSplatBackends(backends))
  {
    const std::string name = vtkSplatBackend::GetBackendAsString(backend);
    const bool cpu = backend == vtkSplatBackend::CPU;
    if (cpu)
    {
      for (auto it = threadCounts.rbegin(); it != threadCounts.rend(); ++it)
      {
        cases.push_back({ "vtkSurfaceSplatMapper", name,
          *it == allThreads ? "default" : "threads", defaults, *it, *it == allThreads,
          splat(backend, nullptr), true });
      }
    }
    else
    {
      cases.push_back({ "vtkSurfaceSplatMapper", name, "default", "default", 0, false,
        splat(backend, nullptr), true });
    }
    for (const SplatSetting& s : SplatSettings())
    {
      if (cpu ? s.OpenGLOnly : s.CPUOnly)
      {
        continue;
      }
      cases.push_back({ "vtkSurfaceSplatMapper", name, s.Family, s.Name, cpu ? allThreads : 0,
        false, splat(backend, s.Apply) });
    }
  }
  // The peer, on the same points: opaque disks of the surfels' radius (the like-for-like surface
  // rendering), and its default Gaussian blobs with the surfels' variance R^2/2 (sigma R/sqrt 2),
  // emissive off (alpha-blended, unsorted).
  const auto disks = [](vtkPolyData* surfels) -> vtkSmartPointer<vtkMapper> {
    return splatexample::PointGaussianDisks(surfels);
  };
  const auto gaussians = [](vtkPolyData* surfels) -> vtkSmartPointer<vtkMapper> {
    vtkNew<vtkPointGaussianMapper> mapper;
    mapper->SetInputData(surfels);
    mapper->SetScaleArray("Radius");
    mapper->SetScaleFactor(1.0 / std::sqrt(2.0));
    mapper->EmissiveOff();
    return mapper;
  };
  cases.push_back(
    { "vtkPointGaussianMapper", "OpenGL", "vtkPointGaussianMapper", "disk", 0, false, disks });
  cases.push_back({ "vtkPointGaussianMapper", "OpenGL", "vtkPointGaussianMapper", "gaussian", 0,
    false, gaussians });
  return cases;
}

// The cases of the volume scenes: vtkVolumeSplatMapper in every ordering mode on each backend
// (the CPU's blended mode is the default), the low-pass filter, cutoffs other than the
// default, the sheets of image data one by one (merging=off) and the exact per-kernel path
// (sheets=off) on the CPU, and VTK's ray casters on the grid, sampling their rays every voxel
// spacing and every quarter of it.
inline std::vector<Case> VolumeCases(const std::vector<std::string>& backends)
{
  const int allThreads = AllThreads();
  std::vector<Case> cases;
  const auto splat =
    [](int backend, int ordering, double cutoff, bool sheets = true, bool merging = true)
  {
    return [=](const VolumeInputs& in) -> vtkSmartPointer<vtkAbstractVolumeMapper> {
      return splatexample::VolumeSplat(in.Kernels, backend, ordering, cutoff, sheets, merging);
    };
  };
  vtkNew<vtkVolumeSplatMapper> probe;
  const double defaultCutoff = probe->GetCutoff();
  const int ordering = probe->GetOrderingMode();
  for (int backend : splatexample::ChosenSplatBackends(backends))
  {
    const std::string name = vtkSplatBackend::GetBackendAsString(backend);
    const bool cpu = backend == vtkSplatBackend::CPU;
    for (int mode : splatexample::OrderingModes())
    {
      const bool defaults = mode == probe->GetOrderingMode();
      Case c{ "vtkVolumeSplatMapper", name, defaults ? "default" : "ordering",
        defaults ? "default (" + std::string(splatexample::OrderingModeName(mode)) + ", cutoff " +
            Fixed(defaultCutoff, 1) + ")"
                 : splatexample::OrderingModeName(mode),
        cpu ? allThreads : 0, cpu && defaults, nullptr, defaults };
      c.MakeVolume = splat(backend, mode, 0.0);
      cases.push_back(c);
    }
    // EWA's low-pass added to the footprints (LOW_PASS_FILTER) rather than the default's floor
    // of their spread; on the CPU with the exact per-kernel path too, which merges no pairs of
    // sheets.
    for (bool sheets : { true, false })
    {
      if (!sheets && !cpu)
      {
        continue;
      }
      Case c{ "vtkVolumeSplatMapper", name, "filter",
        sheets ? "filter=low-pass" : "filter=low-pass (sheets=off)", cpu ? allThreads : 0 };
      c.MakeVolume = [=](const VolumeInputs& in) -> vtkSmartPointer<vtkAbstractVolumeMapper>
      {
        auto mapper = splatexample::VolumeSplat(in.Kernels, backend, ordering, 0.0, sheets);
        mapper->SetFootprintFilterToLowPass();
        return mapper;
      };
      cases.push_back(c);
    }
    if (cpu)
    {
      for (double cutoff : { 2.0, 8.0 })
      {
        Case c{ "vtkVolumeSplatMapper", name, "cutoff", "cutoff=" + Fixed(cutoff, 0), allThreads };
        c.MakeVolume = splat(backend, probe->GetOrderingMode(), cutoff);
        cases.push_back(c);
      }
      // Image data's sheets composited one by one (SheetMerging off), and its voxels splatted
      // one by one on the screen (SheetResampling off).
      Case sheets{ "vtkVolumeSplatMapper", name, "merging", "merging=off", allThreads };
      sheets.MakeVolume = splat(backend, probe->GetOrderingMode(), 0.0, true, false);
      cases.push_back(sheets);
      Case exact{ "vtkVolumeSplatMapper", name, "sheets", "sheets=off", allThreads };
      exact.MakeVolume = splat(backend, probe->GetOrderingMode(), 0.0, false);
      cases.push_back(exact);
    }
  }
  for (bool gpu : { false, true })
  {
    for (double fraction : { 1.0, 0.25 })
    {
      if (gpu && fraction != 1.0)
      {
        continue; // one row: under llvmpipe its time is the CPU's anyway
      }
      const std::string mapper =
        gpu ? "vtkGPUVolumeRayCastMapper" : "vtkFixedPointVolumeRayCastMapper";
      Case c{ mapper, gpu ? "OpenGL" : "CPU", mapper,
        fraction == 1.0 ? "sample=1 voxel" : "sample=" + Fixed(fraction, 2) + " voxel",
        gpu ? 0 : allThreads };
      c.MakeVolume =
        [gpu, fraction](const VolumeInputs& in) -> vtkSmartPointer<vtkAbstractVolumeMapper>
      {
        return splatexample::RayCaster(
          in.Grid, gpu, fraction * splatexample::SmallestSpacing(in.Grid));
      };
      cases.push_back(c);
    }
  }
  return cases;
}

}

#endif
