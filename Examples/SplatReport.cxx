// SPDX-License-Identifier: BSD-3-Clause
// splat_report: the error-against-run-time report. Renders each scene with every quality setting
// of vtkSurfaceSplatMapper and with the peer vtkPointGaussianMapper, times each (median ms per
// frame), measures each image's error against a reference (RMSE and PSNR, OpenImageIO), and
// writes a CSV, a Markdown table, a plot (VTK charts) and every image as PNG.
//
// Scenes:
// - checkerboard: a checkerboard plane seen at a grazing angle (paper 000, figure 8): strong
//   magnification near the camera, strong minification toward the horizon. The reference is
//   analytic: per pixel, the exact checkerboard on exact ray/plane intersections, supersampled
//   (each sub-sample the checkerboard's exact average over its footprint on the plane) and
//   weighted by the screen low-pass filter of EWA (a Gaussian of unit variance in pixels,
//   truncated at 3 sigma). The splats are a regular grid of surfels colored with the
//   checkerboard's exact average over their grid cells (a box prefilter). The scene and its
//   reference are in SplatCheckerboardScene.h and SplatCheckerboardReference.h, shared with
//   TestSurfaceSplatCheckerboardError.
// - bunny, bunny-closeup, armadillo, armadillo-closeup, armadillo-points, sphere: meshes (two
//   scans, each seen whole and magnified, the armadillo also from a point cloud scattered over
//   it, and a sphere of --points vertices seen whole; SplatReportMeshes.h); the reference is the
//   mesh drawn by vtkPolyDataMapper at 4x4 supersampling (4x the size, 4x4 blocks averaged); the
//   splats come from vtkSurfelGenerator.
// - mri, gaussians, vdb: volumes (SplatVolumeScenes.h, SplatVdbScenes.h) drawn by
//   vtkVolumeSplatMapper in every ordering
//   mode and with other cutoffs, and by VTK's ray casters; the reference integrates the same
//   Gaussian mixture by fine ray marching (SplatVolumeReference.h).
//
// Run `splat_report --help` for the options.
#include "SplatCheckerboardReference.h"
#include "SplatCommandLine.h"
#include "SplatExampleUtilities.h"
#include "SplatReportCaptures.h"
#include "SplatReportCases.h"
#include "SplatReportImages.h"
#include "SplatReportDifferentialPoints.h"
#include "SplatReportMeshes.h"
#include "SplatReportOutput.h"
#include "SplatReportStability.h"
#include "SplatReportTexture.h"
#include "SplatVdbScenes.h"
#include "SplatVolumeReference.h"
#include "SplatVolumeScenes.h"
#include "vtkOpenVDBReader.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkVolumeSplatMapper.h"

#include <vtksys/SystemTools.hxx>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using namespace splatreport;
using splatexample::CaptureWindow;
using splatexample::Checkerboard;
using splatexample::CheckerboardReferences;
using splatexample::CheckerboardSurfels;
using splatexample::ParseCount;
using splatexample::StyleCheckerboardActor;
using splatexample::UsageError;

const char* const Usage = R"(Usage: splat_report [OPTIONS]

The error-against-run-time report: renders each scene with every quality setting of
vtkSurfaceSplatMapper (the default, then one setting changed at a time: cutoff, filter mode,
number of A-buffer layers, edge antialiasing, thread count), on the CPU backend and again on the
OpenGL backend (the same settings, plus the approximate filter mode; no thread counts), and with
vtkPointGaussianMapper (opaque disks of the surfels' radius; Gaussians of the surfels'
variance), offscreen, and measures each image against a reference:
  checkerboard  a checkerboard plane at a grazing angle (paper 000, figure 8), about 1 M surfels
                on a regular grid; analytic reference (exact ray/plane intersections, 16x16
                sub-samples per pixel, unit-variance Gaussian pixel filter)
  textured-plane  the checkerboard as a texture acquired onto jittered surfels (at most 250 000)
                by vtkSurfelTextureAcquisition's three modes, checks 4 and 0.6 spacings wide;
                the analytic reference; acquisition time per surfel (SplatReportTexture.h)
  bunny         the Stanford bunny seen whole; reference: the mesh (vtkPolyDataMapper) at 4x4
                supersampling; then differential points against surfels on it
                (SplatReportDifferentialPoints.h, differential-points.csv and .png)
  bunny-closeup the bunny's flank magnified, splats several pixels wide
  armadillo, armadillo-closeup
                CGAL's armadillo (Debian's libcgal-demo) seen whole and magnified
  armadillo-points
                the magnified armadillo drawn from a random point cloud on its triangles, with
                the normals and radii vtkSurfelGenerator estimates (a scan without its mesh)
  sphere        a sphere of --points vertices seen whole, several surfels to a pixel
                (SplatReportMeshes.h for these scenes; the same kind of reference)
  mri           the MRI head ch2.nii.gz (Debian's mricron-data; skipped when absent), shrunk by
                --mri-shrink (vtkImageShrink3D, block means), in TestVolumeSplatCrossRenderer's
                transfer functions and camera
  gaussians     --kernels random anisotropic 3D Gaussians in the unit ball (fixed seed)
  vdb           a cloud of --voxels active voxels of OpenVDB fog on a rotated, non-uniformly
                scaled grid (SplatVdbScenes.h), written as cloud.vdb into the output folder and
                read by vtkOpenVDBReader: its kernels, and its dense copy for the ray casters
  stability     the stiff and extreme cases of Testing/Cxx/SplatStabilityCases.h with both
                mappers on each backend: NaN/Inf values, skipped kernels and why, errors,
                ms per frame against the scene without the extreme, RMSE against a reference
                where one exists; stability.csv, stability.md (SplatReportStability.h)
  captures      3D Gaussian Splatting captures (the generated torus, and the shared data's
                real captures when present) in every ordering mode and footprint filter
                against the rules they were trained under; captures.csv, captures.md
                (SplatReportCaptures.h)
The volume scenes (--volume-size pixels square, black background) are drawn by
vtkVolumeSplatMapper in every ordering mode (blended is the default), with cutoffs 2 and 8 (the
default 4.5 aside), and by vtkFixedPointVolumeRayCastMapper (a sample every voxel spacing and
every quarter of it) and vtkGPUVolumeRayCastMapper (every voxel spacing); for gaussians the ray
casters get the mixture resampled onto a --grid^3 RGBA grid. Reference: the Gaussian mixture
integrated by ray marching (one ray per pixel center, a step of 1/8 of the smallest kernel
standard deviation, emission-absorption front to back); the alternative filters it with EWA's
unit-variance screen filter. The ray casters interpolate voxels trilinearly instead of summing
Gaussians: their error includes that difference of model.
Time is the median milliseconds per frame around vtkRenderWindow::Render(), over all timed
frames of all rounds (each round renders every case, in an order of its own: a warm-up frame,
then the timed frames); error is the RMSE and PSNR of RGB in [0,1] (OpenImageIO's
ImageBufAlgo::compare), for the scene's reference and for the same scene with the other pixel
filter (box or Gaussian). A case is on the Pareto front when no other is as exact and faster in
every round, or more exact and no slower in median; cases that draw the same image to 80 dB (a
setting the scene's path does not use) do not dominate each other.

Writes into the output folder: error_vs_time.csv, error_vs_time.md (a table per scene, the
default setting and the Pareto front of error against time marked), error_vs_time.png (the
plot), <scene>-reference.png, and <scene>-<case>.png and <scene>-<case>-diff.png (4x the
absolute difference) for every case. Prints the tables.

Options (a value follows as --name VALUE or --name=VALUE; lists are comma-separated):
  --output-dir DIR   output folder (default $SPLAT_OUTPUT_DIR/report, else output/report)
  --scenes LIST      checkerboard, textured-plane, bunny, bunny-closeup, armadillo,
                     armadillo-closeup, armadillo-points, sphere, mri, gaussians, vdb,
                     stability, captures
                     (default all; the scans and mri are skipped when absent)
  --backends LIST    the splat mappers' backends: cpu, opengl (default: both for the surface
                     scenes, cpu for the volume scenes; a list given here applies to both;
                     under a software OpenGL renderer such as llvmpipe the OpenGL rows are slow)
  --size WxH         image size in pixels (default 512x384)
  --rounds N         rounds over all cases (default 4)
  --frames N         timed frames per case and round (default 3)
  --budget SECONDS   fewer frames (at least 1) once a case's round took this long (default 3)
  --points N         about how many surfels the checkerboard and the sphere get (default
                     1000000)
  --samples N        reference sub-samples per pixel and axis (default 16)
  --volume-size N    the volume scenes' image size, N x N pixels (default 256)
  --mri-shrink N     the MRI's every N-th voxel per axis (default 2)
  --kernels N        Gaussians of the gaussians scene (default 2000)
  --voxels N         active voxels of the vdb scene's fog (default 100000)
  --grid N           grid points per axis of the gaussians resampled for the ray casters
                     (default 128)
  --quick            smoke run: 256x192, 100000 surfels, 8 sub-samples, 1 round of 2 frames;
                     volumes at 128x128, the MRI shrunk by 4, 500 Gaussians on a 64^3 grid
  --help             print this help

Environment: SPLAT_DATA_DIR, the folder holding bunny.ply (default: ../shared/data next to the
source tree); SPLAT_OUTPUT_DIR (see --output-dir); SPLAT_MRI_FILE, the MRI (default
/usr/share/mricron/templates/ch2.nii.gz).
)";


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
  std::string outputRoot;
  options.OutputDir = vtksys::SystemTools::GetEnv("SPLAT_OUTPUT_DIR", outputRoot) &&
      !outputRoot.empty()
    ? outputRoot + "/report"
    : "output/report";
  const std::map<std::string, splatexample::OptionHandler> handlers = {
    { "--output-dir",
      [&](const std::string&, const std::string& value) { options.OutputDir = value; } },
    { "--scenes",
      [&](const std::string& name, const std::string& value) {
        options.Scenes = splatexample::SplitList(
          name, value, { "checkerboard", "textured-plane", "bunny", "bunny-closeup",
                         "armadillo", "armadillo-closeup", "armadillo-points", "sphere", "mri",
                         "gaussians", "vdb", "stability", "captures" });
      } },
    { "--backends",
      [&](const std::string& name, const std::string& value) {
        options.Backends = splatexample::SplitList(name, value, { "cpu", "opengl" });
        options.VolumeBackends = options.Backends;
      } },
    { "--size",
      [&](const std::string& name, const std::string& value) {
        const auto x = value.find('x');
        if (x == std::string::npos)
        {
          throw UsageError(name + ": expected WIDTHxHEIGHT, got '" + value + "'");
        }
        options.Width = static_cast<int>(ParseCount(name, value.substr(0, x), 16, 4096));
        options.Height = static_cast<int>(ParseCount(name, value.substr(x + 1), 16, 4096));
      } },
    { "--rounds", CountInto(options.Rounds, 1, 100) },
    { "--frames", CountInto(options.Frames, 1, 1000) },
    { "--budget", CountInto(options.Budget, 0, 3600) },
    { "--points", CountInto(options.Points, 1000, 20000000) },
    { "--volume-size", CountInto(options.VolumeSize, 16, 4096) },
    { "--mri-shrink", CountInto(options.MriShrink, 1, 16) },
    { "--kernels", CountInto(options.Kernels, 1, 10000000) },
    { "--voxels", CountInto(options.Voxels, 1000, 100000000) },
    { "--grid", CountInto(options.Grid, 8, 1024) },
    { "--samples", CountInto(options.Samples, 1, 64) },
  };
  const std::map<std::string, std::function<void()>> flags = {
    { "--quick",
      [&] {
        options.Width = 256;
        options.Height = 192;
        options.Points = 100000;
        options.Samples = 8;
        options.Rounds = 1;
        options.Frames = 2;
        options.VolumeSize = 128;
        options.MriShrink = 4;
        options.Kernels = 500;
        options.Voxels = 20000;
        options.Grid = 64;
      } },
  };
  splatexample::ParseArguments(argc, argv, Usage, handlers, flags);
  return options;
}

// Appends the milliseconds of each timed frame, after a warm-up frame, to `ms`: Frames frames,
// fewer once the budget is spent (at least one). A volume is marked modified before each frame,
// as in TestVolumeSplatCrossRenderer.
void TimeFrames(
  vtkRenderWindow* window, const Options& options, std::vector<double>& ms, vtkVolume* volume)
{
  using Clock = std::chrono::steady_clock;
  window->Render();
  window->WaitForCompletion();
  const auto start = Clock::now();
  for (int frame = 0; frame < options.Frames &&
       (frame == 0 || std::chrono::duration<double>(Clock::now() - start).count() < options.Budget);
       ++frame)
  {
    if (volume)
    {
      volume->Modified();
    }
    const auto frameStart = Clock::now();
    window->Render();
    window->WaitForCompletion(); // OpenGL runs asynchronously
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - frameStart).count());
  }
}

std::string Slug(const std::string& text)
{
  std::string slug;
  for (char c : text)
  {
    slug += std::isalnum(static_cast<unsigned char>(c)) || c == '.' ? c : '-';
  }
  return slug;
}

// Makes a case's prop: the mapper and what it draws.
using PropMaker = std::function<vtkSmartPointer<vtkProp3D>(const Case&)>;

// Actors drawing the surfels with each case's mapper, styled by `style`.
PropMaker SurfaceProps(vtkPolyData* surfels, const std::function<void(vtkActor*)>& style)
{
  vtkSmartPointer<vtkPolyData> data = surfels;
  return [data, style](const Case& c) -> vtkSmartPointer<vtkProp3D>
  {
    vtkNew<vtkActor> actor;
    actor->SetMapper(c.Make(data));
    style(actor);
    return actor.Get();
  };
}

// Volumes drawing a volume scene's inputs with each case's mapper: vtkVolumeSplatMapper the
// kernels, the ray casters the grid.
PropMaker VolumeProps(const VolumeInputs& inputs)
{
  return [inputs](const Case& c) -> vtkSmartPointer<vtkProp3D>
  {
    vtkNew<vtkVolume> volume;
    volume->SetMapper(c.MakeVolume(inputs));
    volume->SetProperty(IsOurs(c) ? inputs.Property : inputs.GridProperty);
    volume->SetUserMatrix(IsOurs(c) ? nullptr : inputs.GridMatrix);
    return volume.Get();
  };
}

// What our mappers say they did in the last frame; empty for the peers.
std::string CountsOf(vtkProp3D* prop)
{
  auto* actor = vtkActor::SafeDownCast(prop);
  auto* volume = vtkVolume::SafeDownCast(prop);
  if (auto* splat = vtkSurfaceSplatMapper::SafeDownCast(actor ? actor->GetMapper() : nullptr))
  {
    return std::to_string(splat->GetNumberOfRenderedSplats()) + " splats drawn, " +
      std::to_string(splat->GetNumberOfFrustumCulledSplats()) + " outside the frustum, " +
      std::to_string(splat->GetNumberOfBackfaceCulledSplats()) + " back-facing, " +
      std::to_string(splat->GetNumberOfNegligibleSplats()) + " negligible, " +
      std::to_string(splat->GetNumberOfSkippedPoints()) + " invalid points skipped";
  }
  if (auto* splat = vtkVolumeSplatMapper::SafeDownCast(volume ? volume->GetMapper() : nullptr))
  {
    return std::to_string(splat->GetNumberOfKernels()) + " kernels in the lists (" +
      std::to_string(splat->GetNumberOfTransparentKernels()) + " transparent left out), " +
      std::to_string(splat->GetNumberOfProjectedKernels()) + " projected, " +
      std::to_string(splat->GetNumberOfFrustumCulledKernels()) + " outside the frustum, drawn by " +
      vtkSplatBackend::GetBackendAsString(splat->GetLastBackend());
  }
  return "";
}

// The splats vtkSurfaceSplatMapper drew in the last frame, or -1 for other mappers.
long long DrawnSplats(vtkProp3D* prop)
{
  auto* actor = vtkActor::SafeDownCast(prop);
  auto* splat = vtkSurfaceSplatMapper::SafeDownCast(actor ? actor->GetMapper() : nullptr);
  return splat ? static_cast<long long>(splat->GetNumberOfRenderedSplats()) : -1;
}

// Renders every case's prop (makeProp) into `window` (whose renderer holds the camera) and
// measures each image against `reference` (and `alternative`). The cases are timed in rounds,
// all cases once per round, so that a change of the machine's load while the report runs spreads
// over all cases instead of skewing some; the images come from the last round.
std::vector<Row> MeasureScene(vtkRenderWindow* window, vtkRenderer* renderer,
  const std::string& scene, const PropMaker& makeProp, const OIIO::ImageBuf& reference,
  const OIIO::ImageBuf& alternative, const std::vector<Case>& cases, const Options& options,
  std::vector<std::string>& notes)
{
  const int allThreads = UseThreads(0);
  std::vector<Row> rows(cases.size());
  std::vector<std::vector<double>> ms(cases.size());
  std::vector<std::vector<double>> roundMs(cases.size()); // each round's median
  std::vector<OIIO::ImageBuf> images(cases.size());        // the last round's
  for (int round = 0; round < options.Rounds; ++round)
  {
    const bool last = round + 1 == options.Rounds;
    // Each round times the cases in an order of its own (fixed by the round's number), so that
    // no case always follows the same one: the one after the peers' OpenGL frames ran slower
    // (the default, listed first, by up to a fifth against the identical layers=5).
    std::vector<std::size_t> order(cases.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(static_cast<unsigned>(round)));
    for (const std::size_t i : order)
    {
      const Case& c = cases[i];
      vtkSmartPointer<vtkProp3D> prop = makeProp(c);
      const int threads = UseThreads(c.Threads > 0 ? c.Threads : 0);
      if (c.Threads > 0 && threads != c.Threads && last)
      {
        notes.push_back("vtkSMPTools::Initialize(" + std::to_string(c.Threads) + ") left " +
          std::to_string(threads) + " threads (" + vtkSMPTools::GetBackend() + " backend)");
      }
      std::cerr << "splat_report: " << scene << " (round " << round + 1 << "/" << options.Rounds
                << "): " << c.Mapper << " (" << c.Backend << ") " << c.Setting;
      if (c.Threads > 0)
      {
        std::cerr << ", " << threads << (threads == 1 ? " thread" : " threads");
      }
      std::cerr << std::endl;
      renderer->RemoveAllViewProps(); // the previous case, with its graphics resources
      renderer->AddViewProp(prop);
      const std::size_t timed = ms[i].size();
      TimeFrames(window, options, ms[i], vtkVolume::SafeDownCast(prop));
      roundMs[i].push_back(splatexample::Median(
        std::vector<double>(ms[i].begin() + static_cast<std::ptrdiff_t>(timed), ms[i].end())));
      if (!last)
      {
        continue;
      }

      const OIIO::ImageBuf image = CaptureWindow(window);
      const auto compared = OIIO::ImageBufAlgo::compare(image, reference, 1.0f, 1.0f);
      const auto comparedAlt = OIIO::ImageBufAlgo::compare(image, alternative, 1.0f, 1.0f);
      if (compared.error || comparedAlt.error)
      {
        throw std::runtime_error("comparing the images failed: " + image.geterror());
      }
      const std::string name = scene + "-" + MapperSlug(c) + "-" +
        Slug(c.Defaults ? "default" : c.Setting) +
        (c.Threads > 0 ? "-t" + std::to_string(threads) : "");
      WriteImage(image, options.OutputDir + "/" + name + ".png");
      WriteImage(OIIO::ImageBufAlgo::mul(OIIO::ImageBufAlgo::absdiff(image, reference), 4.0f),
        options.OutputDir + "/" + name + "-diff.png");
      images[i] = image;
      const std::string counts = CountsOf(prop);
      rows[i] = { scene, &c, c.Threads > 0 ? threads : 0, splatexample::Median(ms[i]),
        compared.rms_error, compared.PSNR, comparedAlt.rms_error, comparedAlt.PSNR, false,
        name + ".png", counts, DrawnSplats(prop) };
    }
  }
  renderer->RemoveAllViewProps();
  UseThreads(allThreads);

  // The Pareto front: no other case is as exact and faster, or more exact and not slower. A
  // case is faster than another only if it was in every round: each round times every case in
  // turn, under about the same load, and cases that do the same work (settings that leave a
  // scene's path unchanged) otherwise rank by the machine's noise. It is not slower where its
  // median time is no higher: one round of four that a slower case won by noise does not make
  // it as fast (cutoff=4 on the armadillo's points, 10 % slower in median than the default's
  // 3, was faster in one round).
  auto faster = [&](std::size_t b, std::size_t a)
  {
    for (std::size_t r = 0; r < roundMs[a].size(); ++r)
    {
      if (!(roundMs[b][r] < roundMs[a][r]))
      {
        return false;
      }
    }
    return true;
  };
  // Cases that draw the same image (a setting the scene's path does not use, or one the
  // default already picks) differ in time only by noise: neither dominates the other. Images
  // count as the same to 80 dB (an RMS difference under 1e-4: a few pixels one 8-bit step
  // apart), far beyond the differences between settings.
  constexpr double SameImageRmse = 1e-4;
  auto sameImage = [&](std::size_t a, std::size_t b)
  {
    return std::abs(rows[a].Rmse - rows[b].Rmse) < SameImageRmse &&
      OIIO::ImageBufAlgo::compare(images[a], images[b], 1.0f, 1.0f).rms_error < SameImageRmse;
  };
  for (std::size_t a = 0; a < rows.size(); ++a)
  {
    bool dominated = false;
    for (std::size_t b = 0; b < rows.size() && !dominated; ++b)
    {
      dominated = b != a &&
        ((rows[b].Rmse <= rows[a].Rmse && faster(b, a)) ||
          (rows[b].Rmse < rows[a].Rmse && rows[b].Milliseconds <= rows[a].Milliseconds)) &&
        !sameImage(a, b);
    }
    rows[a].Pareto = !dominated;
  }
  return rows;
}

// A volume scene measured: its rows and its reference.
struct VolumeSceneResult
{
  std::vector<Row> Rows;
  double ReferenceSeconds = 0.0;
  double Step = 0.0;
  long long Samples = 0;
};

// Renders a volume scene (its camera placed) at VolumeSize^2 over black with every case and
// measures each image against the ray-marched integration of `field` (SplatVolumeReference.h)
// and against that reference filtered like EWA's screen low-pass filter.
template <typename Field>
VolumeSceneResult MeasureVolumeScene(vtkRenderWindow* window, vtkRenderer* renderer,
  const std::string& scene, const VolumeInputs& inputs, const Field& field,
  const std::vector<Case>& cases, const Options& options, std::vector<std::string>& notes)
{
  const int size = options.VolumeSize;
  window->SetSize(size, size);
  renderer->SetBackground(0.0, 0.0, 0.0);
  renderer->RemoveAllViewProps();
  std::cerr << "splat_report: " << scene << ": ray-marched reference (step " << field.Step()
            << ")" << std::endl;
  VolumeSceneResult result;
  const auto start = std::chrono::steady_clock::now();
  const splatexample::VolumeReference reference = splatexample::RayMarch(
    splatexample::CameraRays(renderer->GetActiveCamera(), size, size), field, field.Step());
  result.ReferenceSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.Step = reference.Step;
  result.Samples = reference.Samples;
  // [0] the reference, [1] Gaussian-filtered (the alternative).
  const std::array<OIIO::ImageBuf, 2> references =
    VolumeReferenceImages(reference.RGB, size, size);
  WriteImage(references[0], options.OutputDir + "/" + scene + "-reference.png");
  WriteImage(references[1], options.OutputDir + "/" + scene + "-reference-gaussian.png");
  result.Rows = MeasureScene(window, renderer, scene, VolumeProps(inputs), references[0],
    references[1], cases, options, notes);
  return result;
}

// The volume issue's target on the MRI: vtkVolumeSplatMapper's default (blended, CPU) no slower
// than vtkFixedPointVolumeRayCastMapper (a sample every voxel) at no worse error against the
// reference; here at the report's size (the bench times the full MRI at 512^2).
std::string VolumeTargetText(const std::vector<Row>& rows)
{
  const Row* ours = nullptr;
  const Row* peer = nullptr;
  for (const Row& r : rows)
  {
    ours = r.What->IsDefault ? &r : ours;
    peer = !peer && r.What->Mapper == "vtkFixedPointVolumeRayCastMapper" ? &r : peer;
  }
  if (!ours || !peer)
  {
    return "";
  }
  std::ostringstream text;
  text << "Target (blended on the CPU no slower than vtkFixedPointVolumeRayCastMapper at no worse "
       << "error): RMSE " << Fixed(ours->Rmse, 4) << " against " << Fixed(peer->Rmse, 4) << " ("
       << (ours->Rmse <= peer->Rmse ? "met" : "not met") << "), " << Fixed(ours->Milliseconds, 1)
       << " ms against " << Fixed(peer->Milliseconds, 1) << " ms at this size ("
       << (ours->Milliseconds <= peer->Milliseconds ? "met" : "not met")
       << "; `./splat bench` times the full MRI at 512^2).\n";
  return text.str();
}

// What every volume scene's section says about its reference and the ray casters.
std::string VolumeReferenceText(const VolumeSceneResult& result, const std::string& kernels)
{
  std::ostringstream text;
  text << "Reference: " << kernels << " integrated by ray marching (`SplatVolumeReference.h`): "
       << "one ray per pixel center from the camera, a sample every " << std::setprecision(4)
       << result.Step << " (1/8 of the smallest kernel standard deviation; "
       << result.Samples << " samples evaluated), extinction and emission-weighted color of the "
       << "kernels summed at each sample without cutoff, emission-absorption front to back "
       << "over black (" << Fixed(result.ReferenceSeconds, 1) << " s to compute). The last "
       << "column measures against the reference filtered like EWA's screen low-pass filter "
       << "(a unit-variance Gaussian in pixels, `<scene>-reference-gaussian.png`). "
       << "vtkFixedPointVolumeRayCastMapper and vtkGPUVolumeRayCastMapper sample their rays "
       << "every voxel spacing (or a quarter of it) and interpolate the voxels trilinearly, "
       << "classifying after interpolation, instead of summing Gaussian kernels: their error "
       << "includes that difference of model besides their sampling.";
  return text.str();
}

int Run(const Options& options)
{
  if (!vtksys::SystemTools::MakeDirectory(options.OutputDir))
  {
    throw std::runtime_error("cannot create the folder '" + options.OutputDir + "'");
  }
  const auto wants = [&](const char* scene) {
    return std::find(options.Scenes.begin(), options.Scenes.end(), scene) != options.Scenes.end();
  };
  const auto start = std::chrono::steady_clock::now();

  // Thread counts: 1 and all (vtkSMPTools' default).
  const int allThreads = AllThreads();
  UseThreads(allThreads);
  std::vector<int> threadCounts = { allThreads };
  if (allThreads > 1)
  {
    threadCounts.insert(threadCounts.begin(), 1);
  }
  const std::vector<Case> cases = Cases(threadCounts, options.Backends);
  std::vector<std::string> notes;

  // One window for every case (see splatexample::MakeOffscreenWindow).
  vtkSmartPointer<vtkRenderWindow> window = splatexample::MakeOffscreenWindow();
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  window->SetSize(options.Width, options.Height);
  window->Render();
  const std::string glRenderer = splatexample::OpenGLRenderer(window);

  std::vector<Row> rows;
  std::vector<std::string> scenes;
  std::ostringstream md;
  md << "# Error against run time\n\n"
     << "`splat_report`, " << options.Width << "x" << options.Height << " pixels, OpenGL: "
     << glRenderer << ", vtkSMPTools backend " << vtkSMPTools::GetBackend() << " with "
     << allThreads << " threads by default. Time: median ms per frame around "
     << "`vtkRenderWindow::Render()`, over " << options.Rounds << " rounds (each renders every "
     << "case, in an order of its own: a warm-up frame, then up to " << options.Frames
     << " timed frames); the machine's other load shows in these times. Error: RMSE and PSNR "
     << "of RGB in [0,1] "
     << "against the scene's reference (OpenImageIO `ImageBufAlgo::compare`); the last column "
     << "is the RMSE against the same scene with the other pixel filter (box or Gaussian), "
     << "which ranks blur differently. The default setting is in bold; every other "
     << "row changes one setting from it. A row is on the Pareto front when no other row of "
     << "the scene is as exact and faster, or more exact and not slower; a row counts as "
     << "faster than another only if it was in every round (each round times every case in "
     << "turn, under about the same load), so that rows doing the same work do not rank by "
     << "the machine's noise, and as not slower where its median time is no higher; rows "
     << "that draw the same image to 80 dB (an RMS difference under 1e-4: a setting the "
     << "scene's path does not use, or the value the default picks) never dominate each other. "
     << "Backends: the CPU rows run on vtkSMPTools' "
     << "threads; the OpenGL rows repeat the settings in shaders on the OpenGL renderer above "
     << "(under a software renderer such as llvmpipe, its time is the CPU's, not a GPU's) and "
     << "add the approximate filter mode (OpenGL only). Peer: `vtkPointGaussianMapper` on the same "
     << "points, emissive off: `disk` draws opaque disks of the surfels' radius, `gaussian` its "
     << "default alpha-blended Gaussians with the surfels' variance (sigma = radius/sqrt 2).\n\n";

  if (wants("checkerboard"))
  {
    Checkerboard board;
    board.FitPoints(options.Points);
    board.SetCamera(renderer->GetActiveCamera());
    renderer->SetBackground(board.Background.data());
    std::cerr << "splat_report: checkerboard: analytic reference (" << options.Samples << "x"
              << options.Samples << " sub-samples per pixel)" << std::endl;
    const auto refStart = std::chrono::steady_clock::now();
    // [0] Gaussian pixel filter (the reference), [1] the pixel's box (the alternative).
    const std::array<OIIO::ImageBuf, 2> references = CheckerboardReferences(
      board, renderer->GetActiveCamera(), options.Width, options.Height, options.Samples);
    const double refSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - refStart).count();
    WriteImage(references[0], options.OutputDir + "/checkerboard-reference.png");
    WriteImage(references[1], options.OutputDir + "/checkerboard-reference-box.png");
    vtkSmartPointer<vtkPolyData> surfels =
      CheckerboardSurfels(board, renderer->GetActiveCamera(), options.Width, options.Height);
    std::vector<Row> sceneRows = MeasureScene(window, renderer, "checkerboard",
      SurfaceProps(surfels, StyleCheckerboardActor), references[0], references[1], cases, options,
      notes);
    rows.insert(rows.end(), sceneRows.begin(), sceneRows.end());
    scenes.push_back("checkerboard");
    // Paper 000, figure 8: the reference and EWA on top; circular and unfiltered splats below.
    const std::string folder = options.OutputDir + "/checkerboard-";
    WriteMontage({ folder + "reference.png", folder + "splat-default-t" +
        std::to_string(allThreads) + ".png", folder + "splat-filter-circular-t" +
        std::to_string(allThreads) + ".png", folder + "splat-filter-unfiltered-t" +
        std::to_string(allThreads) + ".png" },
      2, options.OutputDir + "/checkerboard-figure8.png");
    md << "## checkerboard\n\n"
       << "A checkerboard plane (z = 0, checks of side " << board.Check << ", grays "
       << Fixed(board.Light[0], 3) << " and " << Fixed(board.Dark[0], 3) << ") seen from height "
       << board.CameraHeight << " looking " << board.PitchDegrees
       << " degrees below the horizon (view angle 30 degrees); the plane ends at y = "
       << board.Far << ", in front of a sky-blue background. "
       << surfels->GetNumberOfPoints() << " surfels on a grid of spacing h = " << board.Spacing
       << " (radius h, normal +z), each colored with the checkerboard's exact mean over its "
       << "grid cell (8-bit). Lighting off. Reference: analytic, " << options.Samples << "x"
       << options.Samples << " sub-pixel cells per pixel, each the checkerboard's exact mean over "
       << "its footprint's bounding box on the plane, weighted by a unit-variance Gaussian "
       << "pixel filter truncated at 3 sigma (" << Fixed(refSeconds, 1) << " s to compute). "
       << "The last column measures against the same cells with the pixel's box as the filter "
       << "(each pixel's exact area average, `checkerboard-reference-box.png`). "
       << "`checkerboard-figure8.png` shows, as paper 000's figure 8, the reference and EWA "
       << "(top), circular and unfiltered splats (bottom).\n\n"
       << MarkdownTable(sceneRows, "box-filtered reference") << "\n";
  }

  if (wants("textured-plane"))
  {
    md << MeasureTexturedPlane(window, renderer, options);
  }
  if (wants("stability"))
  {
    md << MeasureStability(options);
  }
  if (wants("captures"))
  {
    md << MeasureCaptures(options);
  }

  for (const MeshScene& scene : MeshScenes(options.Scenes, options.Points, notes))
  {
    vtkSmartPointer<vtkPolyData> surfels = SceneSurfels(scene);
    const double* color = scene.Color;
    const double background[3] = { 0.1, 0.1, 0.15 };
    renderer->SetBackground(background[0], background[1], background[2]);
    renderer->RemoveAllViewProps();
    scene.PlaceCamera(renderer);

    std::cerr << "splat_report: " << scene.Name << ": reference (the mesh at 4x4 supersampling)"
              << std::endl;
    vtkNew<vtkPolyDataMapper> meshMapper;
    meshMapper->SetInputData(scene.Mesh);
    meshMapper->ScalarVisibilityOff();
    vtkNew<vtkActor> meshActor;
    meshActor->SetMapper(meshMapper);
    meshActor->GetProperty()->SetColor(color[0], color[1], color[2]);
    renderer->AddActor(meshActor);
    // [0] Gaussian then box (the alternative), [1] the 4x4 box (the reference).
    const std::array<OIIO::ImageBuf, 2> references = CaptureSupersampled(window, 4);
    renderer->RemoveAllViewProps();
    WriteImage(references[1], options.OutputDir + "/" + scene.Name + "-reference.png");
    WriteImage(references[0], options.OutputDir + "/" + scene.Name + "-reference-gaussian.png");

    const auto style = [color](vtkActor* actor) {
      actor->GetProperty()->SetColor(color[0], color[1], color[2]);
      actor->GetMapper()->ScalarVisibilityOff();
    };
    std::vector<Row> sceneRows = MeasureScene(window, renderer, scene.Name,
      SurfaceProps(surfels, style), references[1], references[0], cases, options, notes);
    rows.insert(rows.end(), sceneRows.begin(), sceneRows.end());
    scenes.push_back(scene.Name);
    const long long covered = CoveredPixels(references[1], background);
    md << "## " << scene.Name << "\n\n"
       << scene.What << " (" << scene.Mesh->GetNumberOfPoints() << " vertices, "
       << scene.Mesh->GetNumberOfPolys() << " triangles), " << scene.View
       << ", lit by the renderer's headlight, " << options.Width << "x" << options.Height
       << " pixels, " << covered << " of them covered by the mesh. Surfels: "
       << SurfelsText(scene, surfels->GetNumberOfPoints()) << "; the default draws "
       << Fixed(DefaultSplats(sceneRows) / std::max(1.0, double(covered)), 2)
       << " splats per covered pixel. Reference: the mesh drawn "
       << "by vtkPolyDataMapper at 4x the size, 4x4 blocks averaged. The last column measures "
       << "against the same large image filtered like EWA's screen filter (a Gaussian of "
       << "variance 1 - 1/12 pixels^2, then the 4x4 box: unit variance in all, `" << scene.Name
       << "-reference-gaussian.png`).\n\n"
       << MarkdownTable(sceneRows, "Gaussian-filtered reference") << "\n";
    if (scene.Name == "bunny")
    {
      md << MeasureDifferentialPoints(window, renderer, scene.Mesh, references[1], color, options,
        [&]() {
          std::vector<double> ms;
          TimeFrames(window, options, ms, nullptr);
          return splatexample::Median(ms);
        });
    }
  }
  const std::vector<Case> volumeCases = VolumeCases(options.VolumeBackends);
  // Not vtkGPUVolumeRayCastMapper on the resampled Gaussians: VTK 9.1's draws that RGBA grid
  // (dependent components) nearly transparent (see splatexample::ResampleMixture).
  std::vector<Case> gaussiansCases;
  std::copy_if(volumeCases.begin(), volumeCases.end(), std::back_inserter(gaussiansCases),
    [](const Case& c) { return c.Mapper != "vtkGPUVolumeRayCastMapper"; });
  if (wants("mri"))
  {
    if (vtkSmartPointer<vtkImageData> head = splatexample::MriHead(options.MriShrink))
    {
      vtkSmartPointer<vtkVolumeProperty> property = splatexample::MriProperty();
      window->SetSize(options.VolumeSize, options.VolumeSize);
      splatexample::PlaceMriCamera(renderer, head);
      const splatexample::GridField field(head, property);
      const VolumeSceneResult result = MeasureVolumeScene(window, renderer, "mri",
        { head, property, head, property, nullptr }, field, volumeCases, options, notes);
      rows.insert(rows.end(), result.Rows.begin(), result.Rows.end());
      scenes.push_back("mri");
      int dims[3];
      head->GetDimensions(dims);
      md << "## mri\n\n"
         << "The MRI head `" << splatexample::MriFile() << "` (181x217x181 voxels of 1 mm), "
         << (options.MriShrink > 1 ? "shrunk by " + std::to_string(options.MriShrink) +
                 " along each axis, each voxel the mean of its block (vtkImageShrink3D, "
                 "averaging), "
                                   : std::string())
         << dims[0] << "x" << dims[1] << "x" << dims[2] << " voxels, with the transfer functions "
         << "and the camera of TestVolumeSplatCrossRenderer, " << options.VolumeSize << "x"
         << options.VolumeSize << " pixels. vtkVolumeSplatMapper: one Gaussian per voxel of "
         << "non-zero opacity. "
         << VolumeReferenceText(result, "the voxels' Gaussian kernels (tau(scalar) times the voxel "
                                        "volume, standard deviation 0.6 voxel)")
         << "\n\n"
         << MarkdownTable(result.Rows, "Gaussian-filtered reference") << "\n"
         << VolumeTargetText(result.Rows) << "\n";
    }
    else
    {
      notes.push_back("mri scene skipped: " + splatexample::MriFile() +
        " is absent (Debian package mricron-data)");
    }
  }
  if (wants("gaussians"))
  {
    vtkSmartPointer<vtkPolyData> kernels =
      splatexample::RandomGaussians(static_cast<vtkIdType>(options.Kernels));
    vtkSmartPointer<vtkVolumeProperty> property = splatexample::GaussiansProperty(kernels);
    const splatexample::GaussianMixture mixture = splatexample::MixtureOf(kernels, property);
    std::cerr << "splat_report: gaussians: resampling onto " << options.Grid << "^3 voxels"
              << std::endl;
    const splatexample::ResampledVolume grid = splatexample::ResampleMixture(mixture, options.Grid);
    window->SetSize(options.VolumeSize, options.VolumeSize);
    splatexample::PlaceGaussiansCamera(renderer);
    const splatexample::MixtureField field(mixture);
    const VolumeSceneResult result = MeasureVolumeScene(window, renderer, "gaussians",
      { kernels, property, grid.Image, grid.Property, nullptr }, field, gaussiansCases, options,
      notes);
    rows.insert(rows.end(), result.Rows.begin(), result.Rows.end());
    scenes.push_back("gaussians");
    md << "## gaussians\n\n"
       << options.Kernels << " random anisotropic 3D Gaussians in the unit ball (fixed seed; "
       << "`SplatVolumeScenes.h`): covariances as a `Covariance` array, colors as a `Color` "
       << "array, the peak extinction as scalars through an opacity transfer function "
       << "alpha = 1 - exp(-s unitDistance), " << options.VolumeSize << "x" << options.VolumeSize
       << " pixels. " << VolumeReferenceText(result, "the same Gaussians")
       << " The ray casters draw the mixture sampled on a " << options.Grid << "^3 grid over "
       << "[-1, 1]^3 (unsigned char RGBA, dependent components: RGB the emission-weighted "
       << "color, A the extinction in 255 steps), so their error also holds that resampling "
       << "and quantization; vtkGPUVolumeRayCastMapper is left out here: VTK 9.1's draws that "
       << "grid nearly transparent.\n\n"
       << MarkdownTable(result.Rows, "Gaussian-filtered reference") << "\n";
  }
  if (wants("vdb"))
  {
    const std::string file = options.OutputDir + "/cloud.vdb";
    const splatexample::VdbScene cloud =
      splatexample::WriteCloudVdb(file, static_cast<vtkIdType>(options.Voxels));
    vtkNew<vtkOpenVDBReader> reader;
    reader->SetFileName(file.c_str());
    reader->ProduceDenseOutputOn();
    reader->Update();
    vtkPolyData* kernels = reader->GetOutput();
    if (kernels->GetNumberOfPoints() == 0)
    {
      throw std::runtime_error("vtkOpenVDBReader could not read " + file);
    }
    const splatexample::ResampledVolume grid =
      splatexample::AxisAlignedGrid(reader->GetDenseOutput(), cloud.Property);
    window->SetSize(options.VolumeSize, options.VolumeSize);
    cloud.PlaceCamera(renderer->GetActiveCamera());
    renderer->ResetCameraClippingRange(kernels->GetBounds());
    const splatexample::GaussianMixture mixture = splatexample::MixtureOf(kernels, cloud.Property);
    const splatexample::MixtureField field(mixture);
    const VolumeSceneResult result = MeasureVolumeScene(window, renderer, "vdb",
      { kernels, cloud.Property, grid.Image, grid.Property, grid.UserMatrix }, field, volumeCases,
      options, notes);
    rows.insert(rows.end(), result.Rows.begin(), result.Rows.end());
    scenes.push_back("vdb");
    int dims[3];
    grid.Image->GetDimensions(dims);
    md << "## vdb\n\n"
       << "A cloud of " << cloud.ActiveVoxels << " active voxels of OpenVDB fog ("
       << cloud.ActiveVoxels - cloud.LeafVoxels << " of them, inside, stored as " << cloud.Tiles
       << " active tiles; `SplatVdbScenes.h`) on a rotated, non-uniformly scaled grid, written to "
       << "`cloud.vdb` and read by vtkOpenVDBReader: " << kernels->GetNumberOfPoints()
       << " kernels (one per active voxel, the leaf-sized tiles as their voxels, each with the "
       << "voxel's Gaussian and its sample volume; a voxel lattice drawn sheet by sheet), "
       << options.VolumeSize << "x" << options.VolumeSize << " pixels. "
       << VolumeReferenceText(result, "the reader's kernels (tau(density) times the sample volume)")
       << " The ray casters draw the reader's dense copy of the grid (" << dims[0] << "x"
       << dims[1] << "x" << dims[2] << " voxels over the active bounding box, the rotation as "
       << "the volume's matrix: VTK 9.1's vtkFixedPointVolumeRayCastMapper ignores an image's "
       << "direction matrix).\n\n"
       << MarkdownTable(result.Rows, "Gaussian-filtered reference") << "\n";
  }
  if (rows.empty() && !wants("textured-plane") && !wants("stability") && !wants("captures"))
  {
    throw std::runtime_error("no scene was measured");
  }

  if (!notes.empty())
  {
    md << "## Notes\n\n";
    for (const std::string& note : notes)
    {
      md << "- " << note << "\n";
    }
    md << "\n";
  }
  md << "Images: `<scene>-reference.png`, `<scene>-<case>.png` and `<scene>-<case>-diff.png` "
     << "(4x the absolute difference to the reference); plot: `error_vs_time.png`.\n";

  const std::string csvPath = options.OutputDir + "/error_vs_time.csv";
  const std::string mdPath = options.OutputDir + "/error_vs_time.md";
  const std::string pngPath = options.OutputDir + "/error_vs_time.png";
  WriteCsv(rows, csvPath);
  {
    std::ofstream file(mdPath);
    file << md.str();
    if (!file)
    {
      throw std::runtime_error("cannot write '" + mdPath + "'");
    }
  }
  if (!scenes.empty()) // textured-plane, stability and captures have their own tables only
  {
    WritePlot(scenes, rows, pngPath);
  }

  std::cout << md.str() << "\n";
  const std::string folder = vtksys::SystemTools::CollapseFullPath(options.OutputDir);
  std::cout << "Written to " << folder << ":\n  error_vs_time.csv\n  error_vs_time.md\n"
            << "  error_vs_time.png\n  and the reference, rendered and difference images (PNG)\n"
            << "Total " << Fixed(std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count(),
                             1)
            << " s\n";
  return EXIT_SUCCESS;
}
}

int main(int argc, char* argv[])
{
  return splatexample::RunProgram(
    "splat_report", [&] { return Run(ParseCommandLine(argc, argv)); });
}
