// SPDX-License-Identifier: BSD-3-Clause
// splat_bench: a benchmark, not a test. Renders the same points with vtkSurfaceSplatMapper and
// with its peer vtkPointGaussianMapper, in the same run, and prints one CSV row per case:
// milliseconds per frame (median), splats per second and the process's peak memory so far.
// Run `splat_bench --help` for the options.
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"

#include "vtkActor.h"
#include "vtkErrorCode.h"
#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
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

namespace
{
const char* const Usage = R"(Usage: splat_bench [OPTIONS]

Renders points on a unit sphere (Fibonacci sampling, radial normals, radius = sampling spacing)
and the Stanford bunny (vertices through vtkSurfelGenerator) with vtkSurfaceSplatMapper and with
vtkPointGaussianMapper (opaque disks of the same radius, emissive off), offscreen, and
prints CSV rows:
  scene,mapper,backend,setting,points,width,height,ms_per_frame,splats_per_s,peak_rss_mb
ms_per_frame is the median over the timed frames after one warm-up frame; peak_rss_mb is the
peak resident memory of the whole process so far (cases run from small to large).

Options (a value follows as --name VALUE or --name=VALUE; lists are comma-separated):
  --scenes LIST        sphere, bunny (default sphere,bunny; bunny is skipped when absent)
  --points LIST        sphere point counts (default 100000,1000000)
  --sizes LIST         square image sizes in pixels (default 512,1024)
  --mappers LIST       splat (vtkSurfaceSplatMapper), pointgaussian (vtkPointGaussianMapper)
                       (default splat,pointgaussian)
  --frames N           at most N timed frames per case (default 10)
  --budget SECONDS     stop timing a case after this long, once 3 frames (or --frames, if
                       fewer) are timed (default 10)
  --quick              smoke run: 20000 sphere points, 256x256, 2 frames
  --output FILE        CSV file, also written to stdout (default output/bench/bench.csv)
  --image-dir DIR      also write each case's last frame as a PNG into DIR
  --help               print this help

Environment: SPLAT_DATA_DIR, the folder holding bunny.ply (default: ../shared/data next to the
source tree).
)";

struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

struct Options
{
  std::vector<std::string> Scenes = { "sphere", "bunny" };
  std::vector<long long> Points = { 100000, 1000000 };
  std::vector<long long> Sizes = { 512, 1024 };
  std::vector<std::string> Mappers = { "splat", "pointgaussian" };
  int Frames = 10;
  int MinFrames = 3;
  double Budget = 10.0;
  std::string Output = "output/bench/bench.csv";
  std::string ImageDir;
};

std::vector<std::string> SplitList(
  const std::string& option, const std::string& text, const std::vector<std::string>& allowed)
{
  std::vector<std::string> items;
  std::istringstream fields(text);
  std::string item;
  while (std::getline(fields, item, ','))
  {
    if (std::find(allowed.begin(), allowed.end(), item) == allowed.end())
    {
      std::string names;
      for (const auto& name : allowed)
      {
        names += (names.empty() ? "" : ", ") + name;
      }
      throw UsageError(option + ": unknown '" + item + "' (choose from " + names + ")");
    }
    items.push_back(item);
  }
  if (items.empty())
  {
    throw UsageError(option + ": the list is empty");
  }
  return items;
}

long long ParseCount(
  const std::string& option, const std::string& text, long long low, long long high)
{
  char* end = nullptr;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value < low || value > high)
  {
    throw UsageError(option + ": expected a whole number from " + std::to_string(low) + " to " +
      std::to_string(high) + ", got '" + text + "'");
  }
  return value;
}

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

// Long GNU-style options: "--name VALUE" or "--name=VALUE".
Options ParseCommandLine(int argc, char* argv[])
{
  Options options;
  using Handler = std::function<void(const std::string&, const std::string&)>;
  const std::map<std::string, Handler> handlers = {
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
    { "--frames",
      [&](const std::string& name, const std::string& value)
      {
        options.Frames = static_cast<int>(ParseCount(name, value, 1, 100000));
        options.MinFrames = std::min(options.MinFrames, options.Frames);
      } },
    { "--budget",
      [&](const std::string& name, const std::string& value)
      { options.Budget = static_cast<double>(ParseCount(name, value, 0, 86400)); } },
    { "--output", [&](const std::string&, const std::string& value) { options.Output = value; } },
    { "--image-dir",
      [&](const std::string&, const std::string& value) { options.ImageDir = value; } },
  };

  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--help")
    {
      std::cout << Usage;
      std::exit(EXIT_SUCCESS);
    }
    if (argument == "--quick")
    {
      options.Points = { 20000 };
      options.Sizes = { 256 };
      options.Frames = 2;
      options.MinFrames = 1;
      continue;
    }
    const auto equals = argument.find('=');
    const std::string name = argument.substr(0, equals);
    const auto handler = handlers.find(name);
    if (handler == handlers.end())
    {
      throw UsageError("unknown argument '" + name + "' (see --help)");
    }
    if (equals == std::string::npos && i + 1 == argc)
    {
      throw UsageError(name + " needs a value (see --help)");
    }
    handler->second(name, equals == std::string::npos ? argv[++i] : argument.substr(equals + 1));
  }
  return options;
}

// n points uniformly spread on the unit sphere (Fibonacci lattice) with radial normals and the
// radius sqrt(4 pi / n) of the sampling spacing, at which the splats just cover the sphere.
vtkSmartPointer<vtkPolyData> FibonacciSphere(vtkIdType n)
{
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  radii->SetNumberOfTuples(n);
  const double golden = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  const float spacing = static_cast<float>(std::sqrt(4.0 * vtkMath::Pi() / n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(1.0 - z * z);
    const double longitude = golden * i;
    const double p[3] = { r * std::cos(longitude), r * std::sin(longitude), z };
    points->SetPoint(i, p);
    normals->SetTuple(i, p);
    radii->SetValue(i, spacing);
  }
  auto sphere = vtkSmartPointer<vtkPolyData>::New();
  sphere->SetPoints(points);
  sphere->GetPointData()->SetNormals(normals);
  sphere->GetPointData()->AddArray(radii);
  return sphere;
}

// The bunny's vertices as surfels, or nullptr when bunny.ply is absent.
vtkSmartPointer<vtkPolyData> BunnySurfels()
{
  std::string folder;
  if (!vtksys::SystemTools::GetEnv("SPLAT_DATA_DIR", folder) || folder.empty())
  {
    folder = vtksys::SystemTools::CollapseFullPath(SPLAT_SOURCE_DIR "/../shared/data");
  }
  const std::string file = folder + "/bunny.ply";
  if (!vtkPLYReader::CanReadFile(file.c_str()))
  {
    std::cerr << "splat_bench: bunny skipped: " << file << " is absent or unreadable\n";
    return nullptr;
  }
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(file.c_str());
  vtkNew<vtkSurfelGenerator> surfels;
  surfels->SetInputConnection(reader->GetOutputPort());
  surfels->Update();
  return surfels->GetOutput();
}

struct MapperKind
{
  const char* Name;    // the option's name
  const char* Class;   // the VTK class (vtkPointGaussianMapper::New gives an OpenGL subclass)
  const char* Backend; // what draws the splats
  const char* Setting;
};

const MapperKind Kinds[] = {
  { "splat", "vtkSurfaceSplatMapper", "CPU", "default" },
  { "pointgaussian", "vtkPointGaussianMapper", "OpenGL", "disk" },
};

// vtkPointGaussianMapper draws opaque disks of the splats' world-space radius: the like-for-like
// surface rendering. Its default Gaussian shader with emissive off blends unsorted translucent
// blobs whose depth writes hide one another: mostly background shows through.
const char* const DiskShader = "//VTK::Color::Impl\n"
                               "float dist2 = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);\n"
                               "if (dist2 > 1.0) { discard; }\n";

vtkSmartPointer<vtkMapper> MakeMapper(const MapperKind& kind, vtkPolyData* surfels)
{
  if (std::string(kind.Name) == "splat")
  {
    vtkNew<vtkSurfaceSplatMapper> mapper;
    mapper->SetInputData(surfels);
    return mapper;
  }
  vtkNew<vtkPointGaussianMapper> mapper;
  mapper->SetInputData(surfels);
  mapper->SetScaleArray("Radius");
  mapper->SetScaleFactor(1.0);
  mapper->EmissiveOff();
  mapper->SetSplatShaderCode(DiskShader);
  // The disk has radius 1 in splat units: a larger triangle would only shade discarded fragments.
  mapper->SetTriangleScale(1.0);
  return mapper;
}

double PeakResidentMegabytes()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0; // kilobytes on Linux
}

// Median milliseconds per frame after a warm-up frame (surfel build, buffer upload, shader
// compilation): at least MinFrames, at most Frames, and no more once the budget is spent.
double MillisecondsPerFrame(vtkRenderWindow* window, const Options& options)
{
  using Clock = std::chrono::steady_clock;
  window->Render();
  window->WaitForCompletion();
  std::vector<double> ms;
  const auto start = Clock::now();
  while (static_cast<int>(ms.size()) < options.Frames &&
    (static_cast<int>(ms.size()) < options.MinFrames ||
      std::chrono::duration<double>(Clock::now() - start).count() < options.Budget))
  {
    const auto frameStart = Clock::now();
    window->Render();
    // OpenGL runs asynchronously: the frame is done when the GL queue is.
    window->WaitForCompletion();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - frameStart).count());
  }
  std::sort(ms.begin(), ms.end());
  const std::size_t n = ms.size();
  return n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
}

void WritePNG(vtkRenderWindow* window, const std::string& path)
{
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(window);
  image->SetInputBufferTypeToRGB();
  image->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != vtkErrorCode::NoError)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

void MakeDirectory(const std::string& folder)
{
  if (!folder.empty() && !vtksys::SystemTools::MakeDirectory(folder))
  {
    throw std::runtime_error("cannot create the folder '" + folder + "'");
  }
}

// Renders one scene at every size with every mapper into `window` and emits a CSV row per case;
// returns the number of rows.
int MeasureScene(vtkRenderWindow* window, const std::string& scene, vtkPolyData* surfels,
  const Options& options, std::ostream& csv)
{
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  const vtkIdType points = surfels->GetNumberOfPoints();
  int rows = 0;
  for (long long size : options.Sizes)
  {
    for (const auto& name : options.Mappers)
    {
      const MapperKind& kind = *std::find_if(
        std::begin(Kinds), std::end(Kinds), [&](const MapperKind& k) { return name == k.Name; });
      std::cerr << "splat_bench: " << scene << ", " << points << " points, " << size << "x" << size
                << ", " << kind.Class << "\n";
      vtkNew<vtkActor> actor;
      actor->SetMapper(MakeMapper(kind, surfels));
      actor->GetProperty()->SetColor(0.85, 0.75, 0.6);
      renderer->RemoveAllViewProps(); // the previous case, with its graphics resources
      renderer->AddActor(actor);
      window->SetSize(static_cast<int>(size), static_cast<int>(size));
      // The same view for both mappers: their bounds differ (ours include the splat radii).
      renderer->ResetCamera(surfels->GetBounds());

      const double ms = MillisecondsPerFrame(window, options);
      std::ostringstream row;
      row << scene << "," << kind.Class << "," << kind.Backend << "," << kind.Setting << ","
          << points << "," << size << "," << size << "," << std::fixed << std::setprecision(2) << ms
          << "," << std::setprecision(0) << points / (ms * 1e-3) << "," << std::setprecision(1)
          << PeakResidentMegabytes() << "\n";
      std::cout << row.str() << std::flush;
      csv << row.str() << std::flush;
      ++rows;

      if (!options.ImageDir.empty())
      {
        WritePNG(window,
          options.ImageDir + "/" + scene + "-" + std::to_string(points) + "-" +
            std::to_string(size) + "-" + kind.Name + ".png");
      }
    }
  }
  return rows;
}

int Run(const Options& options)
{
  MakeDirectory(vtksys::SystemTools::GetFilenamePath(options.Output));
  MakeDirectory(options.ImageDir);
  std::ofstream csv(options.Output);
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + options.Output + "'");
  }
  const char* const header =
    "scene,mapper,backend,setting,points,width,height,ms_per_frame,splats_per_s,peak_rss_mb\n";
  std::cout << header << std::flush;
  csv << header << std::flush;

  // One window for every case: each window opens its own X display connection, and an X server
  // (Xvfb) that resets when its last client disconnects can refuse the next window's connection.
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);

  // The process's peak memory only grows: the small bunny first, then the spheres by size.
  const auto wants = [&](const char* scene) {
    return std::find(options.Scenes.begin(), options.Scenes.end(), scene) != options.Scenes.end();
  };
  int rows = 0;
  if (wants("bunny"))
  {
    if (auto bunny = BunnySurfels())
    {
      rows += MeasureScene(window, "bunny", bunny, options, csv);
    }
  }
  if (wants("sphere"))
  {
    for (long long n : options.Points)
    {
      rows +=
        MeasureScene(window, "sphere", FibonacciSphere(static_cast<vtkIdType>(n)), options, csv);
    }
  }
  std::cerr << "splat_bench: " << rows << " rows; CSV written to "
            << vtksys::SystemTools::CollapseFullPath(options.Output) << "\n";
  return rows > 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
}

int main(int argc, char* argv[])
{
  try
  {
    return Run(ParseCommandLine(argc, argv));
  }
  catch (const UsageError& e)
  {
    std::cerr << "splat_bench: " << e.what() << "\n";
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "splat_bench: error: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
}
