// SPDX-License-Identifier: BSD-3-Clause
// splat_report's output: the measured rows as CSV, Markdown tables and the plot of error against
// run time (VTK's charts).
#ifndef SplatReportOutput_h
#define SplatReportOutput_h

#include "SplatReportCases.h"

#include "vtkAxis.h"
#include "vtkChart.h"
#include "vtkChartLegend.h"
#include "vtkChartMatrix.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkPlotPoints.h"
#include "vtkRenderWindow.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkVector.h"

#include <algorithm>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace splatreport
{
/// One measured case: its time and its errors against the scene's references.
struct Row
{
  std::string Scene;
  const Case* What;
  int Threads;
  double Milliseconds;
  double Rmse; // against the scene's reference
  double Psnr;
  double RmseAlt; // against the reference with the other pixel filter
  double PsnrAlt;
  bool Pareto = false;
  std::string Image;
  std::string Counts; // what vtkSurfaceSplatMapper says it did in the last frame
  long long Splats = -1; // splats vtkSurfaceSplatMapper drew in the last frame (-1: not ours)
};

// The splats drawn by the default setting on the CPU, or -1.
inline long long DefaultSplats(const std::vector<Row>& rows)
{
  for (const Row& row : rows)
  {
    if (row.What->IsDefault && row.What->Backend == "CPU")
    {
      return row.Splats;
    }
  }
  return -1;
}

inline void WriteCsv(const std::vector<Row>& rows, const std::string& path)
{
  std::ofstream csv(path);
  csv << "scene,mapper,backend,setting,threads,ms_per_frame,rmse,psnr,rmse_alt,psnr_alt,"
         "is_default,pareto,image\n";
  for (const Row& r : rows)
  {
    csv << r.Scene << "," << r.What->Mapper << "," << r.What->Backend << ",\""
        << (r.What->Defaults ? "default" : r.What->Setting)
        << "\"," << (r.Threads > 0 ? std::to_string(r.Threads) : "") << ","
        << Fixed(r.Milliseconds, 2) << "," << Fixed(r.Rmse, 5) << "," << Fixed(r.Psnr, 2) << ","
        << Fixed(r.RmseAlt, 5) << "," << Fixed(r.PsnrAlt, 2) << ","
        << (r.What->IsDefault ? 1 : 0) << "," << (r.Pareto ? 1 : 0) << "," << r.Image << "\n";
  }
  if (!csv)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

inline std::string MarkdownTable(const std::vector<Row>& rows, const std::string& alternative)
{
  std::ostringstream md;
  md << "| mapper | backend | setting | threads | ms/frame | RMSE | PSNR (dB) | Pareto front | "
        "RMSE, "
     << alternative << " |\n"
     << "|---|---|---|---:|---:|---:|---:|:---:|---:|\n";
  for (const Row& r : rows)
  {
    std::string setting = r.What->Setting;
    if (r.What->IsDefault)
    {
      setting = "**" + setting + "**";
    }
    md << "| " << r.What->Mapper << " | " << r.What->Backend << " | " << setting << " | "
       << (r.Threads > 0 ? std::to_string(r.Threads) : "driver") << " | "
       << Fixed(r.Milliseconds, 1) << " | " << Fixed(r.Rmse, 4) << " | " << Fixed(r.Psnr, 2)
       << " | " << (r.Pareto ? "yes" : "") << " | " << Fixed(r.RmseAlt, 4) << " |\n";
  }
  md << "\nPareto front (fastest first):";
  std::vector<const Row*> front;
  for (const Row& r : rows)
  {
    if (r.Pareto)
    {
      front.push_back(&r);
    }
  }
  std::sort(front.begin(), front.end(),
    [](const Row* a, const Row* b) { return a->Milliseconds < b->Milliseconds; });
  for (std::size_t i = 0; i < front.size(); ++i)
  {
    const Row& r = *front[i];
    // Our mapper's CPU rows unnamed, the others by backend ("OpenGL default") or peer.
    md << (i ? "; " : " ")
       << (!IsOurs(*r.What) ? r.What->Mapper + " "
              : OnOtherBackend(*r.What)              ? r.What->Backend + " "
                                                     : "")
       << (r.What->IsDefault ? std::string("the default") : r.What->Setting)
       << (r.Threads > 0
              ? ", " + std::to_string(r.Threads) + (r.Threads == 1 ? " thread" : " threads")
              : "")
       << " (" << Fixed(r.Milliseconds, 1) << " ms, RMSE " << Fixed(r.Rmse, 4) << ")";
  }
  md << ".\n";
  for (const Row& r : rows)
  {
    if (r.What->IsDefault && !r.Counts.empty())
    {
      md << "\n" << r.What->Mapper << " with the default setting, last frame: " << r.Counts
         << ".\n";
    }
  }
  return md.str();
}

// The plot: RMSE against ms per frame (log scale), one chart per scene (two per row), one point
// series per family of settings and backend, and the Pareto front as a line. A family's series
// share a marker and a hue, dark on the CPU and light on OpenGL.
inline void WritePlot(const std::vector<std::string>& scenes, const std::vector<Row>& rows,
  const std::string& path)
{
  vtkNew<vtkContextView> view;
  vtkRenderWindow* window = view->GetRenderWindow();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  // Two charts per row at most (surface scenes on top, volume scenes below).
  const int columns = std::min(2, static_cast<int>(scenes.size()));
  const int chartRows = (static_cast<int>(scenes.size()) + columns - 1) / columns;
  window->SetSize(640 * columns, 620 * chartRows);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartMatrix> matrix;
  matrix->SetSize(vtkVector2i(columns, chartRows));
  matrix->SetGutter(vtkVector2f(70.0f, 60.0f));
  view->GetScene()->AddItem(matrix);

  // Tableau's paired colors, after black and gray for the default.
  const unsigned char palette[][2][3] = { { { 0, 0, 0 }, { 150, 150, 150 } },
    { { 31, 119, 180 }, { 174, 199, 232 } }, { { 255, 127, 14 }, { 255, 187, 120 } },
    { { 44, 160, 44 }, { 152, 223, 138 } }, { { 214, 39, 40 }, { 255, 152, 150 } },
    { { 148, 103, 189 }, { 197, 176, 213 } }, { { 140, 86, 75 }, { 196, 156, 148 } },
    { { 227, 119, 194 }, { 247, 182, 210 } }, { { 188, 189, 34 }, { 219, 219, 141 } },
    { { 23, 190, 207 }, { 158, 218, 229 } } };
  const int markers[] = { vtkPlotPoints::DIAMOND, vtkPlotPoints::CIRCLE, vtkPlotPoints::SQUARE,
    vtkPlotPoints::PLUS, vtkPlotPoints::CROSS };
  std::vector<vtkSmartPointer<vtkTable>> tables; // alive until rendered

  for (std::size_t s = 0; s < scenes.size(); ++s)
  {
    // The chart matrix counts rows from the bottom.
    vtkChart* chart = matrix->GetChart(vtkVector2i(
      static_cast<int>(s) % columns, chartRows - 1 - static_cast<int>(s) / columns));
    chart->SetTitle(scenes[s] + ": error against time");
    chart->GetTitleProperties()->SetFontSize(16);
    chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("ms per frame (log scale)");
    chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(true);
    chart->GetAxis(vtkAxis::LEFT)->SetTitle("RMSE against the reference");
    chart->SetShowLegend(true);
    chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
    chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);

    std::vector<std::string> families; // of settings, in the order of the rows
    std::vector<std::string> series;   // their series, per backend
    std::vector<const Case*> firstCases;
    std::vector<const Row*> front;
    for (const Row& r : rows)
    {
      if (r.Scene != scenes[s])
      {
        continue;
      }
      if (std::find(families.begin(), families.end(), r.What->Family) == families.end())
      {
        families.push_back(r.What->Family);
      }
      if (std::find(series.begin(), series.end(), SeriesOf(*r.What)) == series.end())
      {
        series.push_back(SeriesOf(*r.What));
        firstCases.push_back(r.What);
      }
      if (r.Pareto)
      {
        front.push_back(&r);
      }
    }
    std::sort(front.begin(), front.end(),
      [](const Row* a, const Row* b) { return a->Milliseconds < b->Milliseconds; });
    // Fixed ranges with room at the top for the legend.
    double lowMs = std::numeric_limits<double>::max(), highMs = 0.0, highRmse = 0.0;
    for (const Row& r : rows)
    {
      if (r.Scene == scenes[s])
      {
        lowMs = std::min(lowMs, r.Milliseconds);
        highMs = std::max(highMs, r.Milliseconds);
        highRmse = std::max(highRmse, r.Rmse);
      }
    }
    vtkAxis* time = chart->GetAxis(vtkAxis::BOTTOM);
    time->SetBehavior(vtkAxis::FIXED);
    time->SetUnscaledRange(std::max(lowMs / 1.3, 1e-3), std::max(highMs * 1.3, 2e-3));
    vtkAxis* error = chart->GetAxis(vtkAxis::LEFT);
    error->SetBehavior(vtkAxis::FIXED);
    error->SetRange(0.0, highRmse > 0.0 ? 2.0 * highRmse : 1.0);
    if (front.size() > 1)
    {
      vtkNew<vtkTable> table;
      vtkNew<vtkFloatArray> ms, rmse;
      ms->SetName("ms");
      rmse->SetName("Pareto front");
      for (const Row* r : front)
      {
        ms->InsertNextValue(static_cast<float>(r->Milliseconds));
        rmse->InsertNextValue(static_cast<float>(r->Rmse));
      }
      table->AddColumn(ms);
      table->AddColumn(rmse);
      vtkPlot* line = chart->AddPlot(vtkChart::LINE);
      line->SetInputData(table, 0, 1);
      line->SetColor(160, 160, 160, 255);
      line->SetWidth(1.5f);
      line->GetPen()->SetLineType(vtkPen::DASH_LINE);
      line->SetLabel("Pareto front");
      tables.push_back(table.Get());
    }
    for (std::size_t f = 0; f < series.size(); ++f)
    {
      vtkNew<vtkTable> table;
      vtkNew<vtkFloatArray> ms, rmse;
      ms->SetName("ms");
      rmse->SetName(series[f].c_str());
      for (const Row& r : rows)
      {
        if (r.Scene == scenes[s] && SeriesOf(*r.What) == series[f])
        {
          ms->InsertNextValue(static_cast<float>(r.Milliseconds));
          rmse->InsertNextValue(static_cast<float>(r.Rmse));
        }
      }
      table->AddColumn(ms);
      table->AddColumn(rmse);
      auto* points = vtkPlotPoints::SafeDownCast(chart->AddPlot(vtkChart::POINTS));
      points->SetInputData(table, 0, 1);
      const std::size_t family =
        std::find(families.begin(), families.end(), firstCases[f]->Family) - families.begin();
      const unsigned char* color = palette[family % (sizeof(palette) / sizeof(palette[0]))]
                                          [OnOtherBackend(*firstCases[f]) ? 1 : 0];
      points->SetColor(color[0], color[1], color[2], 255);
      points->SetMarkerStyle(markers[family % (sizeof(markers) / sizeof(markers[0]))]);
      points->SetMarkerSize(family == 0 ? 14.0f : 10.0f);
      points->SetLabel(series[f]);
      tables.push_back(table.Get());
    }
  }
  view->Render();
  splatexample::WritePNG(window, path);
}
}

#endif
