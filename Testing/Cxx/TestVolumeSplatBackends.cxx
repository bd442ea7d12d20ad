// SPDX-License-Identifier: BSD-3-Clause
// The OpenGL backend of vtkVolumeSplatMapper renders what the CPU backend renders. The same
// scenes through both backends, in every ordering mode, must agree within an RMSE bound per
// scene (RGB in [0, 1]; the bounds come from CMake, measured on llvmpipe, justified there):
// - the Gaussian blob of SplatVolumeTestUtilities.h, also against its analytic image, and the
//   same blob colored by its scalar;
// - a set of anisotropic kernels given as covariances, through the transfer functions (the
//   density model), also under the low-pass filter (as the blob), and the same kernels with
//   color and opacity arrays (peak opacities);
// - the blob between two opaque squares: the one in front hides the same pixels in both.
// The bounds must tell a wrong traversal order and a wrong merge apart: the peak-opacity set
// composited in reverse order (its mirror view, flipped back, under a parallel projection) and
// the other ordering modes (clipped, single axis, which merge the lists differently) exceed
// them. GetLastBackend() reports OpenGL when asked, and both backends report the same lists:
// a view straight down an axis traverses exactly one.
#include "SplatVolumeKernel.h"
#include "SplatVolumeTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatMapper.h"


#include <chrono>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

namespace
{
constexpr int Size = 256;
const char* const ModeNames[4] = { "blended", "clipped", "single axis", "depth sorted" };
using splattest::Check;

struct Scene
{
  std::string Name;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkSmartPointer<vtkVolumeSplatMapper> Mapper;
};

Scene MakeScene(const std::string& name, vtkDataSet* input, vtkVolumeProperty* property)
{
  Scene scene{ name, vtkSmartPointer<vtkRenderer>::New(), splattest::MakeRenderWindow(Size, Size),
    vtkSmartPointer<vtkVolumeSplatMapper>::New() };
  scene.Mapper->SetInputData(input);
  splattest::AddVolume(scene.Renderer, scene.Mapper, property);
  scene.Window->AddRenderer(scene.Renderer);
  return scene;
}

void LookFrom(Scene& scene, double x, double y, double z)
{
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(x, y, z);
  camera->SetViewUp(0.0, 1.0, 0.0);
  scene.Renderer->ResetCameraClippingRange();
}

// Renders with the backend and mode; the image's RGB, and the frame's wall-clock time (to the
// GPU's completion) in `ms`.
std::vector<double> Render(Scene& scene, int backend, int mode, double* ms = nullptr)
{
  scene.Mapper->SetBackend(backend);
  scene.Mapper->SetOrderingMode(mode);
  const auto start = std::chrono::steady_clock::now();
  scene.Window->Render();
  scene.Window->WaitForCompletion();
  if (ms)
  {
    *ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count();
  }
  Check(scene.Mapper->GetLastBackend() == backend,
    scene.Name + ": " + vtkSplatBackend::GetBackendAsString(backend) + " requested, " +
      vtkSplatBackend::GetBackendAsString(scene.Mapper->GetLastBackend()) + " drew");
  return splattest::ToRGB(splattest::Capture(scene.Window));
}

// Both backends in every mode: RMSE within the bound, the same lists traversed, and the
// frame times once the lists are built and the kernels uploaded (the first, blended, frames of
// each backend do that for the others: the other modes need no other list). Returns the CPU's
// blended image.
std::vector<double> CompareBackends(Scene& scene, double bound)
{
  std::vector<double> blended;
  for (int mode = 0; mode < 4; ++mode)
  {
    if (mode == vtkVolumeSplatMapper::BLENDED)
    {
      Render(scene, vtkSplatBackend::CPU, mode);
      Render(scene, vtkSplatBackend::OPENGL, mode);
    }
    double cpuMs = 0.0, openGLMs = 0.0;
    const std::vector<double> cpu = Render(scene, vtkSplatBackend::CPU, mode, &cpuMs);
    bool cpuLists[4];
    for (int list = 0; list < 4; ++list)
    {
      cpuLists[list] = scene.Mapper->GetListTraversed(list);
    }
    const std::vector<double> openGL = Render(scene, vtkSplatBackend::OPENGL, mode, &openGLMs);
    const double rmse = splattest::RMSE(cpu, openGL);
    double largest = 0.0;
    for (std::size_t i = 0; i < cpu.size(); ++i)
    {
      largest = std::max(largest, std::abs(cpu[i] - openGL[i]));
    }
    std::printf("%-22s %-12s CPU vs OpenGL RMSE %.5f (bound %.4f, largest %.3f); lists "
                "%d%d%d%d; CPU %.1f ms, OpenGL %.1f ms\n",
      scene.Name.c_str(), ModeNames[mode], rmse, bound, largest, cpuLists[0], cpuLists[1],
      cpuLists[2], cpuLists[3], cpuMs, openGLMs);
    Check(rmse <= bound, scene.Name + " " + ModeNames[mode] + ": the backends differ");
    for (int list = 0; list < 4; ++list)
    {
      Check(scene.Mapper->GetListTraversed(list) == cpuLists[list],
        scene.Name + " " + ModeNames[mode] + ": the backends traverse different lists");
    }
    if (mode == vtkVolumeSplatMapper::BLENDED)
    {
      blended = cpu;
    }
  }
  return blended;
}

// Kernels of random position, shape and orientation, as covariances, with a scalar in [1, 8],
// and for the peak model a color and an opacity array.
vtkSmartPointer<vtkPolyData> KernelSet(int count, bool peakOpacity)
{
  std::mt19937 random(5);
  auto uniform = [&random](double lo, double hi)
  { return lo + (hi - lo) * (random() / 4294967296.0); };
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> covariance, scalars, color, opacity;
  covariance->SetName("Covariance");
  covariance->SetNumberOfComponents(6);
  color->SetName("Color");
  color->SetNumberOfComponents(3);
  opacity->SetName("Opacity");
  for (int i = 0; i < count; ++i)
  {
    points->InsertNextPoint(uniform(-0.6, 0.6), uniform(-0.6, 0.6), uniform(-0.6, 0.6));
    const glm::dvec3 scale(uniform(0.01, 0.15), uniform(0.01, 0.15), uniform(0.01, 0.15));
    const glm::dvec4 rotation(
      uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0));
    const glm::dmat3 V = splat::CovarianceFromScaleRotation(scale, rotation);
    covariance->InsertNextTuple6(V[0][0], V[1][0], V[2][0], V[1][1], V[2][1], V[2][2]);
    scalars->InsertNextValue(static_cast<float>(uniform(1.0, 8.0)));
    color->InsertNextTuple3(uniform(0.0, 1.0), uniform(0.0, 1.0), uniform(0.0, 1.0));
    opacity->InsertNextValue(static_cast<float>(uniform(0.3, 0.95)));
  }
  data->SetPoints(points);
  data->GetPointData()->SetScalars(scalars);
  data->GetPointData()->AddArray(covariance);
  if (peakOpacity)
  {
    data->GetPointData()->AddArray(color);
    data->GetPointData()->AddArray(opacity);
  }
  return data;
}

// Extinction equal to the scalar, colors from red to blue over [1, 8].
vtkSmartPointer<vtkVolumeProperty> KernelProperty()
{
  const double white[3] = { 1.0, 1.0, 1.0 };
  auto property = splattest::ExtinctionProperty(8.0, 1.0, white);
  vtkColorTransferFunction* color = property->GetRGBTransferFunction(0);
  color->RemoveAllPoints();
  color->AddRGBPoint(1.0, 1.0, 0.2, 0.1);
  color->AddRGBPoint(4.5, 0.2, 0.9, 0.2);
  color->AddRGBPoint(8.0, 0.1, 0.3, 1.0);
  return property;
}
}

int main(int, char*[])
{
  const int CPU = vtkSplatBackend::CPU;
  const int OPENGL = vtkSplatBackend::OPENGL;
  const int BLENDED = vtkVolumeSplatMapper::BLENDED;

  // The blob, seen obliquely: the X and Z lists blend across the middle of the image.
  const double sigma = 0.25, peak = 4.0, rgb[3] = { 1.0, 0.7, 0.4 };
  auto blobImage = splattest::GaussianBlob(32, 1.0 / 16.0, sigma, peak);
  auto blobProperty = splattest::ExtinctionProperty(peak, 1.0 / 16.0, rgb);
  {
    Scene blob = MakeScene("blob", blobImage, blobProperty);
    LookFrom(blob, 2.5, 1.2, 3.0);
    const std::vector<double> cpu = CompareBackends(blob, MAX_BLOB_RMSE);
    const std::vector<double> analytic = splattest::BlobImage(blob.Renderer, sigma, peak, rgb);
    const std::vector<double> openGL = Render(blob, OPENGL, BLENDED);
    const double cpuError = splattest::RMSE(cpu, analytic);
    const double openGLError = splattest::RMSE(openGL, analytic);
    std::printf("blob against the analytic image: CPU RMSE %.5f, OpenGL RMSE %.5f (bound %.4f)\n",
      cpuError, openGLError, MAX_BLOB_ANALYTIC_RMSE);
    Check(openGLError <= MAX_BLOB_ANALYTIC_RMSE, "the OpenGL blob is not the analytic image");
    Check(blob.Mapper->GetListTraversed(0) && blob.Mapper->GetListTraversed(2),
      "the oblique view blends the X and Z lists");

    // Straight down Z: one list.
    LookFrom(blob, 0.0, 0.0, 4.0);
    Render(blob, OPENGL, BLENDED);
    std::printf("down Z with OpenGL: lists %d %d %d %d\n", blob.Mapper->GetListTraversed(0),
      blob.Mapper->GetListTraversed(1), blob.Mapper->GetListTraversed(2),
      blob.Mapper->GetListTraversed(3));
    Check(!blob.Mapper->GetListTraversed(0) && !blob.Mapper->GetListTraversed(1) &&
        blob.Mapper->GetListTraversed(2) && !blob.Mapper->GetListTraversed(3),
      "a view down Z traverses the Z list only");
    Check(blob.Mapper->GetNumberOfProjectedKernels() == -1 &&
        blob.Mapper->GetNumberOfNearPlaneKernels() == -1,
      "the OpenGL backend reports its counts as unknown");
  }

  // A coarser blob colored by its scalar: where kernels of one grid sheet overlap, the CPU weights
  // their colors by their shares of the sheet's optical depth, the GPU composites them one by
  // one in the sheet's order.
  {
    auto colored = splattest::ExtinctionProperty(peak, 1.0 / 12.0, rgb);
    vtkColorTransferFunction* color = colored->GetRGBTransferFunction(0);
    color->RemoveAllPoints();
    color->AddRGBPoint(0.0, 0.2, 0.4, 1.0);
    color->AddRGBPoint(peak, 1.0, 0.5, 0.1);
    Scene blob =
      MakeScene("colored blob", splattest::GaussianBlob(24, 1.0 / 12.0, sigma, peak), colored);
    LookFrom(blob, 2.5, 1.2, 3.0);
    CompareBackends(blob, MAX_COLORED_BLOB_RMSE);
  }

  // Anisotropic kernels through the transfer functions (density model).
  auto kernelProperty = KernelProperty();
  {
    Scene kernels = MakeScene("kernels (density)", KernelSet(300, false), kernelProperty);
    LookFrom(kernels, 1.9, 1.4, 2.4);
    const std::vector<double> bandLimit = CompareBackends(kernels, MAX_KERNEL_RMSE);
    // EWA's low-pass rather than the default band limit, also on the blob's sheets: the same on
    // both backends, OpenGL's image nearer the CPU's under the low-pass than under the band
    // limit (else one of them ignored the filter).
    kernels.Mapper->SetFootprintFilterToLowPass();
    const std::vector<double> lowPass = CompareBackends(kernels, MAX_KERNEL_RMSE);
    const std::vector<double> openGL = Render(kernels, OPENGL, BLENDED);
    const double same = splattest::RMSE(openGL, lowPass);
    const double other = splattest::RMSE(openGL, bandLimit);
    std::printf("kernels (density), low-pass: OpenGL vs CPU RMSE %.5f, vs the CPU's band limit "
                "%.5f\n",
      same, other);
    Check(same < 0.75 * other, "a backend draws the low-pass as the band limit");
    Scene blob = MakeScene("blob (low-pass)", blobImage, blobProperty);
    blob.Mapper->SetFootprintFilterToLowPass();
    LookFrom(blob, 2.5, 1.2, 3.0);
    CompareBackends(blob, MAX_BLOB_RMSE);
  }

  // The same kernels with colors and peak opacities; then the bound against wrong orders.
  {
    Scene kernels = MakeScene("kernels (peak opacity)", KernelSet(300, true), kernelProperty);
    LookFrom(kernels, 1.9, 1.4, 2.4);
    const std::vector<double> cpu = CompareBackends(kernels, MAX_PEAK_RMSE);
    // From inside the set: kernels behind the eye and across the near plane are skipped alike.
    LookFrom(kernels, 0.15, 0.1, 0.3);
    for (int mode : { BLENDED, static_cast<int>(vtkVolumeSplatMapper::DEPTH_SORTED) })
    {
      const std::vector<double> inside = Render(kernels, CPU, mode);
      const vtkIdType nearPlane = kernels.Mapper->GetNumberOfNearPlaneKernels();
      const double rmse = splattest::RMSE(inside, Render(kernels, OPENGL, mode));
      std::printf("peak opacity from inside, %s: %lld kernels at the near plane, CPU vs OpenGL "
                  "RMSE %.5f\n",
        ModeNames[mode], static_cast<long long>(nearPlane), rmse);
      Check(nearPlane > 0 && rmse <= MAX_PEAK_RMSE, "from inside: the backends differ");
    }
    LookFrom(kernels, 1.9, 1.4, 2.4);
    for (int mode : { vtkVolumeSplatMapper::CLIPPED, vtkVolumeSplatMapper::SINGLE_AXIS })
    {
      const double rmse = splattest::RMSE(cpu, Render(kernels, OPENGL, mode));
      std::printf("peak opacity: CPU blended vs OpenGL %s RMSE %.5f\n", ModeNames[mode], rmse);
      Check(rmse > MAX_PEAK_RMSE,
        std::string("the bound does not tell blended from ") + ModeNames[mode]);
    }
    // Under a parallel projection the mirror view (the camera on the other side, the same view
    // up) flipped left to right has the same footprints composited in reverse order.
    kernels.Renderer->GetActiveCamera()->ParallelProjectionOn();
    kernels.Renderer->ResetCamera();
    const std::vector<double> front = Render(kernels, CPU, BLENDED);
    const double rmse = splattest::RMSE(front, Render(kernels, OPENGL, BLENDED));
    vtkCamera* camera = kernels.Renderer->GetActiveCamera();
    double position[3];
    camera->GetPosition(position);
    camera->SetPosition(-position[0], -position[1], -position[2]);
    kernels.Renderer->ResetCameraClippingRange();
    const std::vector<double> back = Render(kernels, CPU, BLENDED);
    std::vector<double> reversed(back.size());
    for (int y = 0; y < Size; ++y)
    {
      for (int x = 0; x < Size; ++x)
      {
        for (int c = 0; c < 3; ++c)
        {
          reversed[3 * (y * Size + x) + c] = back[3 * (y * Size + Size - 1 - x) + c];
        }
      }
    }
    const double reversedRmse = splattest::RMSE(front, reversed);
    std::printf("peak opacity, parallel: CPU vs OpenGL RMSE %.5f, vs reversed order %.5f\n", rmse,
      reversedRmse);
    Check(rmse <= MAX_PEAK_RMSE, "parallel projection: the backends differ");
    Check(reversedRmse > MAX_PEAK_RMSE, "the bound does not tell a reversed order");
  }

  // The blob between opaque squares: the front one (x < 0) hides the volume in both backends.
  {
    Scene occluded = MakeScene("occluded blob", blobImage, blobProperty);
    LookFrom(occluded, 0.0, 0.0, 4.0);
    occluded.Renderer->GetActiveCamera()->SetClippingRange(1.0, 10.0);
    occluded.Renderer->AddActor(splattest::OpaqueSquare(-1.0, 0.0, 0.9));
    occluded.Renderer->AddActor(splattest::OpaqueSquare(0.0, 1.0, -0.9));
    const std::vector<double> cpu = Render(occluded, CPU, BLENDED);
    const std::vector<double> openGL = Render(occluded, OPENGL, BLENDED);
    const double rmse = splattest::RMSE(cpu, openGL);
    // The front square's pixels: left of the center column, within the square's image.
    double largestRed[2] = { 0.0, 0.0 };
    int hidden = 0;
    for (int y = 0; y < Size; ++y)
    {
      for (int x = 0; x < Size / 2 - 2; ++x)
      {
        const std::size_t p = 3 * (y * Size + x);
        if (cpu[p + 1] > 0.99 || openGL[p + 1] > 0.99)
        {
          ++hidden;
          largestRed[0] = std::max(largestRed[0], cpu[p]);
          largestRed[1] = std::max(largestRed[1], openGL[p]);
        }
      }
    }
    const int middle = 3 * (Size / 2 * Size + Size / 2 + 10);
    std::printf("occluded blob: CPU vs OpenGL RMSE %.5f (bound %.4f); %d hidden pixels, largest "
                "red there CPU %.4f, OpenGL %.4f; right of the center CPU %.3f, OpenGL %.3f\n",
      rmse, MAX_OCCLUSION_RMSE, hidden, largestRed[0], largestRed[1], cpu[middle],
      openGL[middle]);
    Check(rmse <= MAX_OCCLUSION_RMSE, "occluded blob: the backends differ");
    Check(hidden > Size * Size / 4 && largestRed[0] < 0.01 && largestRed[1] < 0.01,
      "the square in front hides the volume in both backends");
    Check(openGL[middle] > 0.5, "the volume shows in front of the square behind it");
  }
  return splattest::Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
