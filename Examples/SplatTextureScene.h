// SPDX-License-Identifier: BSD-3-Clause
// The textured-plane scene of splat_report and TestSurfelTextureAcquisition: the checkerboard
// plane of SplatCheckerboardScene.h, sampled by a jittered grid of surfels (spacing h, each point
// moved by up to Jitter * h along x and y) that carry texture coordinates (s, t) = (x, y) and get
// their colors from the checkerboard texture by vtkSurfelTextureAcquisition (point sampling,
// view-independent EWA or the optimal fit). The checkerboard is a procedural texture (a callback
// giving the exact checks), so the scene's analytic reference (CheckerboardReferences) is the
// reference of the textured plane too.
#ifndef SplatTextureScene_h
#define SplatTextureScene_h

#include "SplatCheckerboardReference.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelTextureAcquisition.h"

#include "vtkActor.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <chrono>
#include <cmath>
#include <random>

namespace splatexample
{
// Jittered surfels over the visible part of the checkerboard plane (the visible cells of
// ForEachGridCell, as CheckerboardSurfels), radius h, normal +z, texture coordinates (x, y) as the active
// TCoords; no colors. The jitter is deterministic (seed).
inline vtkSmartPointer<vtkPolyData> JitteredCheckerboardSurfels(const Checkerboard& board,
                                                                vtkCamera* camera, int width,
                                                                int height, double jitter,
                                                                unsigned seed = 1)
{
  const double h = board.Spacing;
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-jitter * h, jitter * h);
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName("TCoords");
  tcoords->SetNumberOfComponents(2);
  ForEachGridCell(board, camera, width, height, [&](long long i, long long j, bool visible) {
    const double dx = offset(random), dy = offset(random); // drawn for every cell
    if (!visible)
    {
      return;
    }
    const double px = (i + 0.5) * h + dx;
    const double py = std::min((j + 0.5) * h + dy, board.Far - 0.05 * h);
    points->InsertNextPoint(px, py, 0.0);
    normals->InsertNextTuple3(0.0, 0.0, 1.0);
    radii->InsertNextValue(static_cast<float>(h));
    tcoords->InsertNextTuple2(px, py);
  });
  auto surfels = vtkSmartPointer<vtkPolyData>::New();
  surfels->SetPoints(points);
  surfels->GetPointData()->SetNormals(normals);
  surfels->GetPointData()->AddArray(radii);
  surfels->GetPointData()->SetTCoords(tcoords);
  return surfels;
}

// The checkerboard as a procedural texture over (s, t) = (x, y): the exact checks.
inline vtkSurfelTextureAcquisition::TextureFunction CheckerboardTexture(const Checkerboard& board)
{
  return [board](double s, double t, double rgba[4])
  {
    const double dark = board.DarkFraction(s, s, t, t);
    for (int k = 0; k < 3; ++k)
    {
      rgba[k] = board.Light[k] + dark * (board.Dark[k] - board.Light[k]);
    }
    rgba[3] = 1.0;
  };
}

// Draws the surfels' colors with vtkSurfaceSplatMapper (CPU backend, default settings) in the
// checkerboard scene's style and returns the image; with `milliseconds`, after a warm-up frame,
// the time of one more frame.
inline OIIO::ImageBuf RenderTexturedSurfels(vtkRenderWindow* window, vtkRenderer* renderer,
  vtkPolyData* surfels, double* milliseconds = nullptr)
{
  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(surfels);
  mapper->SetRadiusArrayName("Radius");
  mapper->SetBackendToCPU();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  StyleCheckerboardActor(actor);
  renderer->RemoveAllViewProps();
  renderer->AddActor(actor);
  window->Render();
  if (milliseconds)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    *milliseconds =
      1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  OIIO::ImageBuf image = CaptureWindow(window);
  renderer->RemoveAllViewProps();
  return image;
}

struct AcquiredTexture
{
  vtkSmartPointer<vtkPolyData> Surfels; // with the RGB array "TextureColors" as active scalars
  double Seconds = 0.0;                 // the filter's update
  int Iterations = 0;
  vtkIdType Clamped = 0;
};

// The checkerboard texture acquired onto the surfels with vtkSurfelTextureAcquisition's mode.
inline AcquiredTexture AcquireCheckerboard(vtkPolyData* surfels, const Checkerboard& board,
                                           int mode)
{
  vtkNew<vtkSurfelTextureAcquisition> acquisition;
  acquisition->SetInputData(surfels);
  acquisition->SetTextureFunction(CheckerboardTexture(board));
  acquisition->SetMode(mode);
  const auto start = std::chrono::steady_clock::now();
  acquisition->Update();
  AcquiredTexture result;
  result.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.Surfels = acquisition->GetOutput();
  result.Iterations = acquisition->GetNumberOfIterations();
  result.Clamped = acquisition->GetNumberOfClampedValues();
  return result;
}
}

#endif
