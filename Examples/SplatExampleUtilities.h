// SPDX-License-Identifier: BSD-3-Clause
// Data, window, image and timing helpers shared by the example programs.
#ifndef SplatExampleUtilities_h
#define SplatExampleUtilities_h

#include "vtkErrorCode.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace splatexample
{
/// bunny.ply in SPLAT_DATA_DIR, or in ../shared/data next to the source tree.
inline std::string BunnyFile()
{
  std::string folder;
  if (!vtksys::SystemTools::GetEnv("SPLAT_DATA_DIR", folder) || folder.empty())
  {
    folder = vtksys::SystemTools::CollapseFullPath(SPLAT_SOURCE_DIR "/../shared/data");
  }
  return folder + "/bunny.ply";
}

/// Creates the folder and its parents; an empty name is the current folder.
inline void MakeFolder(const std::string& folder)
{
  if (!folder.empty() && !vtksys::SystemTools::MakeDirectory(folder))
  {
    throw std::runtime_error("cannot create the folder '" + folder + "'");
  }
}

/// An offscreen window without multisampling, holding one renderer. The programs draw all their
/// scenes in one window: each window opens its own X display connection, and an X server (Xvfb)
/// that resets when its last client disconnects can refuse the next window's connection.
inline vtkSmartPointer<vtkRenderWindow> MakeOffscreenWindow()
{
  vtkNew<vtkRenderer> renderer;
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  return window;
}

/// The window's OpenGL renderer string (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"), "unknown"
/// when the window does not say; the window must have been rendered.
inline std::string OpenGLRenderer(vtkRenderWindow* window)
{
  const std::string report = window->ReportCapabilities();
  const std::string key = "OpenGL renderer string:";
  const auto at = report.find(key);
  if (at == std::string::npos)
  {
    return "unknown";
  }
  const auto end = report.find('\n', at);
  std::string name = report.substr(at + key.size(), end - at - key.size());
  name.erase(0, name.find_first_not_of(" \t"));
  return name;
}

/// Renders the window and writes its RGB image as a PNG.
inline void WritePNG(vtkRenderWindow* window, const std::string& path)
{
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(window);
  image->SetInputBufferTypeToRGB();
  image->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != vtkErrorCode::NoError)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}

/// The median; 0 for no values.
inline double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n == 0 ? 0.0 : n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// vtkPointGaussianMapper drawing opaque disks of the surfels' "Radius": the like-for-like peer
/// of vtkSurfaceSplatMapper. Its default Gaussian shader with emissive off blends unsorted
/// translucent blobs whose depth writes hide one another: mostly background shows through.
inline vtkSmartPointer<vtkPointGaussianMapper> PointGaussianDisks(vtkPolyData* surfels)
{
  auto mapper = vtkSmartPointer<vtkPointGaussianMapper>::New();
  mapper->SetInputData(surfels);
  mapper->SetScaleArray("Radius");
  mapper->SetScaleFactor(1.0);
  mapper->EmissiveOff();
  // Discards the fragments outside the disk of radius 1 in splat units.
  mapper->SetSplatShaderCode("//VTK::Color::Impl\n"
                             "float dist2 = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);\n"
                             "if (dist2 > 1.0) { discard; }\n");
  // The disk has radius 1 in splat units: a larger triangle would only shade discarded fragments.
  mapper->SetTriangleScale(1.0);
  return mapper;
}
}

#endif
