// SPDX-License-Identifier: BSD-3-Clause
// 3D Gaussian Splatting captures drawn as they were trained: vtkVolumeSplatMapper with its
// defaults (AUTOMATIC ordering and filter: the exact depth order through
// vtkGaussianSplatRasterizer, the 0.3 px^2 dilation) against the published rasterizer's rules
// written again in SplatCaptureReference.h (its file comment holds the camera, pixel-center and
// image-orientation conventions), at 320 x 320, from cameras outside and inside the capture's
// bounds:
// - every view's PSNR at least MIN_PSNR (dB) on the CPU backend, MIN_OPENGL_PSNR on OpenGL
//   (the same order and rules in shaders, blended in single precision without the early stop);
// - the antialiased and low-pass filters against the reference drawn with the same filter,
//   also at least MIN_PSNR, and each differs from the default image seen from outside;
// - the defaults resolve to DEPTH_SORTED and the dilation for captures, to BLENDED for image
//   data;
// - the same image for 1 and 2 threads;
// - the PIXEL_SORTED ordering (each pixel's order by the depth along its ray at which each
//   Gaussian peaks, StopThePop) against the reference sorted per pixel: on crossing sheets,
//   where the two orders differ by more than MAX_ORDER_PSNR, at least MIN_PSNR; on the
//   captures, whose pixels see more Gaussians than the mapper's window of eight reorders, its
//   PSNR against both references is printed; OpenGL draws DEPTH_SORTED for it;
// - the blended axis lists' PSNR is printed, for the record.
// Without arguments the capture is generated (the bench's torus, splatexample::SyntheticCapture,
// spherical harmonics of degree 3); with --real the two real captures of the shared data
// folder (-D DIR) are read by vtkGaussianSplatReader, and the test skips when they are absent.
#include "SplatCaptureReference.h"
#include "SplatCaptureScene.h"
#include "SplatTestUtilities.h"
#include "SplatVolumeTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPointSet.h"
#include "vtkRenderWindow.h"
#include "vtkRendererCollection.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
constexpr int Size = 320;
using splattest::Check;

struct Rendered
{
  std::vector<double> RGB;
  splattest::ReferenceCamera Camera;
};

// The capture drawn by the mapper (CPU backend unless another is given) from the view; the
// reference camera of the render (its clipping range is the one the mapper used).
Rendered Draw(vtkVolumeSplatMapper* mapper, vtkPointSet* data, const splattest::CaptureView& view,
  int backend = vtkSplatBackend::CPU)
{
  mapper->SetBackend(backend);
  auto window = splattest::DrawVolume(
    mapper, data, view.Position.data(), view.FocalPoint.data(), view.Up.data(), Size);
  vtkCamera* camera = window->GetRenderers()->GetFirstRenderer()->GetActiveCamera();
  Rendered out;
  out.RGB = splattest::ToRGB(splattest::Capture(window));
  out.Camera = splattest::ReferenceCameraOf(camera, Size, Size);
  return out;
}

void TestCapture(const splattest::CaptureScene& capture)
{
  for (const splattest::CaptureView& view : capture.Views)
  {
    const std::string where = capture.Name + " " + view.Name;
    vtkNew<vtkVolumeSplatMapper> mapper;
    const Rendered image = Draw(mapper, capture.Data, view);
    const std::vector<double> reference =
      splattest::RenderReference(capture.Data, image.Camera, capture.Degree);
    const double psnr = splattest::PSNR(image.RGB, reference);
    std::printf("%s: default %.1f dB (%lld drawn, %lld near)", where.c_str(), psnr,
      static_cast<long long>(mapper->GetNumberOfProjectedKernels()),
      static_cast<long long>(mapper->GetNumberOfNearPlaneKernels()));
    Check(psnr >= MIN_PSNR, where + ": PSNR " + std::to_string(psnr) + " dB against the reference");
    Check(mapper->GetLastOrderingMode() == vtkVolumeSplatMapper::DEPTH_SORTED,
      where + ": the default ordering of a capture is not DEPTH_SORTED");
    vtkNew<vtkVolumeSplatMapper> gpu;
    const double opengl = splattest::PSNR(
      Draw(gpu, capture.Data, view, vtkSplatBackend::OPENGL).RGB, reference);
    std::printf(", OpenGL %.1f dB", opengl);
    Check(gpu->GetLastBackend() == vtkSplatBackend::OPENGL, where + ": OpenGL did not draw");
    Check(opengl >= MIN_OPENGL_PSNR,
      where + ": OpenGL PSNR " + std::to_string(opengl) + " dB against the reference");

    // The other filters against the reference drawn with the same filter.
    for (const int filter :
      { vtkVolumeSplatMapper::ANTIALIASED_FILTER, vtkVolumeSplatMapper::LOW_PASS_FILTER })
    {
      const bool antialiased = filter == vtkVolumeSplatMapper::ANTIALIASED_FILTER;
      mapper->SetFootprintFilter(filter);
      const Rendered filtered = Draw(mapper, capture.Data, view);
      const double own = splattest::PSNR(filtered.RGB,
        splattest::RenderReference(capture.Data, filtered.Camera, capture.Degree,
          antialiased ? 0.3 : 1.0, antialiased));
      const double other = splattest::PSNR(filtered.RGB, reference);
      const std::string name = antialiased ? "antialiased" : "low-pass";
      std::printf(", %s %.1f dB (%.1f against the default's reference)", name.c_str(), own, other);
      Check(own >= MIN_PSNR, where + " " + name + ": PSNR " + std::to_string(own) + " dB");
      // Seen from outside, the filters change the small Gaussians' footprints.
      Check(&view != &capture.Views.front() || other < own - 3.0,
        where + " " + name + ": no different from the default filter");
    }
    mapper->SetFootprintFilterToAutomatic();

    // The per-pixel order against both references, for the record.
    mapper->SetOrderingModeToPixelSorted();
    const Rendered pixelSorted = Draw(mapper, capture.Data, view);
    std::printf(", pixel-sorted %.1f dB (%.1f against the depth order)",
      splattest::PSNR(pixelSorted.RGB,
        splattest::RenderReference(
          capture.Data, pixelSorted.Camera, capture.Degree, 0.3, false, true)),
      splattest::PSNR(pixelSorted.RGB, reference));

    // The axis lists, for the record.
    mapper->SetOrderingModeToBlended();
    const double blended = splattest::PSNR(Draw(mapper, capture.Data, view).RGB, reference);
    std::printf(", blended %.1f dB\n", blended);
    mapper->SetOrderingModeToAutomatic();
  }

  // The same image for 1 and 2 threads.
  std::vector<double> images[2];
  for (int threads = 1; threads <= 2; ++threads)
  {
    vtkSMPTools::Initialize(threads);
    vtkNew<vtkVolumeSplatMapper> mapper;
    images[threads - 1] = Draw(mapper, capture.Data, capture.Views.front()).RGB;
  }
  vtkSMPTools::Initialize(0);
  Check(images[0] == images[1], capture.Name + ": the images for 1 and 2 threads differ");
}

// Two flat Gaussians crossing at 60 degrees along a line off their centers, seen from above:
// in the centers' order the nearer one covers the other everywhere, in each pixel's order each
// covers the other on its side of the crossing.
void TestPixelOrder()
{
  vtkNew<vtkPolyData> sheets;
  vtkNew<vtkPoints> points;
  splattest::KernelSetArrays<vtkFloatArray> arrays;
  const double half = 0.5 * vtkMath::RadiansFromDegrees(30.0);
  for (int i = 0; i < 2; ++i)
  {
    const double side = i == 0 ? 1.0 : -1.0;
    points->InsertNextPoint(0.0, 0.0, 0.08 * i);
    arrays.Scale->InsertNextTuple3(0.5, 0.4, 1e-3);
    arrays.Rotation->InsertNextTuple4(std::cos(half), 0.0, side * std::sin(half), 0.0);
    arrays.Opacity->InsertNextTuple1(0.95);
    arrays.Color->InsertNextTuple3(i == 0 ? 1.0 : 0.1, i == 0 ? 0.2 : 0.9, 0.1);
  }
  sheets->SetPoints(points);
  arrays.AddTo(sheets);
  const splattest::CaptureView view{ "above", { 0.0, 0.3, 3.0 }, { 0.0, 0.0, 0.0 }, { 0, 1, 0 } };
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetOrderingModeToPixelSorted();
  const Rendered image = Draw(mapper, sheets, view);
  Check(mapper->GetLastOrderingMode() == vtkVolumeSplatMapper::PIXEL_SORTED,
    "crossing sheets: PIXEL_SORTED did not run on the CPU");
  const std::vector<double> sorted =
    splattest::RenderReference(sheets, image.Camera, 0, 0.3, false, true);
  const double psnr = splattest::PSNR(image.RGB, sorted);
  const double orders =
    splattest::PSNR(splattest::RenderReference(sheets, image.Camera, 0), sorted);
  std::printf("crossing sheets: pixel-sorted %.1f dB, the two orders %.1f dB apart\n", psnr,
    orders);
  Check(orders <= MAX_ORDER_PSNR, "crossing sheets: the two orders do not differ");
  Check(psnr >= MIN_PSNR,
    "crossing sheets: pixel-sorted PSNR " + std::to_string(psnr) + " dB against the reference");
  vtkNew<vtkVolumeSplatMapper> gpu;
  gpu->SetOrderingModeToPixelSorted();
  Draw(gpu, sheets, view, vtkSplatBackend::OPENGL);
  Check(gpu->GetLastOrderingMode() == vtkVolumeSplatMapper::DEPTH_SORTED,
    "crossing sheets: OpenGL did not draw DEPTH_SORTED for PIXEL_SORTED");
}

// Image data keeps the blended axis lists and the low-pass filter.
void TestDensityDefaults()
{
  vtkNew<vtkVolumeSplatMapper> mapper;
  auto blob = splattest::GaussianBlob(16, 0.1, 0.3, 1.0);
  auto window = splattest::MakeRenderWindow(64, 64);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  mapper->SetInputData(blob);
  mapper->SetBackend(vtkSplatBackend::CPU);
  const double white[3] = { 1.0, 1.0, 1.0 };
  splattest::AddVolume(renderer, mapper, splattest::ExtinctionProperty(1.0, 1.0, white));
  renderer->ResetCamera();
  window->Render();
  Check(mapper->GetLastOrderingMode() == vtkVolumeSplatMapper::BLENDED,
    "image data: the default ordering is not BLENDED");
}
}

int main(int argc, char* argv[])
{
  std::vector<splattest::CaptureScene> captures;
  if (splattest::HasFlag(argc, argv, "--real"))
  {
    const std::string data = splattest::Argument(argc, argv, "-D");
    for (const char* file : { "donut_fused.ply", "fruit_drops_minimal.ply" })
    {
      const std::string path = data + "/" + file;
      if (data.empty() || !splattest::FileExists(path))
      {
        std::printf("%s is absent: skipped\n", path.c_str());
        return splattest::SkipReturnCode;
      }
      captures.push_back(splattest::ReadCapture(path));
    }
  }
  else
  {
    captures.push_back({ "torus", splatexample::SyntheticCapture(20000, 3), 3,
      splattest::CaptureViews({ 0, 0, 0 }, 0.8) });
    TestDensityDefaults();
    TestPixelOrder();
  }
  for (const splattest::CaptureScene& capture : captures)
  {
    TestCapture(capture);
  }
  return splattest::Failures() == 0 ? 0 : 1;
}
