// SPDX-License-Identifier: BSD-3-Clause
// splat_report's differential-points section (paper 004's comparison, its table II and figure
// 10): the bunny scene's mesh, camera and reference, drawn by vtkSurfaceSplatMapper (CPU backend,
// default settings) from
// - plain EWA surfels (vtkSurfelGenerator) on the mesh and on decimated copies of it;
// - differential points (vtkDifferentialPointGenerator, simplification off) on the same
//   vertices, EWA-filtered and as the paper's unfiltered rectangles: equal primitives;
// - differential points simplified from the full mesh at several maximum principal errors, by the
//   paper's greedy enclosure test and by the set cover, with both footprints.
// Each row: primitives, bytes per primitive as the filters store them, the time to make them,
// ms per frame (the median over the report's rounds, every row timed in turn in each), RMSE
// against the mesh's reference; for the differential points, the number of
// surfels and their ms at the same error, interpolated along the surfels' rows. Writes
// differential-points.csv, differential-points.png (error against primitives and against time)
// and an image per row; returns the Markdown section.
#ifndef SplatReportDifferentialPoints_h
#define SplatReportDifferentialPoints_h

#include "SplatCheckerboardReference.h" // For CaptureWindow
#include "SplatReportCases.h"
#include "SplatReportImages.h"
#include "vtkDifferentialPointGenerator.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"

#include "vtkActor.h"
#include "vtkAxis.h"
#include "vtkChart.h"
#include "vtkChartLegend.h"
#include "vtkChartMatrix.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkFloatArray.h"
#include "vtkPlotPoints.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkQuadricDecimation.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace splatreport
{
struct DifferentialPointRow
{
  std::string Series; // "surfels", "differential points", ...
  std::string Source; // what the primitives were made from
  vtkIdType Primitives = 0;
  double BytesPerPrimitive = 0.0;
  double MakeSeconds = 0.0;
  double Milliseconds = 0.0;
  double Rmse = 0.0;
  std::string Image;
  vtkSmartPointer<vtkActor> Actor; // kept for the timing rounds
  std::vector<double> Times;       // ms per frame, one per round
};

// Bytes per point of a point set as stored: its coordinates and every point-data array.
inline double StoredBytesPerPoint(vtkPolyData* data)
{
  vtkDataArray* points = data->GetPoints()->GetData();
  double bytes = points->GetDataTypeSize() * points->GetNumberOfComponents();
  vtkPointData* pointData = data->GetPointData();
  for (int i = 0; i < pointData->GetNumberOfArrays(); ++i)
  {
    if (vtkDataArray* array = pointData->GetArray(i))
    {
      bytes += array->GetDataTypeSize() * array->GetNumberOfComponents();
    }
  }
  return bytes;
}

// The surfels' (primitives, ms) at `rmse`, interpolated along their rows (log of the primitives,
// linear in ms) between the two rows whose errors bracket it; false outside their range.
inline bool SurfelsAtError(const std::vector<DifferentialPointRow>& surfels, double rmse,
  double& primitives, double& milliseconds)
{
  for (std::size_t i = 0; i + 1 < surfels.size(); ++i)
  {
    const DifferentialPointRow& a = surfels[i]; // more primitives, less error
    const DifferentialPointRow& b = surfels[i + 1];
    if (a.Rmse <= rmse && rmse <= b.Rmse && b.Rmse > a.Rmse)
    {
      const double t = (rmse - a.Rmse) / (b.Rmse - a.Rmse);
      primitives = std::exp((1.0 - t) * std::log(static_cast<double>(a.Primitives)) +
        t * std::log(static_cast<double>(b.Primitives)));
      milliseconds = (1.0 - t) * a.Milliseconds + t * b.Milliseconds;
      return true;
    }
  }
  return false;
}

// Two charts: RMSE against the number of primitives and against ms per frame, one point series
// per row series.
inline void WriteDifferentialPointPlot(
  const std::vector<DifferentialPointRow>& rows, const std::string& path)
{
  vtkNew<vtkContextView> view;
  vtkRenderWindow* window = view->GetRenderWindow();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(1280, 560);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartMatrix> matrix;
  matrix->SetSize(vtkVector2i(2, 1));
  matrix->SetGutter(vtkVector2f(70.0f, 60.0f));
  view->GetScene()->AddItem(matrix);
  std::vector<std::string> series;
  for (const DifferentialPointRow& r : rows)
  {
    if (std::find(series.begin(), series.end(), r.Series) == series.end())
    {
      series.push_back(r.Series);
    }
  }
  const unsigned char colors[][3] = { { 0, 0, 0 }, { 31, 119, 180 }, { 255, 127, 14 },
    { 44, 160, 44 }, { 214, 39, 40 }, { 148, 103, 189 }, { 140, 86, 75 } };
  const int markers[] = { vtkPlotPoints::DIAMOND, vtkPlotPoints::CIRCLE, vtkPlotPoints::SQUARE,
    vtkPlotPoints::PLUS, vtkPlotPoints::CROSS, vtkPlotPoints::CIRCLE, vtkPlotPoints::SQUARE };
  constexpr std::size_t Styles = sizeof(markers) / sizeof(markers[0]);
  std::vector<vtkSmartPointer<vtkTable>> tables; // alive until rendered
  for (int chartIndex = 0; chartIndex < 2; ++chartIndex)
  {
    const bool byTime = chartIndex == 1;
    vtkChart* chart = matrix->GetChart(vtkVector2i(chartIndex, 0));
    chart->SetTitle(byTime ? "bunny: error against time" : "bunny: error against primitives");
    chart->GetTitleProperties()->SetFontSize(16);
    chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(
      byTime ? "ms per frame (CPU)" : "primitives (log scale)");
    chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(!byTime);
    chart->GetAxis(vtkAxis::LEFT)->SetTitle("RMSE against the mesh");
    chart->SetShowLegend(true);
    chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
    for (std::size_t s = 0; s < series.size(); ++s)
    {
      vtkNew<vtkTable> table;
      vtkNew<vtkFloatArray> x, rmse;
      x->SetName(byTime ? "ms" : "primitives");
      rmse->SetName(series[s].c_str());
      for (const DifferentialPointRow& r : rows)
      {
        if (r.Series == series[s])
        {
          x->InsertNextValue(
            static_cast<float>(byTime ? r.Milliseconds : static_cast<double>(r.Primitives)));
          rmse->InsertNextValue(static_cast<float>(r.Rmse));
        }
      }
      table->AddColumn(x);
      table->AddColumn(rmse);
      auto* points = vtkPlotPoints::SafeDownCast(chart->AddPlot(vtkChart::POINTS));
      points->SetInputData(table, 0, 1);
      const unsigned char* color = colors[s % Styles];
      points->SetColor(color[0], color[1], color[2], 255);
      points->SetMarkerStyle(markers[s % Styles]);
      points->SetMarkerSize(10.0f);
      points->SetLabel(series[s]);
      tables.push_back(table.Get());
    }
  }
  view->Render();
  splatexample::WritePNG(window, path);
}

// Measures the section. The renderer's camera shows the bunny; `reference` is its mesh's
// reference image; timeFrames renders the window's current scene and returns its ms per frame.
inline std::string MeasureDifferentialPoints(vtkRenderWindow* window, vtkRenderer* renderer,
  vtkPolyData* mesh, const OIIO::ImageBuf& reference, const double color[3],
  const Options& options, const std::function<double()>& timeFrames)
{
  using Clock = std::chrono::steady_clock;
  const double delta = mesh->GetLength() / 50.0;
  std::vector<DifferentialPointRow> rows;
  const auto measure = [&](const std::string& series, const std::string& source,
                         vtkPolyData* points, double makeSeconds, bool differential,
                         bool rectangles)
  {
    std::cerr << "splat_report: bunny, differential points: " << series << ", " << source
              << std::endl;
    vtkNew<vtkSurfaceSplatMapper> mapper;
    mapper->SetInputData(points);
    mapper->SetBackendToCPU();
    mapper->ScalarVisibilityOff();
    if (differential)
    {
      mapper->SetPrimitiveToDifferentialPoints();
    }
    if (rectangles)
    {
      mapper->SetFilterModeToUnfiltered();
    }
    DifferentialPointRow row{ series, source, points->GetNumberOfPoints(),
      StoredBytesPerPoint(points), makeSeconds };
    row.Actor = vtkSmartPointer<vtkActor>::New();
    row.Actor->SetMapper(mapper);
    row.Actor->GetProperty()->SetColor(color[0], color[1], color[2]);
    renderer->RemoveAllViewProps();
    renderer->AddActor(row.Actor);
    row.Times.push_back(timeFrames());
    const OIIO::ImageBuf image = splatexample::CaptureWindow(window);
    row.Rmse = OIIO::ImageBufAlgo::compare(image, reference, 1.0f, 1.0f).rms_error;
    row.Image = "differential-points-" + std::to_string(rows.size()) + ".png";
    WriteImage(image, options.OutputDir + "/" + row.Image);
    rows.push_back(row);
    renderer->RemoveAllViewProps();
  };
  const auto seconds = [](Clock::time_point start)
  { return std::chrono::duration<double>(Clock::now() - start).count(); };

  // The mesh and its decimated copies: the same vertices for both kinds of primitive.
  for (const double kept : { 1.0, 0.5, 0.25, 0.125 })
  {
    vtkSmartPointer<vtkPolyData> vertices = mesh;
    if (kept < 1.0)
    {
      vtkNew<vtkQuadricDecimation> decimate;
      decimate->SetInputData(mesh);
      decimate->SetTargetReduction(1.0 - kept);
      decimate->Update();
      vertices = decimate->GetOutput();
    }
    const std::string source =
      std::to_string(vertices->GetNumberOfPoints()) + " vertices" +
      (kept < 1.0 ? " (mesh decimated to " + Fixed(100.0 * kept, 1) + "%)" : " (the mesh)");
    auto start = Clock::now();
    vtkNew<vtkSurfelGenerator> surfels;
    surfels->SetInputData(vertices);
    surfels->Update();
    measure("surfels", source, surfels->GetOutput(), seconds(start), false, false);
    start = Clock::now();
    vtkNew<vtkDifferentialPointGenerator> points;
    points->SetInputData(vertices);
    points->SimplifyOff();
    points->SetMaximumPrincipalWidth(delta);
    points->Update();
    const double made = seconds(start);
    measure("differential points", source, points->GetOutput(), made, true, false);
    measure("rectangles", source, points->GetOutput(), made, true, true);
  }
  // Simplified from the full mesh by each simplification, drawn with each footprint.
  for (const int mode :
    { vtkDifferentialPointGenerator::GREEDY_ENCLOSURE, vtkDifferentialPointGenerator::SET_COVER })
  {
    const std::string name =
      mode == vtkDifferentialPointGenerator::SET_COVER ? "set cover" : "greedy enclosure";
    for (const double epsilon : { 0.005, 0.01, 0.02, 0.05 })
    {
      const auto start = Clock::now();
      vtkNew<vtkDifferentialPointGenerator> points;
      points->SetInputData(mesh);
      points->SetSimplificationMode(mode);
      points->SetMaximumPrincipalError(epsilon);
      points->SetMaximumPrincipalWidth(delta);
      points->Update();
      const double made = seconds(start);
      const std::string source = "eps " + Fixed(epsilon, 3) + " (the mesh)";
      measure(name + ", differential points", source, points->GetOutput(), made, true, false);
      measure(name + ", rectangles", source, points->GetOutput(), made, true, true);
    }
  }
  // The other rounds time every row again, in turn, so that the machine's changing load weighs
  // on all rows alike; each row's time is the median of its rounds'.
  for (int round = 1; round < options.Rounds; ++round)
  {
    for (DifferentialPointRow& row : rows)
    {
      std::cerr << "splat_report: bunny, differential points (round " << round + 1 << "/"
                << options.Rounds << "): " << row.Series << ", " << row.Source << std::endl;
      renderer->AddActor(row.Actor);
      row.Times.push_back(timeFrames());
      renderer->RemoveAllViewProps();
    }
  }
  for (DifferentialPointRow& row : rows)
  {
    row.Milliseconds = splatexample::Median(row.Times);
    row.Actor = nullptr;
  }
  WriteDifferentialPointPlot(rows, options.OutputDir + "/differential-points.png");

  std::vector<DifferentialPointRow> surfels;
  for (const DifferentialPointRow& r : rows)
  {
    if (r.Series == "surfels")
    {
      surfels.push_back(r);
    }
  }
  std::ofstream csv(options.OutputDir + "/differential-points.csv");
  csv << "series,source,primitives,bytes_per_primitive,make_s,ms_per_frame,rmse,"
         "surfels_at_same_rmse,surfel_ms_at_same_rmse,primitive_ratio,time_ratio,image\n";
  std::ostringstream md;
  md << "### bunny: differential points against surfels (paper 004)\n\n"
     << "The bunny scene's mesh, camera and reference, drawn by vtkSurfaceSplatMapper on the "
     << "CPU at its defaults from plain surfels (vtkSurfelGenerator) and from differential "
     << "points (vtkDifferentialPointGenerator, maximum principal width " << Fixed(delta, 5)
     << ", a fiftieth of the diagonal) on the same vertices, simplification off, EWA-filtered "
     << "and as the paper's unfiltered rectangles; then simplified from the full mesh at "
     << "several maximum principal errors by the paper's greedy enclosure test and by the set "
     << "cover (the default), with both footprints. Bytes per primitive: the coordinates and point "
     << "arrays as the filters store them. The last columns interpolate, along the surfels' "
     << "rows, how many surfels reach the same RMSE and in how many ms (blank outside their "
     << "range), and divide them by the row's primitives and ms. The paper's claim: the same "
     << "error with at most half the primitives and at least 1.5x less time (ratios of at least "
     << "2 and 1.5). The surfels' fewest-primitive row shows the frame's fixed cost. Time: the median over " << options.Rounds
     << " rounds, each timing every row in turn. Plot: `differential-points.png`.\n\n"
     << "| primitives | made from | count | bytes each | made in s | ms/frame | RMSE | "
        "surfels at this RMSE | their ms | primitive ratio | time ratio |\n"
     << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const DifferentialPointRow& r : rows)
  {
    double same = 0.0, sameMs = 0.0;
    const bool bracketed =
      r.Series != "surfels" && SurfelsAtError(surfels, r.Rmse, same, sameMs);
    const std::string sameText = bracketed ? std::to_string(std::lround(same)) : "";
    const std::string sameMsText = bracketed ? Fixed(sameMs, 1) : "";
    const std::string primitiveRatio = bracketed ? Fixed(same / r.Primitives, 2) : "";
    const std::string timeRatio = bracketed ? Fixed(sameMs / r.Milliseconds, 2) : "";
    csv << "\"" << r.Series << "\",\"" << r.Source << "\"," << r.Primitives << ","
        << Fixed(r.BytesPerPrimitive, 0) << "," << Fixed(r.MakeSeconds, 3) << ","
        << Fixed(r.Milliseconds, 2) << "," << Fixed(r.Rmse, 5) << "," << sameText << ","
        << sameMsText << "," << primitiveRatio << "," << timeRatio << "," << r.Image << "\n";
    md << "| " << r.Series << " | " << r.Source << " | " << r.Primitives << " | "
       << Fixed(r.BytesPerPrimitive, 0) << " | " << Fixed(r.MakeSeconds, 2) << " | "
       << Fixed(r.Milliseconds, 1) << " | " << Fixed(r.Rmse, 4) << " | " << sameText << " | "
       << sameMsText << " | " << primitiveRatio << " | " << timeRatio << " |\n";
  }
  md << "\n";
  return md.str();
}
}

#endif
