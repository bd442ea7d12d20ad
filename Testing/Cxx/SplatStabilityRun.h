// SPDX-License-Identifier: BSD-3-Clause
// Renders a case of SplatStabilityCases.h with vtkSurfaceSplatMapper or vtkVolumeSplatMapper on
// one backend, measures what came out (Run) and lists what broke (Check).
//
// What every case asserts: the process survives; no value of the mapper's own float image is
// NaN or Inf (the CPU volume rasterizer's RGBA floats, the OpenGL backends' color textures read
// back; the CPU surface rasterizer keeps only 8-bit colors and float depths, so its depths are
// checked); bad input is skipped and counted with a warning, or refused with an error (observed
// with vtkTest::ErrorObserver), exactly as the case expects; and the scene is drawn where it must
// be visible.
#ifndef SplatStabilityRun_h
#define SplatStabilityRun_h

#include "SplatStabilityCases.h"
#include "vtkOpenGLSurfaceSplatRasterizer.h"
#include "vtkOpenGLVolumeSplatRasterizer.h"
#include "vtkSurfaceSplatRasterizer.h"
#include "vtkVolumeSplatRasterizer.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkPixelBufferObject.h"
#include "vtkTestErrorObserver.h"
#include "vtkTextureObject.h"

#include <chrono>

namespace splatstability
{
/// The non-finite floats among n.
inline vtkIdType CountNonFinite(const float* values, std::size_t n)
{
  vtkIdType count = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    count += std::isfinite(values[i]) ? 0 : 1;
  }
  return count;
}

/// The non-finite values of an OpenGL backend's float RGBA result, read back from the GPU.
inline vtkIdType CountNonFinite(vtkTextureObject* texture, vtkRenderWindow* window)
{
  if (!texture || texture->GetHandle() == 0)
  {
    return 0;
  }
  window->MakeCurrent();
  vtkPixelBufferObject* buffer = texture->Download();
  if (!buffer)
  {
    return 0;
  }
  const std::size_t n = static_cast<std::size_t>(texture->GetWidth()) * texture->GetHeight() *
    texture->GetComponents();
  vtkIdType count = 0;
  if (const auto* values = static_cast<const float*>(buffer->MapPackedBuffer()))
  {
    count = CountNonFinite(values, n);
    buffer->UnmapPackedBuffer();
  }
  buffer->Delete();
  return count;
}

/// The CPU backends' float results: the surface rasterizer's depths (its colors are bytes), the
/// volume rasterizer's RGBA image.
inline const std::vector<float>& FloatResult(vtkSurfaceSplatRasterizer* rasterizer)
{
  return rasterizer->GetDepths();
}
inline const std::vector<float>& FloatResult(vtkVolumeSplatRasterizer* rasterizer)
{
  return rasterizer->GetImage();
}

/// A splat mapper (vtkSurfaceSplatMapper or vtkVolumeSplatMapper) with a look at its backends'
/// last float results.
template <typename Mapper>
class Probe : public Mapper
{
public:
  static Probe* New()
  {
    auto* probe = new Probe;
    probe->InitializeObjectBase();
    return probe;
  }
  vtkIdType NonFinitePixels(vtkRenderWindow* window)
  {
    if (this->LastBackend == vtkSplatBackend::OPENGL)
    {
      return CountNonFinite(this->OpenGLRasterizer->GetColorTexture(), window);
    }
    const std::vector<float>& values = FloatResult(this->Rasterizer.Get());
    return CountNonFinite(values.data(), values.size());
  }
};
using SurfaceProbe = Probe<vtkSurfaceSplatMapper>;
using VolumeProbe = Probe<vtkVolumeSplatMapper>;

/// What the mapper left out in its last render, and why.
inline std::string Why(vtkSurfaceSplatMapper* mapper)
{
  std::ostringstream why;
  why << "invalid " << mapper->GetNumberOfSkippedPoints() << "; frustum "
      << mapper->GetNumberOfFrustumCulledSplats() << "; backface "
      << mapper->GetNumberOfBackfaceCulledSplats() << "; negligible "
      << mapper->GetNumberOfNegligibleSplats();
  return why.str();
}
inline std::string Why(vtkVolumeSplatMapper* mapper)
{
  std::ostringstream why;
  why << "invalid " << mapper->GetNumberOfInvalidKernels() << "; transparent "
      << mapper->GetNumberOfTransparentKernels() << "; near plane "
      << mapper->GetNumberOfNearPlaneKernels() << "; frustum "
      << mapper->GetNumberOfFrustumCulledKernels();
  return why.str();
}

// ---- Running a case --------------------------------------------------------------------------

/// Renders case `c` with `backend` (vtkSplatBackend::CPU or OPENGL), `frames` times; the
/// result of the last frame, with the mean time per frame.
inline Result Run(const Case& c, int backend, int frames = 1)
{
  Result result;
  Scene s = c.Make();
  vtkNew<vtkRenderer> renderer;
  auto window = splattest::MakeRenderWindow(s.Width, s.Height);
  window->AddRenderer(renderer);
  vtkNew<vtkTest::ErrorObserver> observer;
  vtkNew<SurfaceProbe> surface;
  vtkNew<VolumeProbe> volume;
  vtkNew<vtkActor> actor;
  if (c.Kind == Surface)
  {
    surface->SetInputData(vtkPolyData::SafeDownCast(s.Input));
    surface->SetBackend(backend);
    surface->SetScalarVisibility(s.ScalarVisibility);
    surface->AddObserver(vtkCommand::ErrorEvent, observer);
    surface->AddObserver(vtkCommand::WarningEvent, observer);
    actor->SetMapper(surface);
    renderer->AddActor(actor);
  }
  else
  {
    volume->SetInputData(s.Input);
    volume->SetBackend(backend);
    volume->AddObserver(vtkCommand::ErrorEvent, observer);
    volume->AddObserver(vtkCommand::WarningEvent, observer);
    splattest::AddVolume(renderer, volume, s.Property);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(s.Position);
  camera->SetFocalPoint(s.FocalPoint);
  camera->SetViewAngle(s.ViewAngle);
  camera->SetParallelProjection(s.Parallel);
  if (s.ResetCamera)
  {
    renderer->ResetCamera();
  }
  camera->SetParallelScale(s.ParallelScale);
  if (s.ClippingRange[0] > 0.0)
  {
    camera->SetClippingRange(s.ClippingRange);
  }
  else
  {
    renderer->ResetCameraClippingRange();
  }
  window->Render(); // the first frame builds the kernels and compiles shaders: not timed
  const auto start = std::chrono::steady_clock::now();
  for (int f = 1; f < frames; ++f)
  {
    window->Render();
  }
  const auto stop = std::chrono::steady_clock::now();
  result.Milliseconds = frames > 1
    ? std::chrono::duration<double, std::milli>(stop - start).count() / (frames - 1)
    : (c.Kind == Surface ? surface->GetLastRenderTimeInMilliseconds()
                         : volume->GetLastRenderTimeInMilliseconds());
  result.Rendered = true;
  if (c.Kind == Surface)
  {
    result.Backend = surface->GetLastBackend();
    result.NonFinite = surface->NonFinitePixels(window);
    result.Skipped = surface->GetNumberOfSkippedPoints();
    result.Why = Why(surface);
  }
  else
  {
    result.Backend = volume->GetLastBackend();
    result.NonFinite = volume->NonFinitePixels(window);
    result.Skipped = volume->GetNumberOfInvalidKernels();
    result.Why = Why(volume);
  }
  result.Error = observer->GetError();
  result.Warning = observer->GetWarning();
  result.Message = result.Error ? observer->GetErrorMessage()
                                : (result.Warning ? observer->GetWarningMessage() : "");
  result.RGB = splattest::ToRGB(splattest::Capture(window));
  for (std::size_t p = 0; p + 2 < result.RGB.size(); p += 3)
  {
    result.Covered += (result.RGB[p] + result.RGB[p + 1] + result.RGB[p + 2] > 0.0) ? 1 : 0;
  }
  return result;
}

/// What went wrong in `r` for case `c`: empty when it passed.
inline std::vector<std::string> Check(const Case& c, const Result& r)
{
  std::vector<std::string> failures;
  auto fail = [&](const std::string& what) { failures.push_back(what); };
  if (!r.Rendered)
  {
    fail("did not render");
  }
  if (r.NonFinite != 0)
  {
    fail(std::to_string(r.NonFinite) + " NaN/Inf values in the mapper's image");
  }
  if (r.Error != c.Expected.Error)
  {
    fail(c.Expected.Error ? "no error for bad input" : "unexpected error: " + r.Message);
  }
  if (c.Expected.Skipped >= 0 && r.Skipped != c.Expected.Skipped)
  {
    fail("skipped " + std::to_string(r.Skipped) + ", expected " +
      std::to_string(c.Expected.Skipped));
  }
  if (c.Expected.Skipped > 0 && !r.Warning)
  {
    fail("skipped points without a warning");
  }
  if (c.Expected.Visible && r.Covered == 0)
  {
    fail("nothing drawn");
  }
  return failures;
}
}

#endif
