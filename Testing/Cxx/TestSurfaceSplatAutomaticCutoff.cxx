// SPDX-License-Identifier: BSD-3-Clause
// vtkSurfaceSplatMapper's automatic cutoff (the default): 0.5 for surfels that cover their
// surface at that cutoff, else 0.6, else the paper's 1 for those that cover it at 1, else 2,
// 3 or 4, and any cutoff set by hand as it is. Checked through GetLastCutoff() and through the image,
// which must be the one the chosen cutoff draws when set by hand:
// - surfels on a mesh's vertices (vtkSurfelGenerator: radius of the longest edge) get 0.5;
// - points scattered at random over the same mesh (radius from the nearest points) get 3 (2
//   leaves more than 1% of what 4 covers open);
// - a grid of surfels whose radius is its spacing gets 0.6 (the tight disks at 0.5 only touch);
// - the same grid with a radius of 1.5 spacings gets 0.5; surfels of one color take a pixel's
//   box filter where they are minified too;
// - with colors from scalars, the grid's splats below splat::CutoffFadeStart (all of them in
//   this view) take the paper's cutoff where the low-pass matters: the image is the one of
//   cutoff 1 set by hand (to a unit of 8 bits: their weights are scaled to the mass they keep
//   at 0.6), not the one of 0.6, while GetLastCutoff() says 0.6;
// - differential points keep 1; SetCutoff(2) and SetCutoffToPaper() are used as set; a
//   negative cutoff is refused with an error and changes nothing.
// The automatic coverage threshold goes with it (GetLastCoverageThreshold()): 0.8 for surfels
// of one color that cover their surface at it with the chosen cutoff (the sphere's vertices,
// the wider grid), the paper's 0.4 for the others (the scattered points and the tight grid,
// whose summed weights fall short of 0.8; colors; differential points; a cutoff set by hand),
// and a threshold set by hand as it is.
#include "SplatTestUtilities.h"
#include "vtkDifferentialPointGenerator.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkPolyDataPointSampler.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cstdio>
#include <functional>
#include <string>

namespace
{
struct Drawn
{
  double Cutoff;
  std::vector<double> Pixels;
  double MinifiedLowPass;
  double CoverageThreshold;
};

// Draws `surfels` with a CPU mapper configured by `apply`: the cutoff it used and its image.
Drawn Draw(vtkPolyData* surfels, const std::function<void(vtkSurfaceSplatMapper*)>& apply)
{
  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(surfels);
  mapper->SetBackend(vtkSplatBackend::CPU);
  if (apply)
  {
    apply(mapper);
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  auto window = splattest::MakeRenderWindow(160, 160);
  window->AddRenderer(renderer);
  renderer->GetActiveCamera()->SetPosition(0.3, 0.4, 4.0);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Dolly(1.5);
  renderer->ResetCameraClippingRange();
  window->Render();
  return { mapper->GetLastCutoff(), splattest::ToRGB(splattest::Capture(window)),
    mapper->GetLastMinifiedLowPassVariance(), mapper->GetLastCoverageThreshold() };
}

// The default's cutoff and coverage threshold on `surfels` must be `expected` and
// `expectedTau`, with the image of both set by hand, and its minified splats (of one color) a
// pixel's box filter.
void CheckAutomatic(
  vtkPolyData* surfels, double expected, double expectedTau, const std::string& what)
{
  const Drawn automatic = Draw(surfels, nullptr);
  std::printf("%s: automatic cutoff %g, coverage threshold %g, minified low-pass %g\n",
    what.c_str(), automatic.Cutoff, automatic.CoverageThreshold, automatic.MinifiedLowPass);
  splattest::Check(automatic.Cutoff == expected,
    what + " draws with cutoff " + std::to_string(expected));
  splattest::Check(automatic.CoverageThreshold == expectedTau,
    what + " draws with coverage threshold " + std::to_string(expectedTau));
  splattest::Check(automatic.MinifiedLowPass == 1.0 / 12.0,
    what + ": minified splats take the box filter");
  const Drawn byHand = Draw(surfels,
    [&](vtkSurfaceSplatMapper* m)
    {
      m->SetCutoff(expected);
      m->SetCoverageThreshold(expectedTau);
    });
  splattest::Check(splattest::LargestDifference(automatic.Pixels, byHand.Pixels) == 0.0,
    what + ": the image is the one of its cutoff and threshold set by hand");
}

vtkSmartPointer<vtkPolyData> Surfels(vtkPolyData* input)
{
  vtkNew<vtkSurfelGenerator> generator;
  generator->SetInputData(input);
  generator->Update();
  return generator->GetOutput();
}

// A 60 x 60 grid of spacing 0.05 in the plane z = 0 with the given radius.
vtkSmartPointer<vtkPolyData> Grid(double radius)
{
  const double center[3] = { 0.0, 0.0, 0.0 };
  const double u[3] = { 0.05, 0.0, 0.0 };
  const double v[3] = { 0.0, 0.05, 0.0 };
  vtkSmartPointer<vtkPolyData> grid = splattest::SurfelPlane(center, u, v, 60, 60);
  vtkDataArray* radii = grid->GetPointData()->GetArray("Radius");
  for (vtkIdType i = 0; i < radii->GetNumberOfTuples(); ++i)
  {
    radii->SetTuple1(i, radius);
  }
  return grid;
}
}

int main(int, char*[])
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(80);
  sphere->SetPhiResolution(40);
  sphere->Update();
  CheckAutomatic(Surfels(sphere->GetOutput()), 0.5, 0.8, "surfels on a sphere's vertices");

  vtkNew<vtkPolyDataPointSampler> sampler;
  sampler->SetInputConnection(sphere->GetOutputPort());
  sampler->SetPointGenerationModeToRandom();
  sampler->SetDistance(0.03);
  sampler->GenerateVertexPointsOff();
  sampler->GenerateEdgePointsOff();
  sampler->Update();
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(sampler->GetOutput()->GetPoints());
  CheckAutomatic(Surfels(cloud), 3.0, 0.4, "points scattered over the sphere");

  CheckAutomatic(Grid(0.05), 0.6, 0.4, "a grid with the radius of its spacing");
  CheckAutomatic(Grid(0.075), 0.5, 0.8, "a grid with 1.5 times the radius of its spacing");

  vtkSmartPointer<vtkPolyData> colored = Grid(0.05);
  const double orange[3] = { 0.9, 0.6, 0.2 };
  splattest::Paint(colored, orange, 1.0);
  const Drawn automatic = Draw(colored, nullptr);
  splattest::Check(automatic.Cutoff == 0.6, "a colored grid's cutoff is 0.6");
  splattest::Check(
    automatic.CoverageThreshold == 0.4, "a colored grid keeps the paper's coverage threshold");
  const double fromPaper = splattest::LargestDifference(automatic.Pixels,
    Draw(colored, [](vtkSurfaceSplatMapper* m) { m->SetCutoffToPaper(); }).Pixels);
  const double fromSnug = splattest::LargestDifference(
    automatic.Pixels, Draw(colored, [](vtkSurfaceSplatMapper* m) { m->SetCutoff(0.6); }).Pixels);
  std::printf("a colored grid: largest difference %g from cutoff 1, %g from 0.6\n", fromPaper,
    fromSnug);
  splattest::Check(fromPaper <= 1.0 / 255.0 && fromSnug > 1.0 / 255.0,
    "a colored grid's small splats draw with the paper's cutoff");

  vtkSmartPointer<vtkPolyData> surfels = Surfels(sphere->GetOutput());
  const Drawn setCutoff = Draw(surfels, [](vtkSurfaceSplatMapper* m) { m->SetCutoff(2.0); });
  splattest::Check(setCutoff.Cutoff == 2.0 && setCutoff.CoverageThreshold == 0.4,
    "a cutoff set by hand is used as set, with the paper's coverage threshold");
  splattest::Check(
    Draw(surfels, [](vtkSurfaceSplatMapper* m) { m->SetCoverageThreshold(0.3); })
        .CoverageThreshold == 0.3,
    "a coverage threshold set by hand is used as set");
  splattest::Check(
    Draw(surfels, [](vtkSurfaceSplatMapper* m) { m->SetCoverageThresholdToPaper(); })
        .CoverageThreshold == 0.4,
    "SetCoverageThresholdToPaper draws with 0.4");
  splattest::Check(
    Draw(surfels, [](vtkSurfaceSplatMapper* m) { m->SetCutoffToPaper(); }).Cutoff == 1.0,
    "SetCutoffToPaper draws with cutoff 1");
  vtkNew<vtkDifferentialPointGenerator> differential;
  differential->SetInputConnection(sphere->GetOutputPort());
  differential->SimplifyOff();
  differential->Update();
  const Drawn points = Draw(differential->GetOutput(),
    [](vtkSurfaceSplatMapper* m) { m->SetPrimitiveToDifferentialPoints(); });
  splattest::Check(points.Cutoff == 1.0 && points.CoverageThreshold == 0.4,
    "differential points keep the paper's cutoff and coverage threshold");

  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetCutoff(2.0);
  vtkObject::GlobalWarningDisplayOff();
  mapper->SetCutoff(-1.0);
  vtkObject::GlobalWarningDisplayOn();
  splattest::Check(mapper->GetCutoff() == 2.0, "a negative cutoff is refused");
  mapper->SetCutoffToAutomatic();
  splattest::Check(mapper->GetCutoff() == 0.0, "SetCutoffToAutomatic sets 0");
  return splattest::Failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
