// SPDX-License-Identifier: BSD-3-Clause
// splat_report's stability section: every stiff and extreme case of
// Testing/Cxx/SplatStabilityCases.h (the cases TestSplatStability asserts under CTest), rendered
// with its mapper on each backend asked for, next to the same scene without the extreme (the
// mapper's baseline case, drawn with the same camera handling). Per case and backend: NaN/Inf
// values in the mapper's float image, whether it rendered (the process survived), the kernels
// skipped and why, errors and warnings, ms per frame against the baseline's, and the RMSE
// against a reference image where the case has one (the same scene moved, scaled or mirrored).
// Writes stability.csv, stability.md and one PNG per case and backend.
#ifndef SplatReportStability_h
#define SplatReportStability_h

#include "SplatReportCases.h"
#include "SplatStabilityRun.h"

#include "vtkImageImport.h"
#include "vtkPNGWriter.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

namespace splatreport
{
// A case's ms per frame may exceed its baseline's by this factor at most, except where the case
// has more kernels or pixels than its baseline (coincident points, the 1x4096 window).
constexpr double StabilityCostBound = 10.0;

// The case of that name for that mapper, or null.
inline const splatstability::Case* FindCase(
  const std::vector<splatstability::Case>& cases, const std::string& name, int kind)
{
  for (const splatstability::Case& c : cases)
  {
    if (c.Name == name && c.Kind == kind)
    {
      return &c;
    }
  }
  return nullptr;
}

// The case's scene without the extreme: its reference if it has one, else the mapper's
// baseline for that kind of input (the surfel sphere, the kernel set or the image blob).
inline std::string BaselineOf(const splatstability::Case& c)
{
  if (!c.Reference.empty())
  {
    return c.Reference;
  }
  if (c.Kind == splatstability::Surface)
  {
    return "sphere";
  }
  return vtkImageData::SafeDownCast(c.Make().Input) ? "blob" : "gaussians";
}

// Writes an RGB image (floats in [0, 1], rows from the bottom) as PNG.
inline void WriteRGB(const std::vector<double>& rgb, int width, int height, const std::string& path)
{
  std::vector<unsigned char> bytes(rgb.size());
  std::transform(rgb.begin(), rgb.end(), bytes.begin(),
    [](double v) { return static_cast<unsigned char>(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); });
  vtkNew<vtkImageImport> import;
  import->CopyImportVoidPointer(bytes.data(), static_cast<vtkIdType>(bytes.size()));
  import->SetDataScalarTypeToUnsignedChar();
  import->SetNumberOfScalarComponents(3);
  import->SetWholeExtent(0, width - 1, 0, height - 1, 0, 0);
  import->SetDataExtentToWholeExtent();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(import->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->Write();
}

// CSV text: quotes and commas out of free text.
inline std::string CsvText(std::string text)
{
  std::replace(text.begin(), text.end(), ',', ';');
  std::replace(text.begin(), text.end(), '"', '\'');
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

// The first line of a VTK error or warning message, without VTK's "ERROR: In file, line"
// header.
inline std::string MessageText(const std::string& message)
{
  std::string text = message;
  const std::size_t object = text.find("): ");
  if (object != std::string::npos)
  {
    text = text.substr(object + 3);
  }
  const std::size_t end = text.find('\n');
  return end == std::string::npos ? text : text.substr(0, end);
}

// Measures every case on the backends of `options` (the surface mapper's list for both
// mappers); writes stability.csv, stability.md and the images; returns the Markdown section.
inline std::string MeasureStability(const Options& options)
{
  const std::vector<splatstability::Case> cases = splatstability::Cases();
  const int frames = std::max(2, options.Frames + 1);
  std::ostringstream csv, table;
  csv << "group,case,mapper,backend,survived,nan_inf,skipped,skipped_why,error,message,"
         "ms_per_frame,baseline,baseline_ms_per_frame,cost_ratio,reference,rmse,covered,failed\n";
  table << "| group | case | mapper | backend | NaN/Inf | skipped (why) | error / warning | "
           "ms/frame | baseline ms | ratio | RMSE vs reference | checks |\n"
        << "|---|---|---|---|---:|---|---|---:|---:|---:|---:|---|\n";
  int failedCases = 0, rows = 0;
  for (const std::string& backendName : options.Backends)
  {
    const int backend =
      backendName == "opengl" ? vtkSplatBackend::OPENGL : vtkSplatBackend::CPU;
    // The baselines' results, by mapper, name and camera handling.
    std::map<std::string, splatstability::Result> baselines;
    auto baseline = [&](const splatstability::Case& c, const std::string& name)
    {
      const splatstability::Case* base = FindCase(cases, name, c.Kind);
      const bool reset = c.Make().ResetCamera;
      const std::string key = std::to_string(c.Kind) + name + (reset ? "-reset" : "");
      auto found = baselines.find(key);
      if (found == baselines.end() && base)
      {
        splatstability::Case adjusted = *base;
        adjusted.Make = [base, reset]
        {
          splatstability::Scene s = base->Make();
          s.ResetCamera = reset;
          return s;
        };
        found = baselines.emplace(key, splatstability::Run(adjusted, backend, frames)).first;
      }
      return found == baselines.end() ? nullptr : &found->second;
    };
    for (const splatstability::Case& c : cases)
    {
      std::cerr << "splat_report: stability, " << backendName << ", "
                << splatstability::MapperName(c.Kind) << " " << c.Group << "/" << c.Name
                << std::endl;
      const splatstability::Result r = splatstability::Run(c, backend, frames);
      const std::vector<std::string> failures = splatstability::Check(c, r);
      failedCases += failures.empty() ? 0 : 1;
      ++rows;
      const std::string baseName = BaselineOf(c);
      const splatstability::Result* base = baseline(c, baseName);
      const double baseMs = base ? base->Milliseconds : 0.0;
      const double ratio = base && baseMs > 0.0 ? r.Milliseconds / baseMs : 0.0;
      double rmse = -1.0;
      if (!c.Reference.empty() && base && base->RGB.size() == r.RGB.size())
      {
        rmse = splattest::RMSE(r.RGB, base->RGB);
      }
      const splatstability::Scene scene = c.Make();
      const std::string file = "stability-" + std::string(splatstability::MapperName(c.Kind)) +
        "-" + c.Name + "-" + backendName + ".png";
      WriteRGB(r.RGB, scene.Width, scene.Height, options.OutputDir + "/" + file);
      const std::string message = MessageText(r.Message);
      std::string checks;
      for (const std::string& failure : failures)
      {
        checks += (checks.empty() ? "" : "; ") + failure;
      }
      csv << c.Group << "," << c.Name << "," << splatstability::MapperName(c.Kind) << ","
          << backendName << "," << (r.Rendered ? 1 : 0) << "," << r.NonFinite << ","
          << r.Skipped << "," << CsvText(r.Why) << "," << (r.Error ? 1 : 0) << ","
          << CsvText(message) << "," << Fixed(r.Milliseconds, 2) << "," << baseName << ","
          << Fixed(baseMs, 2) << "," << Fixed(ratio, 2) << ","
          << (c.Reference.empty() ? "" : c.Reference) << ","
          << (rmse < 0.0 ? "" : Fixed(rmse, 5)) << "," << r.Covered << ","
          << CsvText(checks) << "\n";
      table << "| " << c.Group << " | " << c.Name << " | " << splatstability::MapperName(c.Kind)
            << " | " << backendName << " | " << r.NonFinite << " | " << r.Skipped << " ("
            << r.Why << ") | " << (r.Error ? "error: " : (r.Warning ? "warning: " : ""))
            << message << " | " << Fixed(r.Milliseconds, 1) << " | " << Fixed(baseMs, 1)
            << " | " << Fixed(ratio, 1) << (ratio > StabilityCostBound ? " (over)" : "")
            << " | " << (rmse < 0.0 ? "" : Fixed(rmse, 4)) << " | "
            << (checks.empty() ? "ok" : checks) << " |\n";
    }
  }
  const std::string csvPath = options.OutputDir + "/stability.csv";
  std::ofstream file(csvPath);
  file << csv.str();
  if (!file)
  {
    throw std::runtime_error("cannot write '" + csvPath + "'");
  }
  std::ostringstream md;
  md << "## stability\n\n"
     << "The stiff and extreme cases of `Testing/Cxx/SplatStabilityCases.h` (the ones "
     << "`TestSplatStability` asserts under CTest), " << rows << " rows over the backends "
     << "asked for, " << failedCases << " failing their checks. NaN/Inf counts the values of "
     << "the mapper's own float image (the CPU volume image, the OpenGL backends' color "
     << "textures read back, the CPU surface rasterizer's depths): it must be 0. Skipped: "
     << "points or kernels refused as invalid, with the mapper's counts of what else it left "
     << "out. ms/frame: the mean of " << frames - 1 << " frames after a first untimed one, "
     << "against the same mapper's scene without the extreme (its baseline: `sphere`, "
     << "`gaussians` or `blob`, or the case's reference); the bound is " << StabilityCostBound
     << "x, marked (over) beyond it (coincident points and the 1x4096 window draw more than "
     << "their baselines). RMSE: against the reference case's image where the case is the "
     << "same scene moved, scaled or mirrored (8-bit RGB in [0, 1]). `stability.csv` has the "
     << "figures, `stability-<mapper>-<case>-<backend>.png` the images.\n\n"
     << table.str() << "\n";
  std::ofstream mdFile(options.OutputDir + "/stability.md");
  mdFile << md.str();
  return md.str();
}
}

#endif
