// SPDX-License-Identifier: BSD-3-Clause
// splat_report's textured-plane scene: the checkerboard of SplatCheckerboardScene.h as a
// procedural texture acquired onto jittered surfels (SplatTextureScene.h) by
// vtkSurfelTextureAcquisition's three modes (point sampling, view-independent EWA, optimal),
// each drawn by vtkSurfaceSplatMapper (CPU backend, default settings) and measured against the
// scene's analytic reference, for checks 4 surfel spacings wide and 0.6 spacings wide. Reports
// the acquisition time per surfel, the render time, and the RMSE over the whole image, over the
// magnified rows near the camera and over the minified rows near the far end of the plane.
#ifndef SplatReportTexture_h
#define SplatReportTexture_h

#include "SplatReportCases.h"
#include "SplatReportImages.h"
#include "SplatTextureScene.h"

#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace splatreport
{
// At most this many surfels: the optimal fit's sparse system takes about 1.3 KB per surfel.
constexpr long long MaximumTexturePoints = 250000;

inline double BandRmse(
  const OIIO::ImageBuf& image, const OIIO::ImageBuf& reference, int firstRow, int endRow)
{
  const OIIO::ROI roi(0, image.spec().width, firstRow, endRow, 0, 1, 0, 3);
  return OIIO::ImageBufAlgo::compare(image, reference, 1.0f, 1.0f, roi).rms_error;
}

// Measures the scene; writes textured-plane.csv and the images into options.OutputDir and
// returns the report's Markdown section.
inline std::string MeasureTexturedPlane(
  vtkRenderWindow* window, vtkRenderer* renderer, const Options& options)
{
  const int width = options.Width, height = options.Height;
  // Rows (top first): the magnified bottom quarter; the minified band just below the plane's
  // far end (as in TestSurfelTextureRendering: rows 62 to 78 of 240).
  const int magnifiedFirst = height * 3 / 4;
  const int minifiedFirst = static_cast<int>(0.26 * height);
  const int minifiedEnd = static_cast<int>(0.33 * height);
  const char* const modes[3] = { "point-sampling", "view-independent-ewa", "optimal" };
  std::ostringstream csv, table;
  csv << "checks,mode,surfels,acquisition_s,us_per_surfel,cg_iterations,clamped,ms_per_frame,"
         "rmse,rmse_magnified,rmse_minified,image\n";
  table << "| checks | acquisition | s | us per surfel | CG iterations | ms/frame | RMSE | "
           "RMSE magnified rows | RMSE minified rows |\n"
        << "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  long long surfelCount = 0;
  double far = 0.0;
  for (const double checkOverSpacing : { 4.0, 0.6 })
  {
    splatexample::Checkerboard board;
    board.FitPoints(std::min(options.Points, MaximumTexturePoints));
    board.Check = checkOverSpacing * board.Spacing;
    far = board.Far;
    board.SetCamera(renderer->GetActiveCamera());
    renderer->SetBackground(board.Background.data());
    const std::string checks = Fixed(checkOverSpacing, 1) + "h";
    std::cerr << "splat_report: textured-plane, checks " << checks << ": analytic reference"
              << std::endl;
    const OIIO::ImageBuf reference = splatexample::CheckerboardReferences(
      board, renderer->GetActiveCamera(), width, height, options.Samples)[0];
    const std::string prefix = options.OutputDir + "/textured-plane-" + checks + "-";
    WriteImage(reference, prefix + "reference.png");
    vtkSmartPointer<vtkPolyData> surfels = splatexample::JitteredCheckerboardSurfels(
      board, renderer->GetActiveCamera(), width, height, 0.35);
    surfelCount = surfels->GetNumberOfPoints();
    for (int mode = 0; mode < 3; ++mode)
    {
      std::cerr << "splat_report: textured-plane, checks " << checks << ": " << modes[mode]
                << std::endl;
      const splatexample::AcquiredTexture acquired =
        splatexample::AcquireCheckerboard(surfels, board, mode);
      double ms = 0.0;
      const OIIO::ImageBuf image =
        splatexample::RenderTexturedSurfels(window, renderer, acquired.Surfels, &ms);
      const std::string file = "textured-plane-" + checks + "-" + modes[mode] + ".png";
      WriteImage(image, options.OutputDir + "/" + file);
      const double rmse = BandRmse(image, reference, 0, height);
      const double magnified = BandRmse(image, reference, magnifiedFirst, height);
      const double minified = BandRmse(image, reference, minifiedFirst, minifiedEnd);
      const double perSurfel = 1e6 * acquired.Seconds / std::max<long long>(1, surfelCount);
      csv << checks << "," << modes[mode] << "," << surfelCount << ","
          << Fixed(acquired.Seconds, 3) << "," << Fixed(perSurfel, 2) << ","
          << acquired.Iterations << "," << acquired.Clamped << "," << Fixed(ms, 1) << ","
          << Fixed(rmse, 5) << "," << Fixed(magnified, 5) << "," << Fixed(minified, 5) << ","
          << file << "\n";
      table << "| " << checks << " | " << modes[mode] << " | " << Fixed(acquired.Seconds, 2)
            << " | " << Fixed(perSurfel, 2) << " | " << acquired.Iterations << " | "
            << Fixed(ms, 1) << " | " << Fixed(rmse, 5) << " | " << Fixed(magnified, 5) << " | "
            << Fixed(minified, 5) << " |\n";
    }
  }
  const std::string csvPath = options.OutputDir + "/textured_plane.csv";
  std::ofstream file(csvPath);
  file << csv.str();
  if (!file)
  {
    throw std::runtime_error("cannot write '" + csvPath + "'");
  }

  std::ostringstream md;
  md << "## textured-plane\n\n"
     << "The checkerboard scene's plane (far end y = " << far << ") sampled by " << surfelCount
     << " surfels on a jittered grid (spacing h = 0.05, each point moved by up to 0.35 h along "
     << "x and y, radius h, texture coordinates (x, y); at most " << MaximumTexturePoints
     << " surfels, for the optimal fit's memory), colored by `vtkSurfelTextureAcquisition` from "
     << "the checkerboard as a procedural texture (the exact checks), checks 4 h and 0.6 h "
     << "wide, in its three modes, and drawn by `vtkSurfaceSplatMapper` (CPU backend, default "
     << "settings, one timed frame). Reference: the checkerboard scene's analytic one ("
     << options.Samples << "x" << options.Samples << " sub-samples, Gaussian pixel filter). "
     << "Magnified rows: the bottom quarter (a surfel spans several pixels); minified rows: "
     << minifiedFirst << " to " << minifiedEnd - 1 << " (top first), near the far end, where "
     << "a surfel spans a pixel or less. The acquisition time is the filter's update on "
     << AllThreads() << " threads; `textured_plane.csv` has the figures, "
     << "`textured-plane-<checks>-<mode>.png` the images.\n\n"
     << table.str() << "\n";
  return md.str();
}
}

#endif
