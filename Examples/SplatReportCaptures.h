// SPDX-License-Identifier: BSD-3-Clause
// splat_report's capture section: 3D Gaussian Splatting captures drawn by vtkVolumeSplatMapper
// in every ordering mode and footprint filter, against the image they were trained to produce
// (the published rasterizer's rules, Testing/Cxx/SplatCaptureReference.h, which
// TestVolumeSplatCapture asserts against). Captures: the bench's generated torus
// (SplatCaptureScene.h, 100 000 Gaussians of degree 3) and the real captures of the shared
// data folder when present (donut_fused.ply, fruit_drops_minimal.ply), each from the views of
// splattest::CaptureViews. Per capture, setting and backend: the PSNR against the reference of
// each view (the worst and the mean over the views) and the ms per frame (the mean over the
// views of the mapper's time of the frames after the first). Writes captures.csv and
// captures.md.
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
    { "single-axis", M::SINGLE_AXIS, M::AUTOMATIC_FILTER } };
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
          vtkNew<vtkRenderWindow> window;
          window->SetOffScreenRendering(1);
          window->SetMultiSamples(0);
          window->SetSize(Size, Size);
          vtkNew<vtkRenderer> renderer;
          renderer->SetBackground(0.0, 0.0, 0.0);
          window->AddRenderer(renderer);
          vtkNew<vtkVolumeSplatMapper> mapper;
          mapper->SetInputData(capture.Data);
          mapper->SetBackend(backend);
          mapper->SetOrderingMode(setting.Ordering);
          mapper->SetFootprintFilter(setting.Filter);
          vtkNew<vtkVolumeProperty> property;
          vtkNew<vtkVolume> volume;
          volume->SetMapper(mapper);
          volume->SetProperty(property);
          renderer->AddVolume(volume);
          vtkCamera* camera = renderer->GetActiveCamera();
          camera->SetPosition(view.Position.data());
          camera->SetFocalPoint(view.FocalPoint.data());
          camera->SetViewUp(view.Up.data());
          renderer->ResetCameraClippingRange();
          double viewMs = 0.0;
          for (int frame = 0; frame < frames; ++frame)
          {
            window->Render();
            viewMs += frame > 0 ? mapper->GetLastRenderTimeInMilliseconds() : 0.0;
          }
          ms += viewMs / (frames - 1);
          if (references.size() <= v)
          {
            references.push_back(splattest::RenderReference(capture.Data,
              splattest::ReferenceCameraOf(camera, Size, Size), capture.Degree));
          }
          const double psnr = splattest::PSNR(splattest::ToRGB(splattest::Capture(window)), references[v]);
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
     << table.str() << "\n";
  std::ofstream mdFile(options.OutputDir + "/captures.md");
  mdFile << md.str();
  return md.str();
}
}

#endif
