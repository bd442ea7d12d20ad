// SPDX-License-Identifier: BSD-3-Clause
// One splat mapper shared by two renderers, in one window and in two windows, and two windows
// with a mapper each rendering in two threads at once, give the images of one renderer drawn at
// a time (issue 16). The two views differ in color (each actor or volume has its own property)
// and zoom, so that state kept from one renderer and reused by the other shows.
//
// Usage: TestSplatSharing -mapper surface|volume -backend cpu|opengl [-T DIR]
// -T writes each image that differs from its reference (and the reference) there.
#include "SplatTestUtilities.h"
#include "SplatVolumeTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkPNGWriter.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <X11/Xlib.h> // XInitThreads

#include <array>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

namespace
{
constexpr int Width = 160;
constexpr int Height = 120;
constexpr int Views = 2;

struct Settings
{
  bool Volume = false;
  int Backend = vtkSplatBackend::CPU;
  std::string OutputDir;
};

// The input of either mapper: a surfel sphere or a Gaussian blob as image data.
vtkSmartPointer<vtkDataSet> MakeData(const Settings& settings)
{
  if (settings.Volume)
  {
    return splattest::GaussianBlob(24, 1.0 / 12.0, 0.35, 4.0).GetPointer();
  }
  return splattest::SurfelSphere(5000, 1.0).GetPointer();
}

vtkSmartPointer<vtkAbstractMapper3D> MakeMapper(const Settings& settings, vtkDataSet* data)
{
  if (settings.Volume)
  {
    vtkNew<vtkVolumeSplatMapper> mapper;
    mapper->SetInputData(data);
    mapper->SetBackend(settings.Backend);
    return mapper.GetPointer();
  }
  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(vtkPolyData::SafeDownCast(data));
  mapper->SetBackend(settings.Backend);
  return mapper.GetPointer();
}

// View `view` of `mapper` in `renderer`: its own actor or volume and property (orange or
// blue), the camera reset on the data and zoomed by 1 or 1.6.
void AddView(vtkRenderer* renderer, vtkAbstractMapper3D* mapper, int view, bool volume)
{
  const double rgb[Views][3] = { { 0.9, 0.5, 0.2 }, { 0.2, 0.5, 0.9 } };
  if (volume)
  {
    splattest::AddVolume(renderer, vtkVolumeSplatMapper::SafeDownCast(mapper),
      splattest::ExtinctionProperty(4.0, 1.0, rgb[view]));
  }
  else
  {
    vtkNew<vtkActor> actor;
    actor->SetMapper(vtkSurfaceSplatMapper::SafeDownCast(mapper));
    actor->GetProperty()->SetColor(rgb[view][0], rgb[view][1], rgb[view][2]);
    renderer->AddActor(actor);
  }
  renderer->SetBackground(0.1, 0.1, 0.1);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(view == 0 ? 1.0 : 1.6);
}

// A window of `width` x Height with one renderer per view in `views` side by side, each with its
// own view of `mappers[view]`.
vtkSmartPointer<vtkRenderWindow> MakeWindow(int width, const std::array<int, Views>& views,
  int count, const std::array<vtkAbstractMapper3D*, Views>& mappers, bool volume)
{
  vtkSmartPointer<vtkRenderWindow> window = splattest::MakeRenderWindow(width, Height);
  for (int i = 0; i < count; ++i)
  {
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(static_cast<double>(i) / count, 0.0, (i + 1.0) / count, 1.0);
    window->AddRenderer(renderer);
    AddView(renderer, mappers[i], views[i], volume);
  }
  return window;
}

// Renders twice (the first frame builds the splats) and captures.
vtkSmartPointer<vtkImageData> RenderAndCapture(vtkRenderWindow* window)
{
  window->Render();
  window->Render();
  return splattest::Capture(window);
}

// The number of pixels where a and b differ; writes both images to the output folder when they
// do.
int DifferingPixels(vtkImageData* a, vtkImageData* b, const std::string& name,
  const Settings& settings)
{
  const std::vector<double> x = splattest::ToRGB(a);
  const std::vector<double> y = splattest::ToRGB(b);
  if (x.size() != y.size())
  {
    return static_cast<int>(std::max(x.size(), y.size()) / 3);
  }
  int differing = 0;
  for (std::size_t i = 0; i < x.size(); i += 3)
  {
    differing += x[i] != y[i] || x[i + 1] != y[i + 1] || x[i + 2] != y[i + 2];
  }
  if (differing > 0 && !settings.OutputDir.empty())
  {
    for (auto image : { std::make_pair(a, "-result.png"), std::make_pair(b, "-reference.png") })
    {
      vtkNew<vtkPNGWriter> writer;
      writer->SetInputData(image.first);
      writer->SetFileName((settings.OutputDir + "/" + name + image.second).c_str());
      writer->Write();
    }
  }
  return differing;
}

bool Check(int differing, const std::string& what)
{
  std::cout << what << ": " << differing << " pixels differ from one renderer at a time\n";
  return differing == 0;
}

// Whether the view drawn and the image rendered show something: the splats must be there for
// the comparison to mean anything.
bool ShowsSplats(vtkImageData* image)
{
  const std::vector<double> rgb = splattest::ToRGB(image);
  int lit = 0;
  for (std::size_t i = 0; i < rgb.size(); i += 3)
  {
    lit += rgb[i] + rgb[i + 1] + rgb[i + 2] > 0.5;
  }
  return lit > static_cast<int>(rgb.size() / 3 / 20);
}

bool Run(const Settings& settings)
{
  const std::string prefix = std::string(settings.Volume ? "volume" : "surface") + "-" +
    vtkSplatBackend::GetBackendAsString(settings.Backend);
  vtkSmartPointer<vtkDataSet> data = MakeData(settings);
  bool ok = true;

  // References: each view alone in its window with its own mapper.
  std::array<vtkSmartPointer<vtkImageData>, Views> alone;
  for (int view = 0; view < Views; ++view)
  {
    vtkSmartPointer<vtkAbstractMapper3D> mapper = MakeMapper(settings, data);
    alone[view] = RenderAndCapture(
      MakeWindow(Width, { view, 0 }, 1, { mapper.Get(), nullptr }, settings.Volume));
    if (!ShowsSplats(alone[view]))
    {
      std::cerr << "view " << view << " shows nothing\n";
      ok = false;
    }
  }
  if (!ok)
  {
    return false;
  }

  // One window, two renderers side by side: one mapper for both against a mapper each.
  {
    vtkSmartPointer<vtkAbstractMapper3D> first = MakeMapper(settings, data);
    vtkSmartPointer<vtkAbstractMapper3D> second = MakeMapper(settings, data);
    vtkSmartPointer<vtkImageData> separate = RenderAndCapture(
      MakeWindow(2 * Width, { 0, 1 }, 2, { first.Get(), second.Get() }, settings.Volume));
    vtkSmartPointer<vtkAbstractMapper3D> shared = MakeMapper(settings, data);
    vtkSmartPointer<vtkImageData> together = RenderAndCapture(
      MakeWindow(2 * Width, { 0, 1 }, 2, { shared.Get(), shared.Get() }, settings.Volume));
    ok = Check(DifferingPixels(together, separate, prefix + "-one-window", settings),
           "one mapper, two renderers in one window") &&
      ok;
  }

  // Two windows (two OpenGL contexts) sharing one mapper, drawn in turn twice: the second
  // round draws the first window again after the second.
  {
    vtkSmartPointer<vtkAbstractMapper3D> shared = MakeMapper(settings, data);
    std::array<vtkSmartPointer<vtkRenderWindow>, Views> windows;
    std::array<vtkSmartPointer<vtkImageData>, Views> images;
    for (int view = 0; view < Views; ++view)
    {
      windows[view] =
        MakeWindow(Width, { view, 0 }, 1, { shared.Get(), nullptr }, settings.Volume);
    }
    for (int round = 0; round < 2; ++round)
    {
      for (int view = 0; view < Views; ++view)
      {
        images[view] = RenderAndCapture(windows[view]);
      }
    }
    for (int view = 0; view < Views; ++view)
    {
      ok = Check(DifferingPixels(images[view], alone[view],
                   prefix + "-two-windows-" + std::to_string(view), settings),
             "one mapper in two windows, view " + std::to_string(view)) &&
        ok;
    }
  }

  // Two windows with a mapper each, made and rendered in two threads at once (a copy of the
  // data each: a pipeline update is not thread-safe).
  {
    std::array<vtkSmartPointer<vtkImageData>, Views> images;
    std::array<std::thread, Views> threads;
    for (int view = 0; view < Views; ++view)
    {
      vtkSmartPointer<vtkDataSet> copy = vtkSmartPointer<vtkDataSet>::Take(data->NewInstance());
      copy->DeepCopy(data);
      threads[view] = std::thread(
        [&settings, &images, copy, view]()
        {
          vtkSmartPointer<vtkAbstractMapper3D> mapper = MakeMapper(settings, copy);
          vtkSmartPointer<vtkRenderWindow> window =
            MakeWindow(Width, { view, 0 }, 1, { mapper.Get(), nullptr }, settings.Volume);
          for (int frame = 0; frame < 4; ++frame)
          {
            window->Render();
          }
          images[view] = splattest::Capture(window);
          window->Finalize();
        });
    }
    for (std::thread& thread : threads)
    {
      thread.join();
    }
    for (int view = 0; view < Views; ++view)
    {
      ok = Check(DifferingPixels(images[view], alone[view],
                   prefix + "-threads-" + std::to_string(view), settings),
             "two windows in two threads, view " + std::to_string(view)) &&
        ok;
    }
  }
  return ok;
}
}

int main(int argc, char* argv[])
{
  // Xlib is called from both threads (each window's own display connection).
  XInitThreads();
  Settings settings;
  settings.Volume = splattest::Argument(argc, argv, "-mapper") == "volume";
  settings.Backend = splattest::Argument(argc, argv, "-backend") == "opengl"
    ? vtkSplatBackend::OPENGL
    : vtkSplatBackend::CPU;
  settings.OutputDir = splattest::Argument(argc, argv, "-T");
  return Run(settings) ? EXIT_SUCCESS : EXIT_FAILURE;
}
