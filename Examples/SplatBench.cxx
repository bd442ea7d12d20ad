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
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>


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
"default" (exact EWA) on every scene and, on the sphere (closed, outward normals), also as
"backface" (the actor's BackfaceCulling on); its OpenGL backend also as "approximate" (the
APPROXIMATE filter mode); vtkPointGaussianMapper runs as "disk". Under a software OpenGL
renderer (Mesa's llvmpipe) the OpenGL rows measure that renderer, not a GPU.
ms_per_frame is the median over the timed frames after one warm-up frame, whose time is
first_frame_ms (kernels, lists, buffers and shaders built there); before each timed frame of a
volume scene the camera turns by half a degree, the transfer function unchanged, so that the
timed frames are the later frames of an interaction; peak_rss_mb is the
peak resident memory of the whole process so far (cases run from small to large).
rendered .. skipped are vtkSurfaceSplatMapper's counts for the last frame (splats drawn, culled
outside the frustum, culled as back faces, left out as negligible, input points skipped as
invalid); the OpenGL backend culls in its vertex shader without counting, so its splat counts
are -1; empty for vtkPointGaussianMapper, which does not report them.
Volumes: mri is the MRI head ch2.nii.gz (Debian's mricron-data; skipped when absent) with the
transfer functions and camera of TestVolumeSplatCrossRenderer; gaussians is --kernels random
anisotropic 3D Gaussians in the unit ball (fixed seed): a "Covariance" array, a "Color" array
and the peak extinction as scalars through an opacity transfer function. vtkVolumeSplatMapper
runs in every ordering mode (the setting: blended, clipped, single-axis, depth-sorted) on each
backend; its points are its kernels (GetNumberOfKernels: voxels of zero opacity left out), and
splats_per_s is kernels per second. The ray casters (setting "ray cast", one ray per pixel, a
sample every voxel spacing along it) draw the MRI's voxels and, for gaussians, the mixture
resampled onto a --grid^3 RGBA grid over the ball's cube (points: the grid's voxels; the
resampling is not timed; vtkFixedPointVolumeRayCastMapper only: VTK 9.1's
vtkGPUVolumeRayCastMapper draws that grid nearly transparent). For volumes the counts are:
rendered = kernels projected (a kernel counts once per list that splats it), frustum_culled,
backface_culled empty, negligible = kernels of zero opacity (not in the lists), skipped =
invalid kernels plus those reaching the near plane; the volume data is made once per scene,
so bytes_per_splat is the mapper's memory (kernel lists, buffers) per kernel. Volume cases time
at most 3 frames, the volume marked modified before each. 3dgs is a generated 3D Gaussian
Splatting capture of --kernels Gaussians flattened onto a torus (SplatCaptureScene.h: "Scale",
"Rotation", peak "Opacity" and spherical harmonics of degree 3, evaluated for the camera every
frame); it has no peer (VTK draws no view-dependent Gaussians), so its peer_ratio is empty.
vdb is a cloud of --voxels active voxels of OpenVDB fog (SplatVdbScenes.h, written next to the
CSV as cloud.vdb, tiles in its interior), read by vtkOpenVDBReader into one Gaussian kernel per
active voxel (tiles as 2^3 kernels each) for vtkVolumeSplatMapper and into a dense image of its
active bounding box (the reader's second output) for the ray casters; the reading is not timed.
peer_ratio is the peer's ms_per_frame at the same scene, points and size divided by the row's
(above 1: faster than the peer): vtkPointGaussianMapper for surfaces,
vtkFixedPointVolumeRayCastMapper for volumes. drawn_by is the backend that drew the splat
mappers' last frame (GetLastBackend; an OpenGL request can end up on the CPU).
bytes_per_splat is the resident memory the case added (its data, mapper and frames) per point:
the current resident set size (/proc/self/statm) after the case's frames minus the one before
its data was built, divided by the number of points. A one-line summary per case goes to stderr.

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
                       depth-sorted (default all)
  --frames N           at most N timed frames per case (default 10)
  --budget SECONDS     time a case's frames within this many seconds: after the first timed
                       frame, another is timed only while the elapsed time plus the last
                       frame's stays within the budget (default 10)
  --quick              smoke run: 20000 sphere points, 20000 Gaussians (a 64^3 grid), 50000
                       fog voxels, the MRI
                       shrunk by 2, 256x256, 2 frames
  --output FILE        CSV file, also written to stdout (default output/bench/bench.csv)
  --image-dir DIR      also write each case's last frame as a PNG into DIR
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
          SplitList(name, value, { "blended", "clipped", "single-axis", "depth-sorted" });
      } },
    { "--frames", CountInto(options.Frames, 1, 100000) },
    { "--budget", CountInto(options.Budget, 0, 86400) },
    { "--output", [&](const std::string&, const std::string& value) { options.Output = value; } },
    { "--image-dir",
      [&](const std::string&, const std::string& value) { options.ImageDir = value; } },
  };

  const std::map<std::string, std::function<void()>> flags = {
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
  if (Chosen(options.Mappers, "pointgaussian"))
  {
    kinds.push_back({ "pointgaussian", "vtkPointGaussianMapper", "OpenGL", "disk" });
  }
  return kinds;
}

// Cases per size of a volume scene: vtkVolumeSplatMapper in every ordering mode on each
// backend, then the ray casters (the first, vtkFixedPointVolumeRayCastMapper, is the peer).
std::vector<MapperKind> VolumeKinds(const Options& options)
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

// A surface scene: the points made afresh for every case by makeData (so that the case's memory
// includes them), an actor, the camera framing the points.
Scene SurfaceScene(const std::string& name, bool closed,
  const std::function<vtkSmartPointer<vtkPolyData>()>& makeData, const Options& options)
{
  Scene scene;
  scene.Name = name;
  scene.Closed = closed;
  scene.Kinds = Kinds(options);
  scene.Peer = "pointgaussian";
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
// with `property`; the ray casters draw the grid of makeGrid with its property (made on first
// use, then kept: resampling the Gaussians takes a while), sampled along their rays at the
// grid's spacing; vtkGPUVolumeRayCastMapper only where `gpuRayCaster`; without makeGrid, no ray
// caster and no peer. The data is made once, outside the cases: bytes_per_splat counts the
// mapper and its frames.
Scene VolumeScene(const std::string& name, vtkDataSet* kernels, vtkVolumeProperty* property,
  const std::function<splatexample::ResampledVolume()>& makeGrid,
  const std::function<void(vtkRenderer*)>& place, bool gpuRayCaster, const Options& options)
{
  Scene scene;
  scene.Name = name;
  scene.Kinds = VolumeKinds(options);
  const auto drawn = [&](const MapperKind& kind)
  {
    return kind.Name == "splat" ||
      (makeGrid && (kind.Name == "fixedpoint" || (kind.Name == "gpuraycast" && gpuRayCaster)));
  };
  scene.Kinds.erase(
    std::remove_if(scene.Kinds.begin(), scene.Kinds.end(), std::not_fn(drawn)), scene.Kinds.end());
  scene.Peer = makeGrid ? "fixedpoint" : "";
  scene.Frames = 3; // TestVolumeSplatCrossRenderer's three frames after the first
  vtkSmartPointer<vtkDataSet> data = kernels;
  vtkSmartPointer<vtkVolumeProperty> splatProperty = property;
  auto grid = std::make_shared<splatexample::ResampledVolume>();
  scene.Make = [=](const MapperKind& kind)
  {
    vtkNew<vtkVolume> volume;
    if (kind.Name == "splat")
    {
      volume->SetMapper(splatexample::VolumeSplat(data, kind.SplatBackend, kind.Ordering));
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

int Run(const Options& options)
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

  // One window for every case (see splatexample::MakeOffscreenWindow); each scene sets its size.
  vtkSmartPointer<vtkRenderWindow> window = splatexample::MakeOffscreenWindow();
  window->GetRenderers()->GetFirstRenderer()->SetBackground(0.1, 0.1, 0.15);

  // The process's peak memory only grows: the small bunny first, then the spheres by size, then
  // the volumes.
  const auto wants = [&](const char* scene) { return Chosen(options.Scenes, scene); };
  int rows = 0;
  if (wants("bunny"))
  {
    const std::string bunny = splatexample::BunnyFile();
    if (vtkSplatPLYReader::CanReadFile(bunny.c_str()))
    {
      // The bunny has holes (its base): no backface setting.
      rows += MeasureScene(window,
        SurfaceScene("bunny", false, [&]() { return BunnySurfels(bunny); }, options), options,
        csv);
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
      rows += MeasureScene(window,
        SurfaceScene(
          "sphere", true, [n]() { return UnitSphere(static_cast<vtkIdType>(n)); }, options),
        options, csv);
    }
  }
  if (wants("mri"))
  {
    if (vtkSmartPointer<vtkImageData> head = splatexample::MriHead(options.MriShrink))
    {
      rows += MeasureScene(window,
        VolumeScene("mri", head, splatexample::MriProperty(),
          [&]() { return splatexample::ResampledVolume{ head, splatexample::MriProperty() }; },
          [&](vtkRenderer* renderer) { splatexample::PlaceMriCamera(renderer, head); }, true,
          options),
        options, csv);
    }
    else
    {
      std::cerr << "splat_bench: mri skipped: " << splatexample::MriFile()
                << " is absent (Debian package mricron-data)\n";
    }
  }
  if (wants("gaussians"))
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
    // Not vtkGPUVolumeRayCastMapper: VTK 9.1's draws the RGBA grid (dependent components) nearly
    // transparent (see splatexample::ResampleMixture).
    rows += MeasureScene(window,
      VolumeScene("gaussians", kernels, property, resample, splatexample::PlaceGaussiansCamera,
        false, options),
      options, csv);
  }
  if (wants("3dgs"))
  {
    vtkSmartPointer<vtkPolyData> capture =
      splatexample::SyntheticCapture(static_cast<vtkIdType>(options.Kernels), 3);
    // The kernels' own colors and peak opacities: the transfer functions are not used.
    vtkNew<vtkVolumeProperty> property;
    rows += MeasureScene(window,
      VolumeScene("3dgs", capture, property, {}, splatexample::PlaceCaptureCamera, false, options),
      options, csv);
  }
  if (wants("vdb"))
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
    rows += MeasureScene(window,
      VolumeScene("vdb", kernels, cloud.Property,
        [&]() { return splatexample::AxisAlignedGrid(dense, cloud.Property); },
        [&cloud](vtkRenderer* renderer)
        {
          cloud.PlaceCamera(renderer->GetActiveCamera());
          renderer->ResetCameraClippingRange();
        },
        true, options),
      options, csv);
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
