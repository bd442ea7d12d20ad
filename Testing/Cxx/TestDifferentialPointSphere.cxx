// SPDX-License-Identifier: BSD-3-Clause
// Differential points (Kalaiah and Varshney 2003) drawn by vtkSurfaceSplatMapper, on a sphere
// whose exact image is known: a finely tessellated sphere drawn by vtkPolyDataMapper with Phong
// shading, same camera, lights and property.
// - Shading: a sphere of few differential points, per-pixel normals from their curvatures, is
//   within a bound of the reference (RMSE over the pixels both cover) and clearly closer than
//   plain EWA surfels on the same points, on both backends and with both footprints (the EWA
//   filtered Gaussian and the paper's unfiltered rectangle).
// - Holes: a dense sphere simplified by vtkDifferentialPointGenerator to a few hundred points, by
//   the paper's greedy enclosure test and by the set cover (which must keep far fewer), covers
//   every pixel of the reference's silhouette (shrunk by 2 pixels) at several views.
// - The regression image: the sphere simplified by the set cover, EWA-filtered.
#include "SplatTestUtilities.h"
#include "vtkDifferentialPointGenerator.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"

#include "vtkActor.h"
#include "vtkPNGWriter.h"
#include "vtkCamera.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cstdio>
#include <vector>

namespace
{
constexpr int Size = 300;

// The folder of -T, where the shading check's images are written for a look ("" for none).
std::string OutputDirectory;

void Save(vtkImageData* image, const std::string& name)
{
  if (!OutputDirectory.empty())
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName((OutputDirectory + "/" + name + ".png").c_str());
    writer->Write();
  }
}

struct View
{
  double Azimuth;
  double Elevation;
};

// A window showing the mapper's input with the test's property and a camera that looks at the
// unit sphere from the given view.
struct Scene
{
  vtkNew<vtkActor> Actor;
  vtkNew<vtkRenderer> Renderer;
  vtkSmartPointer<vtkRenderWindow> Window = splattest::MakeRenderWindow(Size, Size);

  explicit Scene(vtkMapper* mapper)
  {
    this->Actor->SetMapper(mapper);
    vtkProperty* property = this->Actor->GetProperty();
    property->SetColor(0.8, 0.7, 0.6);
    property->SetAmbient(0.1);
    property->SetDiffuse(0.8);
    property->SetSpecular(0.4);
    property->SetSpecularPower(30.0);
    property->SetInterpolationToPhong();
    this->Renderer->AddActor(this->Actor);
    this->Renderer->SetBackground(0.0, 0.0, 0.0);
    this->Window->AddRenderer(this->Renderer);
  }

  vtkSmartPointer<vtkImageData> Render(const View& view)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(0.0, 0.0, 4.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetViewAngle(30.0);
    camera->Azimuth(view.Azimuth);
    camera->Elevation(view.Elevation);
    camera->OrthogonalizeViewUp();
    this->Renderer->ResetCameraClippingRange();
    this->Window->Render();
    return splattest::Capture(this->Window);
  }
};

bool Covered(vtkImageData* image, int x, int y)
{
  double rgb[3];
  splattest::Pixel(image, x, y, rgb);
  return rgb[0] + rgb[1] + rgb[2] > 0.0;
}

// RMS color difference over the pixels both images cover.
double RMSE(vtkImageData* reference, vtkImageData* image)
{
  double sum = 0.0;
  long count = 0;
  for (int y = 0; y < Size; ++y)
  {
    for (int x = 0; x < Size; ++x)
    {
      if (Covered(reference, x, y) && Covered(image, x, y))
      {
        double a[3], b[3];
        splattest::Pixel(reference, x, y, a);
        splattest::Pixel(image, x, y, b);
        for (int c = 0; c < 3; ++c)
        {
          sum += (a[c] - b[c]) * (a[c] - b[c]);
        }
        count += 3;
      }
    }
  }
  return count ? std::sqrt(sum / count) : 1.0;
}

// Pixels of the reference's silhouette, at least `margin` pixels inside it, that the image
// leaves uncovered.
long Holes(vtkImageData* reference, vtkImageData* image, int margin)
{
  long holes = 0;
  for (int y = margin; y < Size - margin; ++y)
  {
    for (int x = margin; x < Size - margin; ++x)
    {
      bool inside = true;
      for (int dy = -margin; dy <= margin && inside; ++dy)
      {
        for (int dx = -margin; dx <= margin && inside; ++dx)
        {
          inside = Covered(reference, x + dx, y + dy);
        }
      }
      holes += inside && !Covered(image, x, y);
    }
  }
  return holes;
}

vtkSmartPointer<vtkImageData> Reference(const View& view)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(512);
  sphere->SetPhiResolution(256);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  Scene scene(mapper);
  return scene.Render(view);
}

// The shading check on one backend and footprint: differential points against surfels on the
// same points.
bool CheckShading(vtkAlgorithm* points, vtkAlgorithm* surfels, vtkImageData* reference,
  const View& view, int backend, int filter, const char* name, double bound)
{
  vtkNew<vtkSurfaceSplatMapper> differential;
  differential->SetInputConnection(points->GetOutputPort());
  differential->SetPrimitiveToDifferentialPoints();
  differential->SetBackend(backend);
  differential->SetFilterMode(filter);
  Scene differentialScene(differential);
  const vtkSmartPointer<vtkImageData> differentialImage = differentialScene.Render(view);
  const double differentialError = RMSE(reference, differentialImage);
  Save(differentialImage, std::string("TestDifferentialPointSphere-") + name);

  vtkNew<vtkSurfaceSplatMapper> plain;
  plain->SetInputConnection(surfels->GetOutputPort());
  plain->SetBackend(backend);
  Scene plainScene(plain);
  const vtkSmartPointer<vtkImageData> plainImage = plainScene.Render(view);
  const double plainError = RMSE(reference, plainImage);
  Save(plainImage, std::string("TestDifferentialPointSphere-surfels-") + name);
  const bool ok = differentialError <= bound && differentialError <= 0.6 * plainError &&
    differential->GetNumberOfSkippedPoints() == 0;
  std::printf("shading, %s: RMSE %.4f (bound %.3f), surfels on the same points %.4f (the "
              "differential points' must be at most 0.6 of it) %s\n",
    name, differentialError, bound, plainError, ok ? "ok" : "FAILED");
  return ok;
}
}

int main(int argc, char* argv[])
{
  OutputDirectory = splattest::Argument(argc, argv, "-T");
  const View front{ 20.0, 25.0 };
  const vtkSmartPointer<vtkImageData> reference = Reference(front);
  Save(reference, "TestDifferentialPointSphere-reference");

  // Few points: a coarse sphere mesh's 266 vertices.
  vtkNew<vtkSphereSource> coarse;
  coarse->SetThetaResolution(24);
  coarse->SetPhiResolution(13);
  vtkNew<vtkDifferentialPointGenerator> coarsePoints;
  coarsePoints->SetInputConnection(coarse->GetOutputPort());
  coarsePoints->SimplifyOff();
  vtkNew<vtkSurfelGenerator> coarseSurfels;
  coarseSurfels->SetInputConnection(coarse->GetOutputPort());
  bool ok = true;
  ok = CheckShading(coarsePoints, coarseSurfels, reference, front, vtkSplatBackend::CPU,
         vtkSurfaceSplatMapper::EWA, "CPU-EWA", EWA_SHADING_RMSE) && ok;
  ok = CheckShading(coarsePoints, coarseSurfels, reference, front, vtkSplatBackend::CPU,
         vtkSurfaceSplatMapper::UNFILTERED, "CPU-rectangles", RECTANGLE_SHADING_RMSE) && ok;
  ok = CheckShading(coarsePoints, coarseSurfels, reference, front, vtkSplatBackend::OPENGL,
         vtkSurfaceSplatMapper::EWA, "OpenGL-EWA", EWA_SHADING_RMSE) && ok;
  ok = CheckShading(coarsePoints, coarseSurfels, reference, front, vtkSplatBackend::OPENGL,
         vtkSurfaceSplatMapper::UNFILTERED, "OpenGL-rectangles", RECTANGLE_SHADING_RMSE) && ok;

  // Many points simplified: vtkSphereSource's 12,482 vertices, by the paper's greedy enclosure
  // test and by the set cover; the set cover keeps at most SetCoverRatio of the other's points.
  vtkNew<vtkSphereSource> dense;
  dense->SetThetaResolution(160);
  dense->SetPhiResolution(80);
  dense->Update();
  const vtkIdType inputPoints = dense->GetOutput()->GetNumberOfPoints();
  constexpr double SetCoverRatio = 0.5;
  vtkIdType kept[2] = { 0, 0 };
  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetPrimitiveToDifferentialPoints();
  mapper->SetBackendToCPU();
  Scene scene(mapper);
  vtkNew<vtkDifferentialPointGenerator> simplified;
  for (const int mode :
    { vtkDifferentialPointGenerator::GREEDY_ENCLOSURE, vtkDifferentialPointGenerator::SET_COVER })
  {
    simplified->SetInputConnection(dense->GetOutputPort());
    simplified->SetSimplificationMode(mode);
    simplified->Update();
    kept[mode] = simplified->GetNumberOfKeptPoints();
    std::printf("simplification, %s: %lld points kept of %lld\n",
      simplified->GetSimplificationModeAsString(), static_cast<long long>(kept[mode]),
      static_cast<long long>(inputPoints));
    ok = kept[mode] > 0 && kept[mode] * 5 < inputPoints && ok;
    mapper->SetInputConnection(simplified->GetOutputPort());
    for (const View& view : { View{ 0.0, 0.0 }, View{ 70.0, 40.0 }, View{ 150.0, -60.0 },
           View{ 250.0, 85.0 }, front })
    {
      const vtkSmartPointer<vtkImageData> silhouette = Reference(view);
      for (const int filter : { vtkSurfaceSplatMapper::UNFILTERED, vtkSurfaceSplatMapper::EWA })
      {
        mapper->SetFilterMode(filter);
        const long holes = Holes(silhouette, scene.Render(view), 2);
        std::printf("holes, %s, view (%g, %g), %s: %ld uncovered pixels inside the silhouette\n",
          simplified->GetSimplificationModeAsString(), view.Azimuth, view.Elevation,
          filter == vtkSurfaceSplatMapper::EWA ? "EWA" : "rectangles", holes);
        ok = holes == 0 && ok;
      }
    }
  }
  const bool fewer = kept[vtkDifferentialPointGenerator::SET_COVER] <=
    SetCoverRatio * kept[vtkDifferentialPointGenerator::GREEDY_ENCLOSURE];
  std::printf("set cover / greedy enclosure: %.3f (bound %.2f) %s\n",
    static_cast<double>(kept[vtkDifferentialPointGenerator::SET_COVER]) /
      kept[vtkDifferentialPointGenerator::GREEDY_ENCLOSURE],
    SetCoverRatio, fewer ? "ok" : "FAILED");
  ok = fewer && ok;
  // The regression image: the sphere simplified by the set cover, EWA-filtered, front view.
  const bool imageOk = vtkRegressionTestImage(scene.Window) != vtkTesting::FAILED;
  return ok && imageOk ? EXIT_SUCCESS : EXIT_FAILURE;
}
