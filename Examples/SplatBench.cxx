// SPDX-License-Identifier: BSD-3-Clause
// splat_bench: a benchmark, not a test. Renders the same points with vtkSurfaceSplatMapper (on
// each backend) and with its peer vtkPointGaussianMapper, and the same volumes with
// vtkVolumeSplatMapper (every ordering mode on each backend) and VTK's ray casters (the peer
// vtkFixedPointVolumeRayCastMapper and vtkGPUVolumeRayCastMapper), in the same run, and prints
// one CSV row per case: milliseconds per frame (median), splats per second, the process's peak
// memory so far, what our mapper culled and skipped, the memory per splat that the case added
// and the ratio of the peer's time to the case's.
// Run `splat_bench --help` for the options.
#include "SplatBenchCases.h"
#include "SplatCaptureScene.h"
#include "SplatCommandLine.h"
#include "SplatVdbScenes.h"
#include "SplatExampleUtilities.h"
#include "SplatVolumeScenes.h"
#include "vtkOpenVDBReader.h"
#include "vtkSplatBackend.h"
#include "vtkSplatPLYReader.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"
#include "vtkSurfelSphereSource.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <spawn.h>    // posix_spawn
#include <sys/wait.h> // waitpid

extern char** environ; // for posix_spawn

namespace
{
using namespace splatbench;
using splatexample::ParseCount;
using splatexample::SplitList;
using splatexample::UsageError;

const char* const Usage = R"(Usage: splat_bench [OPTIONS]

Renders points on a unit sphere (Fibonacci sampling, radial normals, radius = sampling spacing)
and the Stanford bunny (vertices through vtkSurfelGenerator) with vtkSurfaceSplatMapper and with
vtkPointGaussianMapper (opaque disks of the same radius, emissive off), and two volumes with
vtkVolumeSplatMapper, vtkFixedPointVolumeRayCastMapper and vtkGPUVolumeRayCastMapper, offscreen,
and prints CSV rows:
  scene,mapper,backend,setting,points,width,height,ms_per_frame,splats_per_s,peak_rss_mb,
  rendered,frustum_culled,backface_culled,negligible,skipped,bytes_per_splat,peer_ratio,drawn_by,
  first_frame_ms
Settings: vtkSurfaceSplatMapper runs on each backend (the CPU rasterizer, then OpenGL) as
"default" (EWA; on the CPU minified splats summed per pixel, the default MinifiedVariance, and
the level of detail) on every scene and, on the sphere (closed, outward normals), also as
"backface" (the actor's BackfaceCulling on); its CPU backend also as "exact" (MinifiedVariance
0: every splat its own kernel) and "no-lod" (LevelOfDetail off: every surfel its own splat), its
OpenGL backend as "approximate" (the APPROXIMATE filter mode); vtkPointGaussianMapper runs as
"disk". Under a software OpenGL renderer (Mesa's llvmpipe) the OpenGL rows measure that
renderer, not a GPU. The first frame of the default CPU row builds the level of detail.
Each case (row) runs in a fresh process of its own: this program again, with --case.
ms_per_frame is the median over the timed frames after one warm-up frame, whose time is
first_frame_ms (kernels, lists, buffers and shaders built there); before each timed frame of a
volume scene the camera turns by half a degree, the transfer function unchanged, so that the
timed frames are the later frames of an interaction; peak_rss_mb is the
peak resident memory (VmHWM) of the case's process, its data included.
rendered .. skipped are vtkSurfaceSplatMapper's counts for the last frame (splats drawn, a
merged splat of the level of detail counting once; culled outside the frustum, culled as back faces, left out as negligible, input points skipped as
invalid); the OpenGL backend culls in its vertex shader without counting, so its splat counts
are -1; empty for vtkPointGaussianMapper, which does not report them.
Volumes: mri is the MRI head ch2.nii.gz (Debian's mricron-data; skipped when absent) with the
transfer functions and camera of TestVolumeSplatCrossRenderer; gaussians is --kernels random
anisotropic 3D Gaussians in the unit ball (fixed seed): a "Covariance" array, a "Color" array
and the peak extinction as scalars through an opacity transfer function. vtkVolumeSplatMapper
runs in every ordering mode (the setting: blended, clipped, single-axis, depth-sorted) on each
backend, and on the CPU in blended mode with SheetResampling off (blended-exact); its points
are its kernels (GetNumberOfKernels: voxels of zero opacity left out), and splats_per_s is
kernels per second. The ray casters (setting "ray cast", one ray per pixel, a
sample every voxel spacing along it) draw the MRI's voxels and, for gaussians, the mixture
resampled onto a --grid^3 RGBA grid over the ball's cube (points: the grid's voxels; the
resampling is not timed; vtkFixedPointVolumeRayCastMapper only: VTK 9.1's
vtkGPUVolumeRayCastMapper draws that grid nearly transparent). For volumes the counts are:
rendered = kernels projected (a kernel counts once per list that splats it), frustum_culled,
backface_culled empty, negligible = kernels of zero opacity (not in the lists), skipped =
invalid kernels plus those reaching the near plane. Volume cases time
at most 3 frames (unless --frames), the volume marked modified before each. 3dgs is a generated 3D Gaussian
Splatting capture of --kernels Gaussians flattened onto a torus (SplatCaptureScene.h: "Scale",
"Rotation", peak "Opacity" and spherical harmonics of degree 3, evaluated for the camera every
frame); it has no peer (VTK draws no view-dependent Gaussians), so its peer_ratio is empty.
vdb is a cloud of --voxels active voxels of OpenVDB fog (SplatVdbScenes.h, written next to the
CSV as cloud.vdb, tiles in its interior), read by vtkOpenVDBReader into one Gaussian kernel per
active voxel (its leaf-sized tiles as their voxels: a lattice, drawn sheet by sheet) for
vtkVolumeSplatMapper and into a dense image of its active bounding box (the reader's second
output) for the ray casters; the reading is not timed.
peer_ratio is the peer's ms_per_frame at the same scene, points and size divided by the row's
(above 1: faster than the peer): vtkPointGaussianMapper for surfaces,
vtkFixedPointVolumeRayCastMapper for volumes. drawn_by is the backend that drew the splat
mappers' last frame (GetLastBackend; an OpenGL request can end up on the CPU).
bytes_per_splat is what a user should plan for per point (per kernel for volumes): the case
process's peak resident memory (VmHWM of /proc/self/status, transient allocations included)
minus the same process's resident memory before the case's data was made (with its window
already rendered once, empty, at the case's size), divided by the points. It counts the data
(points and their arrays; the image or the kernels of volumes), the mapper's own arrays and
frame buffers, the OpenGL driver's copies (in-process under llvmpipe) and one-time costs such
as shader compilation; for the ray casters, the grid they draw (for gaussians, its resampling).
At small counts the per-pixel buffers dominate. A one-line summary per case goes to stderr.

Options (a value follows as --name VALUE or --name=VALUE; lists are comma-separated):
  --scenes LIST        sphere, bunny, mri, gaussians, 3dgs, vdb (default all; bunny and mri
                       are skipped when absent)
  --points LIST        sphere point counts (default 100000,1000000,5000000)
  --kernels N          Gaussians of the gaussians and 3dgs scenes (default 1000000)
  --voxels N           active voxels of the vdb scene's fog (default 1000000)
  --grid N             grid points per axis of the gaussians resampled for the ray casters
                       (default 256)
  --mri-shrink N       the MRI's every N-th voxel per axis, each the mean of its N^3 block
                       (vtkImageShrink3D; default 1)
  --sizes LIST         square image sizes in pixels (default 512,1024)
  --mappers LIST       splat (vtkSurfaceSplatMapper, vtkVolumeSplatMapper), pointgaussian
                       (vtkPointGaussianMapper), fixedpoint (vtkFixedPointVolumeRayCastMapper),
                       gpuraycast (vtkGPUVolumeRayCastMapper) (default all)
  --backends LIST      the splat mappers' backends: cpu, opengl (default: cpu,opengl for the
                       surfaces, cpu for the volumes, whose OpenGL rows are slow under llvmpipe;
                       a list given here applies to both)
  --orderings LIST     vtkVolumeSplatMapper's ordering modes: blended, clipped, single-axis,
                       depth-sorted, blended-exact (CPU only: blended with image data's
                       voxels splatted one by one on the screen, SheetResampling off), and
                       for 3dgs depth-sorted-antialiased and depth-sorted-low-pass (the
                       other footprint filters; every other row of a capture has the
                       dilation it was trained with) (default all)
  --frames N           at most N timed frames per case (default 10, 3 for volumes)
  --budget SECONDS     time a case's frames within this many seconds: after the first timed
                       frame, another is timed only while the elapsed time plus the last
                       frame's stays within the budget (default 10)
  --quick              smoke run: 20000 sphere points, 20000 Gaussians (a 64^3 grid), 50000
                       fog voxels, the MRI
                       shrunk by 2, 256x256, 2 frames
  --scale              the scale run: 20 M sphere points and 20 M Gaussians at 1024x1024,
                       vtkSurfaceSplatMapper and vtkVolumeSplatMapper on the CPU, 3 frames
                       (about 6 GB and 6 minutes on 2 cores)
  --output FILE        CSV file, also written to stdout (default output/bench/bench.csv)
  --image-dir DIR      also write each case's last frame as a PNG into DIR
  --gpu-timings        print the GPU time of each render pass of a case's last timed frame to
                       stderr (vtkRenderWindow's render timer log: OpenGL timer queries)
  --case K             run only the K-th case (from 0, in the order of the rows) of the one
                       scene, size and point count given, in this process, and write its row
                       (peer_ratio empty) to --output: what each case's process runs
  --help               print this help

Environment: SPLAT_DATA_DIR, the folder holding bunny.ply (default: ../shared/data next to the
source tree); SPLAT_MRI_FILE, the MRI (default /usr/share/mricron/templates/ch2.nii.gz).
)";

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

// The handler of an option taking a whole number from `low` to `high` into `target`.
template <typename T>
splatexample::OptionHandler CountInto(T& target, long long low, long long high)
{
  return [&target, low, high](const std::string& name, const std::string& value)
  { target = static_cast<T>(ParseCount(name, value, low, high)); };
}

Options ParseCommandLine(int argc, char* argv[])
{
  Options options;
  const std::map<std::string, splatexample::OptionHandler> handlers = {
    { "--scenes",
      [&](const std::string& name, const std::string& value) {
        options.Scenes = SplitList(
          name, value, { "sphere", "bunny", "mri", "gaussians", "3dgs", "vdb" });
      } },
    { "--points",
      [&](const std::string& name, const std::string& value)
      { options.Points = ParseCounts(name, value, 1, 100000000); } },
    { "--kernels", CountInto(options.Kernels, 1, 100000000) },
    { "--grid", CountInto(options.Grid, 8, 1024) },
    { "--voxels", CountInto(options.Voxels, 1000, 100000000) },
    { "--mri-shrink", CountInto(options.MriShrink, 1, 16) },
    { "--sizes",
      [&](const std::string& name, const std::string& value)
      { options.Sizes = ParseCounts(name, value, 1, 16384); } },
    { "--mappers",
      [&](const std::string& name, const std::string& value) {
        options.Mappers =
          SplitList(name, value, { "splat", "pointgaussian", "fixedpoint", "gpuraycast" });
      } },
    { "--backends",
      [&](const std::string& name, const std::string& value) {
        options.Backends = SplitList(name, value, { "cpu", "opengl" });
        options.VolumeBackends = options.Backends;
      } },
    { "--orderings",
      [&](const std::string& name, const std::string& value) {
        options.Orderings =
          SplitList(name, value,
            { "blended", "clipped", "single-axis", "depth-sorted", "blended-exact",
              "depth-sorted-antialiased", "depth-sorted-low-pass" });
      } },
    { "--frames", CountInto(options.Frames, 1, 100000) },
    { "--budget", CountInto(options.Budget, 0, 86400) },
    { "--output", [&](const std::string&, const std::string& value) { options.Output = value; } },
    { "--image-dir",
      [&](const std::string&, const std::string& value) { options.ImageDir = value; } },
    { "--case", CountInto(options.Case, 0, 100) },
  };

  const std::map<std::string, std::function<void()>> flags = {
    { "--gpu-timings", [&] { options.GpuTimings = true; } },
    { "--quick",
      [&]
      {
        options.Points = { 20000 };
        options.Kernels = 20000;
        options.Grid = 64;
        options.Voxels = 50000;
        options.MriShrink = 2;
        options.Sizes = { 256 };
        options.Frames = 2;
      } },
    { "--scale",
      [&]
      {
        options.Scenes = { "sphere", "gaussians" };
        options.Points = { 20000000 };
        options.Kernels = 20000000;
        options.Sizes = { 1024 };
        options.Mappers = { "splat" };
        options.Backends = options.VolumeBackends = { "cpu" };
        options.Frames = 3;
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
  vtkNew<vtkSplatPLYReader> reader;
  reader->SetFileName(file.c_str());
  vtkNew<vtkSurfelGenerator> surfels;
  surfels->SetInputConnection(reader->GetOutputPort());
  surfels->Update();
  return surfels->GetOutput();
}

bool Chosen(const std::vector<std::string>& list, const std::string& name)
{
  return std::find(list.begin(), list.end(), name) != list.end();
}

// Cases per size of a surface scene, in this order, for the mappers and backends chosen with
// --mappers and --backends: vtkSurfaceSplatMapper's settings on each backend, then the peer.
std::vector<MapperKind> Kinds(const Options& options)
{
  std::vector<MapperKind> kinds;
  if (Chosen(options.Mappers, "splat"))
  {
    for (int backend : splatexample::ChosenSplatBackends(options.Backends))
    {
      const std::string name = vtkSplatBackend::GetBackendAsString(backend);
      const MapperKind splat{ "splat", "vtkSurfaceSplatMapper", name, "default", false, false,
        backend, vtkSurfaceSplatMapper::EWA };
      kinds.push_back(splat);
      // APPROXIMATE is OpenGL only: the CPU would draw EWA again. Minified splats are the
      // CPU's: OpenGL always draws exact kernels.
      if (backend == vtkSplatBackend::OPENGL)
      {
        MapperKind approximate = splat;
        approximate.Setting = "approximate";
        approximate.FilterMode = vtkSurfaceSplatMapper::APPROXIMATE;
        kinds.push_back(approximate);
      }
      else
      {
        MapperKind exact = splat;
        exact.Setting = "exact";
        exact.ExactKernels = true;
        kinds.push_back(exact);
        MapperKind flat = splat;
        flat.Setting = "no-lod";
        flat.LevelOfDetail = false;
        kinds.push_back(flat);
      }
      MapperKind backface = splat;
      backface.Setting = "backface";
      backface.BackfaceCulling = backface.ClosedOnly = true;
      kinds.push_back(backface);
    }
  }
  if (Chosen(options.Mappers, "pointgaussian"))
  {
    kinds.push_back({ "pointgaussian", "vtkPointGaussianMapper", "OpenGL", "disk" });
  }
  return kinds;
}

// Cases per size of a volume scene: vtkVolumeSplatMapper in every ordering mode on each
// backend (for a capture also its depth order with the antialiased and low-pass filters), then
// the ray casters (the first, vtkFixedPointVolumeRayCastMapper, is the peer).
std::vector<MapperKind> VolumeKinds(const Options& options, bool capture)
{
  std::vector<MapperKind> kinds;
  if (Chosen(options.Mappers, "splat"))
  {
    for (int backend : splatexample::ChosenSplatBackends(options.VolumeBackends))
    {
      for (int mode : splatexample::OrderingModes())
      {
        if (!Chosen(options.Orderings, splatexample::OrderingModeName(mode)))
        {
          continue;
        }
        MapperKind kind{ "splat", "vtkVolumeSplatMapper",
          vtkSplatBackend::GetBackendAsString(backend), splatexample::OrderingModeName(mode) };
        kind.SplatBackend = backend;
        kind.Ordering = mode;
        kinds.push_back(kind);
      }
      for (const int filter :
        { vtkVolumeSplatMapper::ANTIALIASED_FILTER, vtkVolumeSplatMapper::LOW_PASS_FILTER })
      {
        const std::string setting = std::string("depth-sorted-") +
          (filter == vtkVolumeSplatMapper::LOW_PASS_FILTER ? "low-pass" : "antialiased");
        if (!capture || !Chosen(options.Orderings, setting))
        {
          continue;
        }
        MapperKind kind{ "splat", "vtkVolumeSplatMapper",
          vtkSplatBackend::GetBackendAsString(backend), setting };
        kind.SplatBackend = backend;
        kind.Ordering = vtkVolumeSplatMapper::DEPTH_SORTED;
        kind.FootprintFilter = filter;
        kinds.push_back(kind);
      }
      // The CPU's default ordering without the sheets: every voxel splatted on the screen.
      if (backend == vtkSplatBackend::CPU && Chosen(options.Orderings, "blended-exact"))
      {
        MapperKind kind{ "splat", "vtkVolumeSplatMapper", "CPU", "blended-exact" };
        kind.SplatBackend = backend;
        kind.ExactKernels = true;
        kinds.push_back(kind);
      }
    }
  }
  if (Chosen(options.Mappers, "fixedpoint"))
  {
    kinds.push_back({ "fixedpoint", "vtkFixedPointVolumeRayCastMapper", "CPU", "ray cast" });
  }
  if (Chosen(options.Mappers, "gpuraycast"))
  {
    kinds.push_back({ "gpuraycast", "vtkGPUVolumeRayCastMapper", "OpenGL", "ray cast" });
  }
  return kinds;
}

// The cases of a scene, in the order they run: the backface setting only on the sphere (closed,
// outward-oriented); the ray casters only where the scene has a grid for them (not 3dgs), and
// vtkGPUVolumeRayCastMapper not on gaussians (VTK 9.1's draws that RGBA grid nearly
// transparent, see splatexample::ResampleMixture).
std::vector<MapperKind> SceneKinds(const std::string& scene, const Options& options)
{
  const bool surface = scene == "sphere" || scene == "bunny";
  const bool grid = scene != "3dgs";
  const bool gpuGrid = scene == "mri" || scene == "vdb";
  std::vector<MapperKind> kinds =
    surface ? Kinds(options) : VolumeKinds(options, scene == "3dgs");
  const auto drawn = [&](const MapperKind& kind)
  {
    return surface ? !kind.ClosedOnly || scene == "sphere"
                   : kind.Name == "splat" ||
        (grid && (kind.Name == "fixedpoint" || (kind.Name == "gpuraycast" && gpuGrid)));
  };
  kinds.erase(std::remove_if(kinds.begin(), kinds.end(), std::not_fn(drawn)), kinds.end());
  return kinds;
}

// The MapperKind::Name whose time a scene's peer_ratio column divides ("": no peer).
std::string ScenePeer(const std::string& scene)
{
  if (scene == "sphere" || scene == "bunny")
  {
    return "pointgaussian";
  }
  return scene == "3dgs" ? "" : "fixedpoint";
}

vtkSmartPointer<vtkMapper> MakeMapper(const MapperKind& kind, vtkPolyData* surfels)
{
  if (kind.Name == "splat")
  {
    vtkNew<vtkSurfaceSplatMapper> mapper;
    mapper->SetInputData(surfels);
    mapper->SetBackend(kind.SplatBackend);
    mapper->SetFilterMode(kind.FilterMode);
    if (kind.ExactKernels)
    {
      mapper->SetMinifiedVariance(0.0);
    }
    mapper->SetLevelOfDetail(kind.LevelOfDetail);
    return mapper;
  }
  return splatexample::PointGaussianDisks(surfels);
}

// A surface scene: the points made by makeData, an actor, the camera framing the points.
Scene SurfaceScene(const std::string& name,
  const std::function<vtkSmartPointer<vtkPolyData>()>& makeData, const Options& options)
{
  Scene scene;
  scene.Name = name;
  scene.Kinds = SceneKinds(name, options);
  scene.Make = [makeData](const MapperKind& kind)
  {
    vtkSmartPointer<vtkPolyData> surfels = makeData();
    vtkNew<vtkActor> actor;
    actor->SetMapper(MakeMapper(kind, surfels));
    actor->GetProperty()->SetColor(0.85, 0.75, 0.6);
    actor->GetProperty()->SetBackfaceCulling(kind.BackfaceCulling);
    return Stage{ actor.Get(), surfels };
  };
  // The same view for both mappers: their bounds differ (ours include the splat radii).
  scene.Place = [](vtkRenderer* renderer, const Stage& stage)
  { renderer->ResetCamera(stage.Data->GetBounds()); };
  return scene;
}

// A volume scene: vtkVolumeSplatMapper draws `kernels` (image data or a point set of Gaussians)
// with `property`; the ray casters (SceneKinds says which) draw the grid of makeGrid with its
// property (made on their first use), sampled along their rays at the grid's spacing.
Scene VolumeScene(const std::string& name, vtkDataSet* kernels, vtkVolumeProperty* property,
  const std::function<splatexample::ResampledVolume()>& makeGrid,
  const std::function<void(vtkRenderer*)>& place, const Options& options)
{
  Scene scene;
  scene.Name = name;
  scene.Kinds = SceneKinds(name, options);
  scene.Frames = 3; // TestVolumeSplatCrossRenderer's three frames after the first
  vtkSmartPointer<vtkDataSet> data = kernels;
  vtkSmartPointer<vtkVolumeProperty> splatProperty = property;
  auto grid = std::make_shared<splatexample::ResampledVolume>();
  scene.Make = [=](const MapperKind& kind)
  {
    vtkNew<vtkVolume> volume;
    if (kind.Name == "splat")
    {
      vtkSmartPointer<vtkVolumeSplatMapper> mapper = splatexample::VolumeSplat(
        data, kind.SplatBackend, kind.Ordering, 0.0, !kind.ExactKernels);
      mapper->SetFootprintFilter(kind.FootprintFilter);
      volume->SetMapper(mapper);
      volume->SetProperty(splatProperty);
      return Stage{ volume.Get(), data };
    }
    if (!grid->Image)
    {
      *grid = makeGrid();
    }
    volume->SetMapper(splatexample::RayCaster(grid->Image, kind.Name == "gpuraycast",
      splatexample::SmallestSpacing(grid->Image)));
    volume->SetProperty(grid->Property);
    volume->SetUserMatrix(grid->UserMatrix);
    return Stage{ volume.Get(), grid->Image };
  };
  scene.Place = [place](vtkRenderer* renderer, const Stage&) { place(renderer); };
  return scene;
}

// Runs case options.Case of the one scene, size and point count on the command line in this
// process and writes its CSV row to options.Output (see MeasureOneCase); the resident set before
// the scene's data is made, with the window already rendered at the size, is the baseline of the
// case's memory.
int RunOneCase(const Options& options)
{
  if (options.Scenes.size() != 1 || options.Sizes.size() != 1 || options.Points.size() != 1)
  {
    throw UsageError("--case needs one scene, one size and one point count");
  }
  std::ofstream csv(options.Output);
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + options.Output + "'");
  }
  vtkSmartPointer<vtkRenderWindow> window = splatexample::MakeOffscreenWindow();
  window->GetRenderers()->GetFirstRenderer()->SetBackground(0.1, 0.1, 0.15);
  const int size = static_cast<int>(options.Sizes.front());
  window->SetSize(size, size);
  window->Render();
  window->WaitForCompletion();
  const long long baseline = ProcessStatusBytes("VmRSS");
  const std::string& scene = options.Scenes.front();
  if (scene == "bunny")
  {
    const std::string bunny = splatexample::BunnyFile();
    MeasureOneCase(window,
      SurfaceScene("bunny", [&]() { return BunnySurfels(bunny); }, options), options, csv,
      baseline);
  }
  else if (scene == "sphere")
  {
    const auto n = static_cast<vtkIdType>(options.Points.front());
    MeasureOneCase(window, SurfaceScene("sphere", [n]() { return UnitSphere(n); }, options),
      options, csv, baseline);
  }
  else if (scene == "mri")
  {
    vtkSmartPointer<vtkImageData> head = splatexample::MriHead(options.MriShrink);
    if (!head)
    {
      throw std::runtime_error("cannot read " + splatexample::MriFile());
    }
    MeasureOneCase(window,
      VolumeScene("mri", head, splatexample::MriProperty(),
        [&]() { return splatexample::ResampledVolume{ head, splatexample::MriProperty() }; },
        [&](vtkRenderer* renderer) { splatexample::PlaceMriCamera(renderer, head); }, options),
      options, csv, baseline);
  }
  else if (scene == "gaussians")
  {
    vtkSmartPointer<vtkPolyData> kernels =
      splatexample::RandomGaussians(static_cast<vtkIdType>(options.Kernels));
    vtkSmartPointer<vtkVolumeProperty> property = splatexample::GaussiansProperty(kernels);
    const auto resample = [&]()
    {
      std::cerr << "splat_bench: gaussians: resampling onto " << options.Grid << "^3 voxels\n";
      return splatexample::ResampleMixture(
        splatexample::MixtureOf(kernels, property), static_cast<int>(options.Grid));
    };
    MeasureOneCase(window,
      VolumeScene(
        "gaussians", kernels, property, resample, splatexample::PlaceGaussiansCamera, options),
      options, csv, baseline);
  }
  else if (scene == "3dgs")
  {
    vtkSmartPointer<vtkPolyData> capture =
      splatexample::SyntheticCapture(static_cast<vtkIdType>(options.Kernels), 3);
    // The kernels' own colors and peak opacities: the transfer functions are not used.
    vtkNew<vtkVolumeProperty> property;
    MeasureOneCase(window,
      VolumeScene("3dgs", capture, property, {}, splatexample::PlaceCaptureCamera, options),
      options, csv, baseline);
  }
  else if (scene == "vdb")
  {
    const std::string file =
      vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(options.Output)) +
      "/cloud.vdb";
    const splatexample::VdbScene cloud =
      splatexample::WriteCloudVdb(file, static_cast<vtkIdType>(options.Voxels));
    std::cerr << "splat_bench: vdb: " << cloud.ActiveVoxels << " active voxels (" << cloud.Tiles
              << " tiles) in " << file << "\n";
    vtkNew<vtkOpenVDBReader> reader;
    reader->SetFileName(file.c_str());
    reader->ProduceDenseOutputOn();
    reader->Update();
    vtkSmartPointer<vtkPolyData> kernels = reader->GetOutput();
    vtkSmartPointer<vtkImageData> dense = reader->GetDenseOutput();
    if (kernels->GetNumberOfPoints() == 0 || dense->GetNumberOfPoints() == 0)
    {
      throw std::runtime_error("vtkOpenVDBReader could not read " + file);
    }
    MeasureOneCase(window,
      VolumeScene("vdb", kernels, cloud.Property,
        [&]() { return splatexample::AxisAlignedGrid(dense, cloud.Property); },
        [&cloud](vtkRenderer* renderer)
        {
          cloud.PlaceCamera(renderer->GetActiveCamera());
          renderer->ResetCameraClippingRange();
        },
        options),
      options, csv, baseline);
  }
  return EXIT_SUCCESS;
}

// Splits a CSV row (no quoting: the bench's fields hold no commas).
std::vector<std::string> CsvFields(const std::string& row)
{
  std::vector<std::string> fields;
  std::istringstream stream(row);
  std::string field;
  while (std::getline(stream, field, ','))
  {
    fields.push_back(field);
  }
  if (!row.empty() && row.back() == ',')
  {
    fields.emplace_back();
  }
  return fields;
}

// Runs this program again with `arguments` and waits for it; returns its exit status (-1 when it
// could not start or was killed).
int RunSelf(const std::vector<std::string>& arguments)
{
  const std::string self = vtksys::SystemTools::GetRealPath("/proc/self/exe");
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(self.c_str()));
  for (const std::string& argument : arguments)
  {
    argv.push_back(const_cast<char*>(argument.c_str()));
  }
  argv.push_back(nullptr);
  pid_t child = 0;
  if (posix_spawn(&child, self.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
  {
    return -1;
  }
  int status = 0;
  if (waitpid(child, &status, 0) != child || !WIFEXITED(status))
  {
    return -1;
  }
  return WEXITSTATUS(status);
}

// Runs every case in a fresh process of its own (this program with --case), so that each row's
// memory is the case's alone, and writes the rows with the peer's time ratio filled in: a
// scene's rows at a size once its peer has run. `arguments` is the command line, to which each
// case's scene, size, point count, case and output are appended (later options win).
int RunCases(const Options& options, const std::vector<std::string>& arguments)
{
  splatexample::MakeFolder(vtksys::SystemTools::GetFilenamePath(options.Output));
  splatexample::MakeFolder(options.ImageDir);
  std::ofstream csv(options.Output);
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + options.Output + "'");
  }
  // The required columns first, then the culling counts, the memory per splat, the ratio to
  // the peer and the backend that drew.
  const char* const header =
    "scene,mapper,backend,setting,points,width,height,ms_per_frame,splats_per_s,peak_rss_mb,"
    "rendered,frustum_culled,backface_culled,negligible,skipped,bytes_per_splat,peer_ratio,"
    "drawn_by,first_frame_ms\n";
  std::cout << header << std::flush;
  csv << header << std::flush;

  const std::string caseOutput = options.Output + ".case";
  int rows = 0;
  for (const std::string scene : { "bunny", "sphere", "mri", "gaussians", "3dgs", "vdb" })
  {
    if (!Chosen(options.Scenes, scene))
    {
      continue;
    }
    if (scene == "bunny" && !vtkSplatPLYReader::CanReadFile(splatexample::BunnyFile().c_str()))
    {
      std::cerr << "splat_bench: bunny skipped: " << splatexample::BunnyFile()
                << " is absent or unreadable\n";
      continue;
    }
    if (scene == "mri" && !vtksys::SystemTools::FileExists(splatexample::MriFile()))
    {
      std::cerr << "splat_bench: mri skipped: " << splatexample::MriFile()
                << " is absent (Debian package mricron-data)\n";
      continue;
    }
    const std::vector<MapperKind> kinds = SceneKinds(scene, options);
    const std::string peer = ScenePeer(scene);
    // Only the sphere's point count varies; the others take theirs from --kernels or the data.
    const std::vector<long long> points =
      scene == "sphere" ? options.Points : std::vector<long long>{ options.Points.front() };
    for (long long n : points)
    {
      for (long long size : options.Sizes)
      {
        std::vector<std::vector<std::string>> results;
        double peerMilliseconds = 0.0;
        for (std::size_t k = 0; k < kinds.size(); ++k)
        {
          std::vector<std::string> caseArguments = arguments;
          caseArguments.insert(caseArguments.end(),
            { "--scenes", scene, "--points", std::to_string(n), "--sizes", std::to_string(size),
              "--case", std::to_string(k), "--output", caseOutput });
          vtksys::SystemTools::RemoveFile(caseOutput);
          const int status = RunSelf(caseArguments);
          std::ifstream row(caseOutput);
          std::string line;
          if (status != 0 || !std::getline(row, line))
          {
            std::cerr << "splat_bench: " << scene << " " << kinds[k].Class << " ("
                      << kinds[k].Backend << ", " << kinds[k].Setting
                      << ") failed: exit status " << status << "\n";
            continue;
          }
          results.push_back(CsvFields(line));
          if (kinds[k].Name == peer)
          {
            peerMilliseconds = std::stod(results.back()[7]);
          }
        }
        for (std::vector<std::string>& fields : results)
        {
          const double ms = std::stod(fields[7]);
          if (peerMilliseconds > 0.0 && ms > 0.0)
          {
            std::ostringstream ratio;
            ratio << std::fixed << std::setprecision(3) << peerMilliseconds / ms;
            fields[16] = ratio.str();
          }
          std::string row;
          for (std::size_t f = 0; f < fields.size(); ++f)
          {
            row += (f > 0 ? "," : "") + fields[f];
          }
          std::cout << row << "\n" << std::flush;
          csv << row << "\n" << std::flush;
          ++rows;
        }
      }
    }
  }
  vtksys::SystemTools::RemoveFile(caseOutput);
  // What drew the OpenGL rows, as the cases' processes saw it.
  vtkSmartPointer<vtkRenderWindow> probe = splatexample::MakeOffscreenWindow();
  probe->Render();
  std::cerr << "splat_bench: " << rows << " rows; CSV written to "
            << vtksys::SystemTools::CollapseFullPath(options.Output)
            << " (OpenGL renderer: " << splatexample::OpenGLRenderer(probe) << ")\n";
  return rows > 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
}

int main(int argc, char* argv[])
{
  return splatexample::RunProgram("splat_bench",
    [&]
    {
      const Options options = ParseCommandLine(argc, argv);
      return options.Case >= 0 ? RunOneCase(options)
                               : RunCases(options, std::vector<std::string>(argv + 1, argv + argc));
    });
}
