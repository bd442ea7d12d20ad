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
#include "vtkImageData.h"
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
  }
  for (const splattest::CaptureScene& capture : captures)
  {
    TestCapture(capture);
  }
  return splattest::Failures() == 0 ? 0 : 1;
}
