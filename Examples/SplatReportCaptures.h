// SPDX-License-Identifier: BSD-3-Clause
// splat_report's capture section: 3D Gaussian Splatting captures drawn by vtkVolumeSplatMapper
// in every ordering mode and footprint filter, against the image they were trained to produce
// (the published rasterizer's rules, Testing/Cxx/SplatCaptureReference.h, which
// TestVolumeSplatCapture asserts against). Captures: the bench's generated torus
// (SplatCaptureScene.h, 100 000 Gaussians of degree 3) and the real captures of the shared
// data folder when present (donut_fused.ply, fruit_drops_minimal.ply), each from the views of
// splattest::CaptureViews. Per capture, setting and backend: the PSNR against the reference of
// each view (the worst and the mean over the views) and the ms per frame (the mean over the
// views of the mapper's time of the frames after the first). Then the popping of the depth and
// per-pixel orders as the camera turns (MeasureTurns). Writes captures.csv and captures.md.
#ifndef SplatReportCaptures_h
#define SplatReportCaptures_h

#include "SplatCaptureReference.h"
#include "SplatCaptureScene.h"
#include "SplatExampleUtilities.h"
#include "SplatReportCases.h"
#include "SplatVolumeTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkCamera.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace splatreport
{
// A setting of the capture table: an ordering mode and a footprint filter.
struct CaptureSetting
{
  std::string Name;
  int Ordering;
  int Filter;
};

inline std::vector<CaptureSetting> CaptureSettings()
{
  using M = vtkVolumeSplatMapper;
  return { { "default (depth-sorted, dilation)", M::AUTOMATIC, M::AUTOMATIC_FILTER },
    { "depth-sorted, antialiased", M::DEPTH_SORTED, M::ANTIALIASED_FILTER },
    { "depth-sorted, low-pass", M::DEPTH_SORTED, M::LOW_PASS_FILTER },
    { "blended", M::BLENDED, M::AUTOMATIC_FILTER },
    { "clipped", M::CLIPPED, M::AUTOMATIC_FILTER },
    { "single-axis", M::SINGLE_AXIS, M::AUTOMATIC_FILTER },
    { "pixel-sorted", M::PIXEL_SORTED, M::AUTOMATIC_FILTER } };
}

// A capture in a render window of its own, drawn by vtkVolumeSplatMapper with a backend and
// setting from views turned by `azimuth` degrees about their focal points: the image (RGB,
// rows from the bottom), the reference camera of the render and the mean ms of the frames
// after the first.
struct CaptureImage
{
  std::vector<double> RGB;
  splattest::ReferenceCamera Camera;
  double Ms = 0.0;
};

class CaptureRenderer
{
public:
  CaptureRenderer(vtkPointSet* data, int backend, const CaptureSetting& setting, int size)
    : Size(size)
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(size, size);
    this->Renderer->SetBackground(0.0, 0.0, 0.0);
    this->Window->AddRenderer(this->Renderer);
    this->Mapper->SetInputData(data);
    this->Mapper->SetBackend(backend);
    this->Mapper->SetOrderingMode(setting.Ordering);
    this->Mapper->SetFootprintFilter(setting.Filter);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
  }

  CaptureImage Draw(const splattest::CaptureView& view, int frames, double azimuth = 0.0)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(view.Position.data());
    camera->SetFocalPoint(view.FocalPoint.data());
    camera->SetViewUp(view.Up.data());
    camera->Azimuth(azimuth);
    this->Renderer->ResetCameraClippingRange();
    CaptureImage image;
    for (int frame = 0; frame < frames; ++frame)
    {
      this->Window->Render();
      image.Ms +=
        frame > 0 ? this->Mapper->GetLastRenderTimeInMilliseconds() / (frames - 1) : 0.0;
    }
    image.RGB = splattest::ToRGB(splattest::Capture(this->Window));
    image.Camera = splattest::ReferenceCameraOf(camera, this->Size, this->Size);
    return image;
  }

private:
  int Size;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolumeSplatMapper> Mapper;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkVolume> Volume;
};

// The popping table (see the file comment) of the captures on the CPU, the depth order against
// the per-pixel order.
inline std::string MeasureTurns(
  const std::vector<splattest::CaptureScene>& captures, int size, int frames)
{
  using M = vtkVolumeSplatMapper;
  constexpr int Steps = 10; // of a twentieth of a degree: half a degree
  std::ostringstream table;
  table << "| capture | order | pops per pixel and half degree (%) | mean change over half a "
        << "degree | ms/frame |\n|---|---|---:|---:|---:|\n";
  for (const splattest::CaptureScene& capture : captures)
  {
    std::cerr << "splat_report: captures, turns, " << capture.Name << std::endl;
    for (const CaptureSetting& order :
      { CaptureSetting{ "depth-sorted", M::DEPTH_SORTED, M::AUTOMATIC_FILTER },
        CaptureSetting{ "pixel-sorted", M::PIXEL_SORTED, M::AUTOMATIC_FILTER } })
    {
      CaptureRenderer renderer(capture.Data, vtkSplatBackend::CPU, order, size);
      double pops = 0.0, change = 0.0, ms = 0.0;
      for (const splattest::CaptureView& view : capture.Views)
      {
        std::vector<std::vector<double>> images;
        for (int step = 0; step <= Steps; ++step)
        {
          const CaptureImage image =
            renderer.Draw(view, step == 0 ? frames : 1, 0.5 * step / Steps);
          images.push_back(image.RGB);
          ms += image.Ms;
        }
        const std::size_t values = images[0].size();
        for (std::size_t p = 0; p < values; p += 3)
        {
          for (int step = 1; step < Steps; ++step)
          {
            double bend = 0.0;
            for (std::size_t c = p; c < p + 3; ++c)
            {
              bend = std::max(bend,
                std::abs(images[step - 1][c] - 2.0 * images[step][c] + images[step + 1][c]));
            }
            pops += bend > 0.1 ? 3.0 / values : 0.0;
          }
          for (std::size_t c = p; c < p + 3; ++c)
          {
            change += std::abs(images[Steps][c] - images[0][c]) / values;
          }
        }
      }
      const double views = static_cast<double>(capture.Views.size());
      table << "| " << capture.Name << " | " << order.Name << " | "
            << Fixed(100.0 * pops / views, 2) << " | " << Fixed(change / views, 4) << " | "
            << Fixed(ms / views, 1) << " |\n";
    }
  }
  std::ostringstream md;
  md << "### popping as the camera turns\n\n"
     << "The same captures and views on the CPU, each turned about its focal point by half a "
     << "degree in " << Steps << " steps. A pixel pops at a step when its second difference "
     << "I(k - 1) - 2 I(k) + I(k + 1) exceeds 0.1 in a channel: over such small steps a "
     << "smooth change (the image moving by a fifth of a pixel a step) is nearly linear, while "
     << "a Gaussian passing in front of another is a jump. The pops are counted over the steps "
     << "per pixel; the mean change is that of a channel from the view to the view turned by "
     << "half a degree. `pixel-sorted` orders each pixel's Gaussians by their depths along its "
     << "ray (StopThePop), through a window of the last 32 kernels of each group of eight pixels. "
     << "Means over the views; "
     << "ms/frame as above.\n\n"
     << table.str() << "\n";
  return md.str();
}

// Measures the captures on the volume backends of `options`; writes captures.csv and
// captures.md; returns the Markdown section.
inline std::string MeasureCaptures(const Options& options)
{
  constexpr int Size = 320;
  std::vector<splattest::CaptureScene> captures = { { "torus (generated)",
    splatexample::SyntheticCapture(100000, 3), 3, splattest::CaptureViews({ 0, 0, 0 }, 0.8) } };
  const std::string data = vtksys::SystemTools::GetFilenamePath(splatexample::BunnyFile());
  for (const char* file : { "donut_fused.ply", "fruit_drops_minimal.ply" })
  {
    if (vtksys::SystemTools::FileExists(data + "/" + file, true))
    {
      captures.push_back(splattest::ReadCapture(data + "/" + file));
    }
  }
  const int frames = std::max(2, options.Frames + 1);
  std::ostringstream csv, table;
  csv << "capture,kernels,setting,backend,views,min_psnr_db,mean_psnr_db,ms_per_frame\n";
  table << "| capture | setting | backend | PSNR, worst view (dB) | PSNR, mean (dB) | ms/frame |\n"
        << "|---|---|---|---:|---:|---:|\n";
  for (const splattest::CaptureScene& capture : captures)
  {
    // The reference images, one per view, from the cameras the mapper draws with.
    std::vector<std::vector<double>> references;
    for (const std::string& backendName : options.VolumeBackends)
    {
      const int backend =
        backendName == "opengl" ? vtkSplatBackend::OPENGL : vtkSplatBackend::CPU;
      for (const CaptureSetting& setting : CaptureSettings())
      {
        std::cerr << "splat_report: captures, " << capture.Name << ", " << setting.Name << ", "
                  << backendName << std::endl;
        double worst = 1e9, sum = 0.0, ms = 0.0;
        for (std::size_t v = 0; v < capture.Views.size(); ++v)
        {
          const splattest::CaptureView& view = capture.Views[v];
          const CaptureImage image =
            CaptureRenderer(capture.Data, backend, setting, Size).Draw(view, frames);
          ms += image.Ms;
          if (references.size() <= v)
          {
            references.push_back(
              splattest::RenderReference(capture.Data, image.Camera, capture.Degree));
          }
          const double psnr = splattest::PSNR(image.RGB, references[v]);
          worst = std::min(worst, psnr);
          sum += psnr;
        }
        const double views = static_cast<double>(capture.Views.size());
        csv << capture.Name << "," << capture.Data->GetNumberOfPoints() << ",\"" << setting.Name
            << "\"," << backendName << "," << capture.Views.size() << "," << Fixed(worst, 2)
            << "," << Fixed(sum / views, 2) << "," << Fixed(ms / views, 2) << "\n";
        table << "| " << capture.Name << " | " << setting.Name << " | " << backendName << " | "
              << Fixed(worst, 1) << " | " << Fixed(sum / views, 1) << " | "
              << Fixed(ms / views, 1) << " |\n";
      }
    }
  }
  const std::string turns = MeasureTurns(captures, Size, frames);
  const std::string csvPath = options.OutputDir + "/captures.csv";
  std::ofstream file(csvPath);
  file << csv.str();
  if (!file)
  {
    throw std::runtime_error("cannot write '" + csvPath + "'");
  }
  std::ostringstream md;
  md << "## captures\n\n"
     << "3D Gaussian Splatting captures against the image they were trained to produce: the "
     << "published rasterizer's rules written again in `Testing/Cxx/SplatCaptureReference.h` "
     << "(the reference `TestVolumeSplatCapture` asserts 45 dB against), " << Size << "x" << Size
     << ", black background, " << "the views of `splattest::CaptureViews` (three outside, two "
     << "inside). The default (`AUTOMATIC` ordering and filter) is the exact depth order with "
     << "the 0.3 px^2 dilation; the antialiased and low-pass filters are measured against the "
     << "same (trained) reference, so their PSNR is what they change, not an error. ms/frame: "
     << "the mapper's time, the mean over the views of " << frames - 1 << " frames after the "
     << "first. `captures.csv` has the figures.\n\n"
     << table.str() << "\n" << turns;
  std::ofstream mdFile(options.OutputDir + "/captures.md");
  mdFile << md.str();
  return md.str();
}
}

#endif
