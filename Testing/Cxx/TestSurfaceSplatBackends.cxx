// SPDX-License-Identifier: BSD-3-Clause
// The OpenGL backend renders what the CPU backend renders: the same scenes (a lit, scalar-colored
// sphere; the bunny scan where ../shared/data has it; the grazing checkerboard plane of
// splat_report; translucent planes over an opaque one; a sphere of 20 surfels seen close, whose
// splats are hundreds of pixels wide) through both backends at the same camera
// must agree within an RMSE bound per scene (on RGB in [0,1]), and the
// OpenGL backend's other filters (approximate, circular) must not, so that each bound tells the
// filters apart. AUTO must pick the CPU under a software OpenGL renderer (llvmpipe here) and
// report what it picked.
#include "SplatCheckerboardScene.h"
#include "SplatTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace
{
constexpr int Width = 320;
constexpr int Height = 240;

// A scene: its splat mappers (the ones whose backend is switched) and the RMSE bound between
// the backends' images.
struct Scene
{
  std::string Name;
  std::vector<vtkSurfaceSplatMapper*> Mappers;
  double MaxRmse;
};

vtkSurfaceSplatMapper* AddSplats(vtkRenderer* renderer, vtkPolyData* surfels)
{
  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(surfels);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  return mapper;
}

void SetBackend(const Scene& scene, int backend)
{
  for (vtkSurfaceSplatMapper* mapper : scene.Mappers)
  {
    mapper->SetBackend(backend);
  }
}

Scene Sphere(vtkRenderer* renderer)
{
  vtkSmartPointer<vtkPolyData> sphere = splattest::SurfelSphere(20000, 1.0);
  vtkNew<vtkFloatArray> height;
  height->SetName("Height");
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    height->InsertNextValue(static_cast<float>(sphere->GetPoint(i)[2]));
  }
  sphere->GetPointData()->SetScalars(height);
  vtkSurfaceSplatMapper* mapper = AddSplats(renderer, sphere);
  mapper->SetScalarRange(-1.0, 1.0);
  vtkActor* actor = renderer->GetActors()->GetLastActor();
  actor->GetProperty()->SetSpecular(0.4);
  actor->GetProperty()->SetSpecularPower(30.0);
  actor->RotateX(-60.0);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.6);
  return { "sphere", { mapper }, 0.0 };
}

// A sphere of few surfels seen close: splats hundreds of pixels wide, each fragment far from its
// splat's center.
Scene MagnifiedSphere(vtkRenderer* renderer)
{
  vtkSurfaceSplatMapper* mapper = AddSplats(renderer, splattest::SurfelSphere(20, 1.0));
  vtkActor* actor = renderer->GetActors()->GetLastActor();
  actor->GetProperty()->SetColor(0.9, 0.7, 0.3);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(5.0);
  return { "magnified sphere", { mapper }, 0.0 };
}

// No mappers (the scene is skipped) where the file is absent.
Scene Bunny(vtkRenderer* renderer, const std::string& file)
{
  if (!splattest::FileExists(file))
  {
    return { "bunny", {}, 0.0 };
  }
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(file.c_str());
  vtkNew<vtkSurfelGenerator> generator;
  generator->SetInputConnection(reader->GetOutputPort());
  generator->Update();
  vtkSurfaceSplatMapper* mapper = AddSplats(renderer, generator->GetOutput());
  renderer->GetActors()->GetLastActor()->GetProperty()->SetColor(0.9, 0.75, 0.6);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.4);
  return { "bunny", { mapper }, 0.0 };
}

Scene Checkerboard(vtkRenderer* renderer)
{
  splatexample::Checkerboard board;
  board.FitPoints(100000);
  board.SetCamera(renderer->GetActiveCamera());
  renderer->SetBackground(board.Background.data());
  vtkSurfaceSplatMapper* mapper = AddSplats(renderer,
    splatexample::CheckerboardSurfels(board, renderer->GetActiveCamera(), Width, Height));
  splatexample::StyleCheckerboardActor(renderer->GetActors()->GetLastActor());
  return { "checkerboard", { mapper }, 0.0 };
}

// An opaque plane behind two translucent planes that cross each other, the translucent ones in
// one mapper: its layers are peeled (OpenGL) or kept per pixel (CPU).
Scene TranslucentPlanes(vtkRenderer* renderer)
{
  const double u[3] = { 0.05, 0.0, 0.0 };
  const double v[3] = { 0.0, 0.05, 0.0 };
  const double tiltedV[3] = { 0.0, 0.035, 0.035 };
  const double center[3][3] = { { 0.0, 0.0, -0.5 }, { -0.3, 0.0, 0.0 }, { 0.1, 0.1, 0.1 } };
  const double color[3][3] = { { 0.9, 0.2, 0.2 }, { 0.2, 0.8, 0.3 }, { 0.3, 0.4, 0.9 } };
  vtkNew<vtkAppendPolyData> translucent;
  vtkSmartPointer<vtkPolyData> planes[3];
  for (int i = 0; i < 3; ++i)
  {
    planes[i] = splattest::SurfelPlane(center[i], u, i == 2 ? tiltedV : v, 30, 30);
    splattest::Paint(planes[i], color[i], i == 0 ? 1.0 : 0.5);
  }
  translucent->AddInputData(planes[1]);
  translucent->AddInputData(planes[2]);
  translucent->Update();
  Scene scene{ "translucent planes", { AddSplats(renderer, planes[0]),
                                        AddSplats(renderer, translucent->GetOutput()) },
    0.0 };
  for (vtkSurfaceSplatMapper* mapper : scene.Mappers)
  {
    mapper->SetColorModeToDirectScalars();
  }
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Elevation(20.0);
  renderer->GetActiveCamera()->Azimuth(25.0);
  return scene;
}
}

int main(int argc, char* argv[])
{
  const std::string bunny = splattest::Argument(argc, argv, "-D") + "/bunny.ply";
  const std::string output = splattest::Argument(argc, argv, "-T");
  // The bounds: the RMSE measured on llvmpipe, with margin. Measured: sphere 0.0102, bunny
  // 0.0043, checkerboard 0.0034, translucent planes 0.00001, magnified sphere 0.00017 (its 20
  // surfels get the automatic cutoff 2; the bunny and it have hardly a minified splat, and the
  // CPU draws them with exact kernels, as OpenGL does). What differs: on the sphere's rim, the
  // CPU's minified splats let slivers give way (OpaqueSlot in SplatSurfaceFragment.h), which
  // brings its silhouette out to the mesh's (splat_report's sphere: CPU 0.0029, OpenGL
  // 0.0056); the OpenGL backend's depth-ordered peels rarely lose a
  // surface to slivers, and the same rule there, peeling on past them, cost 1.6x the time for
  // no gain (bunny 0.0264 from 0.0263, sphere 0.0056 from 0.0056). Elsewhere:
  // the GPU evaluates exp() per fragment where the CPU steps forward differences through a
  // table (a few 1e-6 per weight), and shades at the weighted mean depth of a surface where the
  // CPU takes its nearest contribution, which moves specular highlights and the accumulate-or-
  // separate decision at silhouettes (the bunny's ears and folds: single pixels up to 0.77).
  // The OpenGL backend's other filters exceed the bound of every scene but the sphere, whose
  // rim outweighs its filter (approximate / circular: sphere 0.0104 / 0.0190, bunny
  // 0.0253 / 0.0290, checkerboard 0.1048 / 0.1340, translucent planes 0.0176 / 0.0125,
  // magnified sphere 0.0099 / 0.1183): a change of the exact filter to either fails elsewhere.
  struct Case
  {
    std::function<Scene(vtkRenderer*)> Make;
    double MaxRmse;
    bool TellsFilters;
  };
  const std::vector<Case> scenes = {
    { Sphere, 0.011, false },
    { [&bunny](vtkRenderer* r) { return Bunny(r, bunny); }, 0.008, true },
    { Checkerboard, 0.004, true },
    { TranslucentPlanes, 0.004, true },
    { MagnifiedSphere, 0.002, true },
  };
  int failures = 0;
  for (const auto& entry : scenes)
  {
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0.1, 0.1, 0.15);
    auto window = splattest::MakeRenderWindow(Width, Height);
    window->AddRenderer(renderer);
    Scene scene = entry.Make(renderer);
    if (scene.Mappers.empty())
    {
      std::printf("%-20s skipped: no data\n", scene.Name.c_str());
      continue;
    }
    scene.MaxRmse = entry.MaxRmse;
    std::vector<double> images[2];
    const int backends[2] = { vtkSplatBackend::CPU, vtkSplatBackend::OPENGL };
    for (int b = 0; b < 2; ++b)
    {
      SetBackend(scene, backends[b]);
      window->Render();
      vtkSmartPointer<vtkImageData> image = splattest::Capture(window);
      images[b] = splattest::ToRGB(image);
      if (scene.Mappers[0]->GetLastBackend() != backends[b])
      {
        std::printf("FAIL: %s: backend %s requested, %s drew\n", scene.Name.c_str(),
          vtkSplatBackend::GetBackendAsString(backends[b]),
          vtkSplatBackend::GetBackendAsString(scene.Mappers[0]->GetLastBackend()));
        ++failures;
      }
      if (!output.empty())
      {
        std::string name = "TestSurfaceSplatBackends-" + scene.Name + "-" +
          vtkSplatBackend::GetBackendAsString(backends[b]) + ".png";
        std::replace(name.begin(), name.end(), ' ', '-');
        vtkNew<vtkPNGWriter> writer;
        writer->SetInputData(image);
        writer->SetFileName((output + "/" + name).c_str());
        writer->Write();
      }
    }
    const double rmse = splattest::RMSE(images[0], images[1]);
    std::printf("%-20s CPU vs OpenGL RMSE %.5f (bound %.3f), max difference %.3f\n",
      scene.Name.c_str(), rmse, scene.MaxRmse, splattest::LargestDifference(images[0], images[1]));
    if (!(rmse <= scene.MaxRmse))
    {
      std::printf("FAIL: %s: the backends differ by more than the bound\n", scene.Name.c_str());
      ++failures;
    }

    // The other filters of the OpenGL backend must differ from the CPU's EWA by more.
    const std::pair<const char*, int> filters[2] = { { "approximate",
                                                       vtkSurfaceSplatMapper::APPROXIMATE },
      { "circular", vtkSurfaceSplatMapper::CIRCULAR } };
    for (const auto& filter : filters)
    {
      for (vtkSurfaceSplatMapper* mapper : scene.Mappers)
      {
        mapper->SetFilterMode(filter.second);
      }
      window->Render();
      const double filterRmse =
        splattest::RMSE(images[0], splattest::ToRGB(splattest::Capture(window)));
      std::printf("%-20s CPU EWA vs OpenGL %s RMSE %.5f\n", scene.Name.c_str(), filter.first,
        filterRmse);
      if (entry.TellsFilters && !(filterRmse > scene.MaxRmse))
      {
        std::printf("FAIL: %s: the bound does not tell EWA from the %s filter\n",
          scene.Name.c_str(), filter.first);
        ++failures;
      }
    }
    for (vtkSurfaceSplatMapper* mapper : scene.Mappers)
    {
      mapper->SetFilterModeToEWA();
    }

    // AUTO: the CPU under a software OpenGL renderer, OpenGL on a GPU.
    SetBackend(scene, vtkSplatBackend::AUTO);
    window->Render();
    const int expected =
      vtkSplatBackend::IsSoftwareRenderer(window) ? vtkSplatBackend::CPU : vtkSplatBackend::OPENGL;
    if (scene.Mappers[0]->GetLastBackend() != expected)
    {
      std::printf("FAIL: AUTO drew with %s\n",
        vtkSplatBackend::GetBackendAsString(scene.Mappers[0]->GetLastBackend()));
      ++failures;
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
