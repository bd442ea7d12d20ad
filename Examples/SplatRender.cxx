// SPDX-License-Identifier: BSD-3-Clause
// splat_render: renders a point cloud or a mesh (.ply, .vtp, .xyz, .off) as EWA surface splats,
// or a 3D Gaussian Splatting capture (.ply, compressed .ply, .splat, .spz, .sog or its
// meta.json, .ksplat, .glb, .gltf) or a volume (.nii, .nii.gz, .vti, .mhd, .mha)
// by EWA volume splatting, into a PNG and reports the frame time. Without a file it renders the
// project's demo scenes.
// Run `splat_render --help` for the options.
#include "SplatCaptureCameras.h"
#include "SplatExampleUtilities.h"
#include "SplatFileReaders.h"
#include "SplatRenderOptions.h"
#include "SplatVdbScenes.h"
#include "SplatVolumeScenes.h"
#include "vtkOpenVDBReader.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"
#include "vtkSurfelSphereSource.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using namespace splatrender;
using splatexample::HasExtension;
using splatexample::IsGaussianSplatFile;
using splatexample::IsVolumeFile;
using splatexample::ReadPolyData;
using splatexample::ReadVolume;


// A mapper drawing the surfels vtkSurfelGenerator makes from `data`, with the image
// `options.Texture` acquired onto them when there is one.
vtkSmartPointer<vtkSurfaceSplatMapper> SplatMapper(vtkPolyData* data, const Options& options)
{
  vtkNew<vtkSurfelGenerator> surfels;
  surfels->SetInputData(data);
  surfels->SetRadiusScale(options.RadiusScale);
  surfels->Update();
  if (surfels->GetOutput()->GetNumberOfPoints() == 0)
  {
    throw std::runtime_error("vtkSurfelGenerator made no surfels from the input");
  }
  auto mapper = vtkSmartPointer<vtkSurfaceSplatMapper>::New();
  if (options.Texture.empty())
  {
    mapper->SetInputConnection(surfels->GetOutputPort());
  }
  else
  {
    mapper->SetInputData(splatexample::AcquireTexture(surfels->GetOutput(),
      splatexample::ReadTextureImage(options.Texture), options.Acquisition));
    mapper->ScalarVisibilityOn();
    mapper->SetColorModeToDirectScalars();
  }
  if (options.Cutoff)
  {
    mapper->SetCutoff(*options.Cutoff);
  }
  mapper->SetBackend(options.Backend);
  mapper->SetFilterMode(options.FilterMode);
  return mapper;
}

// `facing` turns the default view about the view up for scenes modeled facing away from +z;
// `bounds` (default: the scene's) is the box the view fits.
void SetUpCamera(
  vtkRenderer* renderer, const Options& options, double facing, const double* bounds = nullptr)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  if (options.ViewDirection)
  {
    // ResetCamera keeps this direction of projection and moves the camera back to fit the scene.
    const Triple& d = *options.ViewDirection;
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(-d[0], -d[1], -d[2]);
  }
  if (options.ViewUp)
  {
    camera->SetViewUp(options.ViewUp->data());
  }
  if (bounds)
  {
    renderer->ResetCamera(bounds);
  }
  else
  {
    renderer->ResetCamera();
  }
  camera->Azimuth(facing + options.Azimuth);
  camera->Elevation(options.Elevation);
  camera->OrthogonalizeViewUp();
  camera->Zoom(options.Zoom);
  renderer->ResetCameraClippingRange();
}

// One window for every scene (see splatexample::MakeOffscreenWindow).
vtkSmartPointer<vtkRenderWindow> MakeWindow(const Options& options)
{
  vtkSmartPointer<vtkRenderWindow> window = splatexample::MakeOffscreenWindow();
  const Triple background = options.Background.value_or(Triple{ 0.1, 0.1, 0.15 });
  window->GetRenderers()->GetFirstRenderer()->SetBackground(background.data());
  window->SetSize(options.Width, options.Height);
  return window;
}

// The median wall-clock and mapper milliseconds of options.Frames frames (to the GPU's
// completion: OpenGL runs asynchronously); `mapperMs` reads the mapper's own time of a frame.
std::pair<double, double> TimeFrames(
  vtkRenderWindow* window, const Options& options, const std::function<double()>& mapperMs)
{
  std::vector<double> frame, mapper;
  for (int i = 0; i < options.Frames; ++i)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    frame.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    mapper.push_back(mapperMs());
  }
  return { splatexample::Median(frame), splatexample::Median(mapper) };
}

// Prints the backend that drew (AUTO resolves per window) with the OpenGL renderer behind it.
void PrintBackend(vtkRenderWindow* window, int backend)
{
  std::cout << "  backend:       " << vtkSplatBackend::GetBackendAsString(backend)
            << " (OpenGL renderer: " << splatexample::OpenGLRenderer(window) << ")\n";
}

// Renders one scene: a warm-up frame, then options.Frames timed frames; prints the figures and
// writes the last frame to `png`.
void RenderScene(vtkRenderWindow* window, vtkSurfaceSplatMapper* mapper, const Options& options,
  const std::string& png, double facing = 0.0)
{
  // Before the work, so that a bad path fails early.
  splatexample::MakeFolder(vtksys::SystemTools::GetFilenamePath(png));
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  Triple color = options.Color.value_or(Triple{ 0.85, 0.75, 0.6 });
  actor->GetProperty()->SetColor(color.data());
  actor->GetProperty()->SetSpecular(0.2);
  actor->GetProperty()->SetSpecularPower(20.0);
  if (options.Color)
  {
    mapper->ScalarVisibilityOff();
  }

  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  renderer->RemoveAllViewProps(); // the previous scene, with its graphics resources
  renderer->AddActor(actor);
  vtkNew<vtkCamera> camera;
  renderer->SetActiveCamera(camera);
  SetUpCamera(renderer, options, facing);

  // The warm-up frame builds the surfel arrays and the OpenGL resources.
  window->Render();
  if (mapper->GetNumberOfSplats() == 0)
  {
    throw std::runtime_error("nothing to draw: no point has a valid position, normal and radius");
  }
  const auto [ms, mapperMs] =
    TimeFrames(window, options, [mapper] { return mapper->GetLastRenderTimeInMilliseconds(); });
  const vtkIdType splats = mapper->GetNumberOfSplats();
  PrintBackend(window, mapper->GetLastBackend());
  std::cout << "  splats:        " << splats << " (";
  // The OpenGL backend culls in its vertex shader without counting (the counts are -1).
  if (mapper->GetNumberOfRenderedSplats() >= 0)
  {
    std::cout << mapper->GetNumberOfRenderedSplats() << " drawn, "
              << mapper->GetNumberOfCulledSplats() << " culled, ";
  }
  std::cout << mapper->GetNumberOfSkippedPoints() << " invalid points skipped)\n"
            << std::fixed << std::setprecision(2) << "  ms per frame:  " << ms << " (median of "
            << options.Frames << " frames, render window); mapper "
            << mapperMs << " (GetLastRenderTimeInMilliseconds"
            // OpenGL runs asynchronously: the mapper's own time need not include the GPU's work.
            << (mapper->GetLastBackend() == vtkSplatBackend::OPENGL ? ", without queued GPU work"
                                                                   : "")
            << ")\n"
            << "  splats per s:  " << std::setprecision(0) << splats / (ms * 1e-3) << "\n";
  splatexample::WritePNG(window, png);
  std::cout << "  image:         " << png << " (" << options.Width << "x" << options.Height << ")"
            << std::endl;
}

// A unit sphere of points with radial normals, colored by a smooth scalar field through a
// cool-to-warm transfer function: shows scalar coloring through the mapper's lookup table.
const vtkIdType SpherePoints = 200000;

vtkSmartPointer<vtkSurfaceSplatMapper> ColoredSphere(const Options& options)
{
  vtkNew<vtkSurfelSphereSource> sphere;
  sphere->SetNumberOfPoints(SpherePoints);
  sphere->SetRadius(1.0);
  sphere->Update();
  vtkPolyData* cloud = sphere->GetOutput();
  vtkNew<vtkFloatArray> wave;
  wave->SetName("Wave");
  wave->SetNumberOfTuples(SpherePoints);
  for (vtkIdType i = 0; i < SpherePoints; ++i)
  {
    double p[3];
    cloud->GetPoint(i, p);
    wave->SetValue(i, static_cast<float>(std::sin(6.0 * p[0]) * std::cos(4.0 * p[1]) + p[2]));
  }
  cloud->GetPointData()->AddArray(wave);

  // vtkSurfelGenerator replaces the source's radii, as for any input, so that --radius-scale
  // applies.
  auto mapper = SplatMapper(cloud, options);
  const double* range = wave->GetRange();
  vtkNew<vtkColorTransferFunction> coolToWarm;
  coolToWarm->SetColorSpaceToDiverging();
  coolToWarm->AddRGBPoint(range[0], 0.231, 0.299, 0.754);
  coolToWarm->AddRGBPoint(range[1], 0.706, 0.016, 0.150);
  mapper->SetLookupTable(coolToWarm);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("Wave");
  mapper->SetScalarRange(range);
  mapper->ScalarVisibilityOn();
  return mapper;
}

// The transfer functions of a volume file: over the scalars' finite range, transparent in the
// lowest fifth (background), then an opacity per `unitDistance` (a voxel's spacing) rising to 0.1
// and a color from dark red through orange to white.
vtkSmartPointer<vtkVolumeProperty> RangeProperty(vtkDataArray* scalars, double unitDistance)
{
  double range[2];
  scalars->GetFiniteRange(range, 0);
  const double span = std::max(range[1] - range[0], 1e-12);
  const double low = range[0] + 0.2 * span;
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(range[0], 0.0);
  opacity->AddPoint(low, 0.0);
  opacity->AddPoint(range[0] + span, 0.1);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(low, 0.5, 0.1, 0.05);
  color->AddRGBPoint(low + 0.4 * span, 0.95, 0.55, 0.3);
  color->AddRGBPoint(range[0] + span, 1.0, 1.0, 0.95);
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetScalarOpacityUnitDistance(unitDistance);
  return property;
}

// The training cameras of the capture options.Input: --cameras, else a cameras.json beside the
// file or one folder up (the INRIA layout keeps the point cloud in
// point_cloud/iteration_N/); empty when there is none.
std::string TrainingCameras(const Options& options)
{
  if (!options.Cameras.empty())
  {
    return options.Cameras;
  }
  std::string folder = vtksys::SystemTools::GetFilenamePath(options.Input);
  for (int up = 0; up < 3; ++up)
  {
    const std::string candidate = (folder.empty() ? std::string(".") : folder) + "/cameras.json";
    if (vtksys::SystemTools::FileExists(candidate, true))
    {
      return candidate;
    }
    folder = vtksys::SystemTools::GetFilenamePath(folder);
  }
  return "";
}

// SetUpCamera fitted to the bulk of `points`, from the 2nd to the 98th percentile along each
// axis: captures hold sparse background Gaussians far out, which would leave the scene a dot.
void PlaceOnBulk(vtkRenderer* renderer, vtkPointSet* points, const Options& options)
{
  double bounds[6];
  std::vector<double> values;
  values.reserve(points->GetNumberOfPoints());
  for (int axis = 0; axis < 3; ++axis)
  {
    values.clear();
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      const double value = points->GetPoint(i)[axis];
      if (std::isfinite(value))
      {
        values.push_back(value);
      }
    }
    if (values.empty())
    {
      throw std::runtime_error("nothing to draw: no point has a finite position");
    }
    for (int side = 0; side < 2; ++side)
    {
      const auto at = values.begin() +
        static_cast<std::ptrdiff_t>((side ? 0.98 : 0.02) * (values.size() - 1));
      std::nth_element(values.begin(), at, values.end());
      bounds[2 * axis + side] = *at;
    }
  }
  SetUpCamera(renderer, options, 0.0, bounds);
}

// Renders a volume (image data, shaded as options.Shade says) or a set of Gaussian kernels like
// RenderScene a surface: `place` sets the camera.
void RenderVolumeScene(vtkRenderWindow* window, vtkDataSet* kernels, vtkVolumeProperty* property,
  const Options& options, const std::string& png,
  const std::function<void(vtkRenderer*)>& place)
{
  splatexample::MakeFolder(vtksys::SystemTools::GetFilenamePath(png));
  vtkSmartPointer<vtkVolumeSplatMapper> mapper = splatexample::VolumeSplat(
    kernels, options.Backend, options.Ordering, options.Cutoff.value_or(0.0));
  mapper->SetFootprintFilter(options.FootprintFilter);
  const bool voxels = vtkImageData::SafeDownCast(kernels) != nullptr;
  if (voxels)
  {
    property->SetShade(options.Shade ? 1 : 0);
  }
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  renderer->RemoveAllViewProps();
  renderer->AddVolume(volume);
  vtkNew<vtkCamera> camera;
  renderer->SetActiveCamera(camera);
  place(renderer);

  // The warm-up frame builds the kernels and their lists.
  window->Render();
  if (mapper->GetNumberOfKernels() == 0)
  {
    throw std::runtime_error(voxels ? "nothing to draw: the transfer function hides every voxel"
                                    : "nothing to draw: every kernel is transparent or invalid");
  }
  const auto [ms, mapperMs] =
    TimeFrames(window, options, [&mapper] { return mapper->GetLastRenderTimeInMilliseconds(); });
  PrintBackend(window, mapper->GetLastBackend());
  const vtkIdType count = mapper->GetNumberOfKernels();
  std::cout << "  kernels:       " << count << " (" << mapper->GetNumberOfTransparentKernels()
            << " transparent " << (voxels ? "voxels" : "kernels") << " left out, "
            << mapper->GetNumberOfInvalidKernels()
            << " invalid; " << splatexample::OrderingModeName(mapper->GetLastOrderingMode())
            << " ordering, lists";
  for (int list = 0; list < 4; ++list)
  {
    if (mapper->GetListTraversed(list))
    {
      std::cout << " " << "XYZD"[list];
    }
  }
  if (mapper->GetNumberOfProjectedKernels() >= 0)
  {
    std::cout << ", " << mapper->GetNumberOfProjectedKernels() << " projected";
  }
  std::cout << "; " << (property->GetShade() ? "shaded" : "unshaded") << ")\n"
            << std::fixed << std::setprecision(2) << "  ms per frame:  " << ms << " (median of "
            << options.Frames << " frames, render window); mapper " << mapperMs << "\n"
            << "  kernels per s: " << std::setprecision(0) << count / (ms * 1e-3) << "\n";
  splatexample::WritePNG(window, png);
  std::cout << "  image:         " << png << " (" << options.Width << "x" << options.Height << ")"
            << std::endl;
}

// Reads the grid of an OpenVDB file that `options` selects; throws when it cannot.
vtkSmartPointer<vtkPolyData> ReadVdbGrid(const std::string& path, const Options& options)
{
  splatexample::RequireFile(path);
  vtkNew<vtkOpenVDBReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetGridName(options.Grid.c_str());
  reader->SetSurfelRadiusScale(options.RadiusScale);
  splatexample::UpdateReader(reader, path);
  std::cout << path << ": OpenVDB, " << reader->GetNumberOfGrids() << " grids" << std::endl;
  for (int i = 0; i < reader->GetNumberOfGrids(); ++i)
  {
    std::cout << "  " << reader->GetGridName(i) << ": " << reader->GetGridClass(i) << ", "
              << reader->GetGridValueType(i) << ", " << reader->GetGridActiveVoxelCount(i)
              << " active voxels" << std::endl;
  }
  return reader->GetOutput();
}

// An OpenVDB file's grid, drawn by what the reader made of it: Gaussian kernels (fog and other
// scalar or vector grids) through FogProperty where the values are densities (none negative:
// the reader's "DensityStatistics"), otherwise RangeProperty with a unit distance of the
// smallest sample's width, framed on all the active voxels (a grid has no stray samples to
// leave out); surfels (level sets) with their own radii; or a point cloud (point grids).
int RenderVdbFile(const Options& options, const std::string& png)
{
  vtkSmartPointer<vtkPolyData> data = ReadVdbGrid(options.Input, options);
  vtkPointData* arrays = data->GetPointData();
  if (vtkDataArray* volumes = arrays->GetArray("SampleVolume"))
  {
    std::cout << "grid '" << (arrays->GetScalars() ? arrays->GetScalars()->GetName() : "")
              << "': " << data->GetNumberOfPoints()
              << " Gaussian kernels, drawn by vtkVolumeSplatMapper" << std::endl;
    const bool densities = data->GetFieldData()->GetArray("DensityStatistics") != nullptr;
    RenderVolumeScene(MakeWindow(options), data,
      densities ? splatexample::FogProperty(data)
                : RangeProperty(arrays->GetScalars(), std::cbrt(volumes->GetRange(0)[0])),
      options, png, [&options](vtkRenderer* renderer) { SetUpCamera(renderer, options, 0.0); });
    return EXIT_SUCCESS;
  }
  if (arrays->GetArray("Radius") && arrays->GetNormals())
  {
    std::cout << "level set: " << data->GetNumberOfPoints()
              << " surfels on its surface, drawn as surface splats" << std::endl;
    vtkNew<vtkSurfaceSplatMapper> mapper;
    mapper->SetInputData(data);
    mapper->SetRadiusArrayName("Radius");
    RenderScene(MakeWindow(options), mapper, options, png);
    return EXIT_SUCCESS;
  }
  std::cout << "point grid: " << data->GetNumberOfPoints()
            << " points, drawn as surface splats" << std::endl;
  RenderScene(MakeWindow(options), SplatMapper(data, options), options, png);
  return EXIT_SUCCESS;
}

int RenderDemoScenes(const Options& given)
{
  // --texture is for the textured scene only: the other meshes have no texture coordinates.
  Options options = given;
  options.Texture.clear();
  const std::string folder = options.OutputDir.value_or("output/demo");
  vtkSmartPointer<vtkRenderWindow> window = MakeWindow(options);
  int images = 0;
  const std::string bunny = splatexample::BunnyFile();
  if (vtksys::SystemTools::FileExists(bunny, true))
  {
    std::cout << "bunny: " << bunny << std::endl;
    RenderScene(window, SplatMapper(ReadPolyData(bunny), options), options, folder + "/bunny.png");
    ++images;
  }
  else if (vtksys::SystemTools::FileExists(splatexample::CgalData, true))
  {
    std::cout << "armadillo: " << bunny << " is absent; using armadillo.off from "
              << splatexample::CgalData << std::endl;
    RenderScene(window, SplatMapper(splatexample::ReadCgalArmadillo(), options), options,
      folder + "/armadillo.png", 180.0);
    ++images;
  }
  else
  {
    std::cout << "mesh scene skipped: neither " << bunny << " nor " << splatexample::CgalData
              << " (Debian package libcgal-demo) is present\n";
  }
  std::cout << "sphere: " << SpherePoints << " points colored by the scalar 'Wave'" << std::endl;
  RenderScene(window, ColoredSphere(options), options, folder + "/sphere.png");
  ++images;
  {
    splatexample::MakeFolder(folder);
    const auto [texture, mesh] = splatexample::WriteTexturedDemo(folder);
    std::cout << "textured: " << mesh << " with " << texture << " (both generated)" << std::endl;
    Options textured = options;
    textured.Texture = given.Texture.empty() ? texture : given.Texture;
    if (!given.ViewDirection && !given.ViewUp) // the sphere's axis is z: seen from the side
    {
      textured.ViewDirection = Triple{ -0.68, -0.68, -0.28 };
      textured.ViewUp = Triple{ 0.0, 0.0, 1.0 };
    }
    RenderScene(window, SplatMapper(splatexample::ReadMesh(mesh), textured), textured,
      folder + "/textured.png");
    ++images;
  }
  if (vtkSmartPointer<vtkImageData> head = splatexample::MriHead(1))
  {
    std::cout << "mri: " << splatexample::MriFile() << ", vtkVolumeSplatMapper" << std::endl;
    RenderVolumeScene(window, head, splatexample::MriFaceProperty(), options,
      folder + "/mri.png",
      [&head](vtkRenderer* renderer) { splatexample::PlaceMriFaceCamera(renderer, head); });
    ++images;
  }
  else
  {
    std::cout << "volume scene skipped: " << splatexample::MriFile()
              << " (Debian package mricron-data) is absent\n";
  }
  const std::string vdb = folder + "/cloud.vdb";
  splatexample::MakeFolder(folder);
  const splatexample::VdbScene cloud = splatexample::WriteCloudVdb(vdb, 500000);
  std::cout << "cloud: " << cloud.ActiveVoxels << " active voxels (" << cloud.Tiles
            << " tiles) of OpenVDB fog written to " << vdb << ", vtkOpenVDBReader and "
            << "vtkVolumeSplatMapper" << std::endl;
  RenderVolumeScene(window, ReadVdbGrid(vdb, options), cloud.Property, options,
    folder + "/cloud.png",
    [&cloud](vtkRenderer* renderer)
    {
      cloud.PlaceCamera(renderer->GetActiveCamera());
      renderer->ResetCameraClippingRange();
    });
  ++images;
  {
    // Drawn as `splat_render smoke.vdb` draws it: the first view of a fog file.
    Options smoke = options;
    smoke.Input = folder + "/smoke.vdb";
    std::cout << "smoke: " << splatexample::WriteSmokeVdb(smoke.Input, 300000)
              << " active voxels of OpenVDB fog written to " << smoke.Input << std::endl;
    RenderVdbFile(smoke, folder + "/smoke.png");
    ++images;
  }
  std::cout << "Wrote " << images << " images to " << vtksys::SystemTools::CollapseFullPath(folder)
            << "\n";
  return EXIT_SUCCESS;
}

int RenderFile(const Options& options)
{
  std::string name = vtksys::SystemTools::GetFilenameWithoutLastExtension(options.Input);
  if (HasExtension(name, ".nii")) // name.nii.gz
  {
    name = vtksys::SystemTools::GetFilenameWithoutLastExtension(name);
  }
  const std::string png =
    options.Output.value_or(options.OutputDir.value_or("output") + "/" + name + ".png");
  if (IsVolumeFile(options.Input))
  {
    vtkSmartPointer<vtkImageData> image = ReadVolume(options.Input);
    const int* dims = image->GetDimensions();
    std::cout << options.Input << ": " << dims[0] << "x" << dims[1] << "x" << dims[2]
              << " voxels" << std::endl;
    RenderVolumeScene(MakeWindow(options), image,
      RangeProperty(image->GetPointData()->GetScalars(), splatexample::SmallestSpacing(image)),
      options, png,
      [&options](vtkRenderer* renderer) { SetUpCamera(renderer, options, 0.0); });
    return EXIT_SUCCESS;
  }
  if (HasExtension(options.Input, ".vdb"))
  {
    return RenderVdbFile(options, png);
  }
  if (IsGaussianSplatFile(options.Input))
  {
    const splatexample::GaussianSplats capture =
      splatexample::ReadGaussianSplats(options.Input, options.SPZFromRUB);
    std::cout << options.Input << ": 3D Gaussian Splatting capture: "
              << capture.Kernels->GetNumberOfPoints() << " Gaussians, SH degree "
              << capture.Degree << ", drawn by vtkVolumeSplatMapper" << std::endl;
    // Unshaded: the captured colors hold the lighting. The kernels' own colors and opacities
    // are drawn (the mapper's Color and Opacity arrays), not transfer functions. On black, as
    // captures are trained, from a training camera where there is one.
    vtkNew<vtkVolumeProperty> property;
    property->ShadeOff();
    Options view = options;
    view.Background = options.Background.value_or(Triple{ 0.0, 0.0, 0.0 });
    const std::string cameras = TrainingCameras(options);
    std::optional<splatexample::TrainingCamera> training;
    if (!cameras.empty())
    {
      training = splatexample::ReadTrainingCamera(cameras, options.Camera);
      std::cout << "  view:          training camera " << options.Camera << " ("
                << (training->Name.empty() ? "unnamed" : training->Name) << ") of " << cameras
                << std::endl;
      if (!options.SizeGiven)
      {
        const double scale = std::min(1.0, 800.0 / std::max(training->Width, training->Height));
        view.Width = std::max(1, static_cast<int>(std::lround(scale * training->Width)));
        view.Height = std::max(1, static_cast<int>(std::lround(scale * training->Height)));
      }
    }
    RenderVolumeScene(MakeWindow(view), capture.Kernels, property, view, png,
      [&view, &capture, &training](vtkRenderer* renderer)
      {
        if (!training)
        {
          PlaceOnBulk(renderer, capture.Kernels, view);
          return;
        }
        training->Apply(renderer->GetActiveCamera());
        renderer->ResetCameraClippingRange();
      });
    return EXIT_SUCCESS;
  }
  vtkSmartPointer<vtkPolyData> data = splatexample::ReadMesh(options.Input);
  std::cout << options.Input << ": mesh/point cloud: " << data->GetNumberOfPoints()
            << " points, " << data->GetNumberOfPolys() << " polygons, drawn as surface splats"
            << std::endl;
  RenderScene(MakeWindow(options), SplatMapper(data, options), options, png);
  return EXIT_SUCCESS;
}
}

int main(int argc, char* argv[])
{
  return splatexample::RunProgram("splat_render",
    [&]
    {
      const Options options = ParseCommandLine(argc, argv);
      return options.Input.empty() ? RenderDemoScenes(options) : RenderFile(options);
    });
}
