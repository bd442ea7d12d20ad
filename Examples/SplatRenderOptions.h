// SPDX-License-Identifier: BSD-3-Clause
// splat_render's command line: its usage text, its options and their parsing.
#ifndef SplatRenderOptions_h
#define SplatRenderOptions_h

#include "SplatCommandLine.h"
#include "SplatFileReaders.h"
#include "SplatTexturedMesh.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkVolumeSplatMapper.h"

#include <vtksys/SystemTools.hxx>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>

namespace splatrender
{
using splatexample::HasExtension;
using splatexample::UsageError;
using Triple = std::array<double, 3>;

const char* const Usage = R"(Usage: splat_render [OPTIONS] [FILE]

Renders FILE (.ply, .vtp, .xyz, .off or .obj; a mesh or a point cloud) as EWA surface splats
(vtkSurfelGenerator + vtkSurfaceSplatMapper) into a PNG and prints the backend, the number of
splats, the time per frame and the splats per second. A volume FILE (.nii, .nii.gz, .vti, .mhd
or .mha: image data with point scalars) is drawn by vtkVolumeSplatMapper, one Gaussian kernel
per voxel, through a transfer function over the scalar range (transparent below a fifth of
it, then more opaque and from dark red to white towards the top), shaded unless --shade off.
A 3D Gaussian Splatting capture (a .ply whose vertices have the 3DGS properties f_dc_*,
opacity, scale_* and rot_* or PlayCanvas's compressed ones, .splat, .spz, .sog or the meta.json
of its folder, .ksplat, or a .glb or .gltf with KHR_gaussian_splatting) is drawn by vtkVolumeSplatMapper as its Gaussians with
their own colors and opacities; other .ply files are meshes or point clouds. An OpenVDB file
(.vdb) is listed grid by grid and its grid (--grid, default the first one vtkOpenVDBReader
supports) drawn by what it holds: fog volumes and other scalar or vector grids as one Gaussian
kernel per active voxel (vtkVolumeSplatMapper, the transfer function of volume files over the
values or the magnitude), level sets as surfels on the surface and point grids as a point cloud
(vtkSurfaceSplatMapper). splat_render says which it chose.
Without FILE, renders the demo scenes (the Stanford bunny, or the CGAL armadillo when the bunny
is absent, a colored sphere, a sphere with a texture the project generates, written as
texture.png and textured_sphere.obj next to the images and read back, the MRI head of Debian's mricron-data when present, and a cloud
written as an OpenVDB fog volume by the project, cloud.vdb, next to the images).

.xyz files hold one point per line: "x y z" or "x y z nx ny nz"; lines starting with # are
skipped. Points without normals get normals from their neighbors.

Options (a value follows as --name VALUE or --name=VALUE):
  --output FILE.png       image of FILE to write (default DIR/<name of FILE>.png)
  --output-dir DIR        folder for the images (default output; output/demo for the demos)
  --size WxH              image size in pixels (default 800x800)
  --azimuth DEG           rotate the camera about the view up vector (default 0)
  --elevation DEG         rotate the camera up over the focal point (default 0)
  --zoom F                zoom factor, > 1 moves closer (default 1)
  --view-up x,y,z         camera view up vector (default 0,1,0)
  --view-direction x,y,z  direction the camera looks along (default 0,0,-1)
  --backend auto|cpu|opengl
                          rendering backend (default auto: OpenGL on a hardware GPU, the CPU
                          under a software OpenGL renderer such as Mesa's llvmpipe)
  --filter ewa|circular|unfiltered|approximate
                          screen-space filter (default ewa, exact EWA; approximate is the
                          OpenGL backend's cheaper filter, the CPU draws EWA for it)
  --radius-scale F        vtkSurfelGenerator RadiusScale: splat radius / point spacing (default 1)
  --cutoff F              Cutoff on the kernel exponent (default: the mapper's, automatic 0.5,
                          1 or 2 for surface splats, 4.5 for volumes)
  --ordering auto|blended|clipped|single-axis|depth-sorted
                          volumes: vtkVolumeSplatMapper's visibility ordering (default auto:
                          depth-sorted for captures, blended for density volumes)
  --footprint-filter auto|low-pass|dilation|antialiased
                          volumes: the screen filter of the footprints (default auto: the
                          0.3 px^2 dilation captures are trained with, EWA's 1 px^2 low-pass
                          for density volumes; antialiased: the dilation with the opacity
                          compensated, for captures seen far from their training views)
  --cameras FILE          captures: the training cameras (INRIA cameras.json; default the
                          cameras.json beside the capture or up to two folders up): the
                          view is camera --camera's, the size its aspect at most 800 pixels
                          wide unless --size is given
  --camera N              captures: the training camera to view from (default 0)
  --spz-frame stored|rub  .spz captures: take the values as stored (default: the .ply's frame,
                          as splat-transform writes them) or as the right-up-back frame of
                          the format's README, turned into the .ply's
                          (vtkGaussianSplatReader::SPZFromRUB)
  --shade on|off          volumes: light the kernels by the scalar gradient (default on)
  --grid NAME             .vdb files: the grid to draw (default the first one supported)
  --texture IMAGE         meshes with texture coordinates (PLY u,v or s,t; OBJ vt): acquire the
                          image (PNG, JPEG, TIFF, BMP, PNM) onto the surfels
                          (vtkSurfelTextureAcquisition) and draw its colors
  --acquisition point|ewa|optimal
                          how --texture is acquired: point sampling, view-independent EWA
                          prefilter (default) or the optimal least-squares fit
  --color r,g,b           splat color in [0,1], replaces the data's own colors
  --background r,g,b      background color in [0,1] (default 0.1,0.1,0.15; black for
                          captures, as they are trained)
  --frames N              frames timed after one warm-up frame (default 5)
  --help                  print this help

Environment: SPLAT_DATA_DIR, the folder holding bunny.ply for the demo scenes
(default: ../shared/data next to the source tree).
)";

struct Options
{
  std::string Input;
  std::optional<std::string> Output;
  std::optional<std::string> OutputDir;
  int Width = 800;
  int Height = 800;
  double Azimuth = 0.0;
  double Elevation = 0.0;
  double Zoom = 1.0;
  std::optional<Triple> ViewUp;
  std::optional<Triple> ViewDirection;
  double RadiusScale = 1.0;
  std::optional<double> Cutoff;
  int Ordering = vtkVolumeSplatMapper::AUTOMATIC;
  int FootprintFilter = vtkVolumeSplatMapper::AUTOMATIC_FILTER;
  std::string Cameras; // a capture's training cameras; empty: cameras.json beside it, if any
  int Camera = 0;
  bool SPZFromRUB = false;
  bool SizeGiven = false;
  bool Shade = true;
  std::string Grid; // of a .vdb file; empty: the reader's default
  int Backend = vtkSplatBackend::AUTO;
  int FilterMode = vtkSurfaceSplatMapper::EWA;
  std::optional<Triple> Color;
  std::string Texture; // image acquired onto the surfels; empty: none
  int Acquisition = vtkSurfelTextureAcquisition::VIEW_INDEPENDENT_EWA;
  std::optional<Triple> Background; // unset: splatexample's default, black for captures
  int Frames = 5;
};

inline double ParseNumber(const std::string& option, const std::string& text)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
  {
    throw UsageError(option + ": '" + text + "' is not a number");
  }
  return value;
}

inline double ParsePositive(const std::string& option, const std::string& text)
{
  const double value = ParseNumber(option, text);
  if (!(value > 0.0))
  {
    throw UsageError(option + ": expected a positive number, got '" + text + "'");
  }
  return value;
}

inline int ParseCount(const std::string& option, const std::string& text, int low, int high)
{
  const double value = ParseNumber(option, text);
  if (value != std::floor(value) || value < low || value > high)
  {
    throw UsageError(option + ": expected a whole number from " + std::to_string(low) + " to " +
      std::to_string(high) + ", got '" + text + "'");
  }
  return static_cast<int>(value);
}

inline Triple ParseTriple(const std::string& option, const std::string& text)
{
  std::vector<double> values;
  std::istringstream fields(text);
  std::string field;
  while (std::getline(fields, field, ','))
  {
    values.push_back(ParseNumber(option, field));
  }
  if (values.size() != 3)
  {
    throw UsageError(option + ": expected three comma-separated numbers, got '" + text + "'");
  }
  return { values[0], values[1], values[2] };
}

inline Triple ParseColor(const std::string& option, const std::string& text)
{
  const Triple color = ParseTriple(option, text);
  for (double c : color)
  {
    if (c < 0.0 || c > 1.0)
    {
      throw UsageError(option + ": color components must lie in [0,1], got '" + text + "'");
    }
  }
  return color;
}

inline Triple ParseDirection(const std::string& option, const std::string& text)
{
  Triple direction = ParseTriple(option, text);
  if (vtkMath::Normalize(direction.data()) == 0.0)
  {
    throw UsageError(option + ": the vector must not be zero");
  }
  return direction;
}

// The value of one of `choices`' names, case-insensitive.
inline int ParseChoice(
  const std::string& option, const std::string& text, const std::map<std::string, int>& choices)
{
  const auto choice = choices.find(vtksys::SystemTools::LowerCase(text));
  if (choice == choices.end())
  {
    std::string names;
    for (const auto& c : choices)
    {
      names += (names.empty() ? "" : ", ") + c.first;
    }
    throw UsageError(option + ": unknown '" + text + "' (choose from " + names + ")");
  }
  return choice->second;
}

// Long GNU-style options: "--name VALUE" or "--name=VALUE"; one optional input file.
inline Options ParseCommandLine(int argc, char* argv[])
{
  Options options;
  const std::map<std::string, splatexample::OptionHandler> handlers = {
    { "--output",
      [&](const std::string& name, const std::string& value)
      {
        if (!HasExtension(value, ".png"))
        {
          throw UsageError(
            name + ": the image is written as PNG, name it *.png (got '" + value + "')");
        }
        options.Output = value;
      } },
    { "--output-dir",
      [&](const std::string&, const std::string& value) { options.OutputDir = value; } },
    { "--size",
      [&](const std::string& name, const std::string& value)
      {
        const auto x = value.find('x');
        if (x == std::string::npos)
        {
          throw UsageError(name + ": expected WxH, e.g. 800x600, got '" + value + "'");
        }
        options.Width = ParseCount(name, value.substr(0, x), 1, 16384);
        options.Height = ParseCount(name, value.substr(x + 1), 1, 16384);
        options.SizeGiven = true;
      } },
    { "--azimuth",
      [&](const std::string& name, const std::string& value)
      { options.Azimuth = ParseNumber(name, value); } },
    { "--elevation",
      [&](const std::string& name, const std::string& value)
      { options.Elevation = ParseNumber(name, value); } },
    { "--zoom",
      [&](const std::string& name, const std::string& value)
      { options.Zoom = ParsePositive(name, value); } },
    { "--view-up",
      [&](const std::string& name, const std::string& value)
      { options.ViewUp = ParseDirection(name, value); } },
    { "--view-direction",
      [&](const std::string& name, const std::string& value)
      { options.ViewDirection = ParseDirection(name, value); } },
    { "--backend",
      [&](const std::string& name, const std::string& value)
      {
        options.Backend = ParseChoice(name, value,
          { { "auto", vtkSplatBackend::AUTO }, { "cpu", vtkSplatBackend::CPU },
            { "opengl", vtkSplatBackend::OPENGL } });
      } },
    { "--filter",
      [&](const std::string& name, const std::string& value)
      {
        options.FilterMode = ParseChoice(name, value,
          { { "ewa", vtkSurfaceSplatMapper::EWA }, { "circular", vtkSurfaceSplatMapper::CIRCULAR },
            { "unfiltered", vtkSurfaceSplatMapper::UNFILTERED },
            { "approximate", vtkSurfaceSplatMapper::APPROXIMATE } });
      } },
    { "--radius-scale",
      [&](const std::string& name, const std::string& value)
      { options.RadiusScale = ParsePositive(name, value); } },
    { "--cutoff",
      [&](const std::string& name, const std::string& value)
      { options.Cutoff = ParsePositive(name, value); } },
    { "--ordering",
      [&](const std::string& name, const std::string& value)
      {
        options.Ordering = ParseChoice(name, value,
          { { "auto", vtkVolumeSplatMapper::AUTOMATIC },
            { "blended", vtkVolumeSplatMapper::BLENDED },
            { "clipped", vtkVolumeSplatMapper::CLIPPED },
            { "single-axis", vtkVolumeSplatMapper::SINGLE_AXIS },
            { "depth-sorted", vtkVolumeSplatMapper::DEPTH_SORTED } });
      } },
    { "--footprint-filter",
      [&](const std::string& name, const std::string& value)
      {
        options.FootprintFilter = ParseChoice(name, value,
          { { "auto", vtkVolumeSplatMapper::AUTOMATIC_FILTER },
            { "low-pass", vtkVolumeSplatMapper::LOW_PASS_FILTER },
            { "dilation", vtkVolumeSplatMapper::DILATION_FILTER },
            { "antialiased", vtkVolumeSplatMapper::ANTIALIASED_FILTER } });
      } },
    { "--cameras", [&](const std::string&, const std::string& value) { options.Cameras = value; } },
    { "--camera",
      [&](const std::string& name, const std::string& value)
      { options.Camera = ParseCount(name, value, 0, 1 << 20); } },
    { "--spz-frame",
      [&](const std::string& name, const std::string& value)
      { options.SPZFromRUB = ParseChoice(name, value, { { "stored", 0 }, { "rub", 1 } }) != 0; } },
    { "--shade",
      [&](const std::string& name, const std::string& value)
      { options.Shade = ParseChoice(name, value, { { "on", 1 }, { "off", 0 } }) != 0; } },
    { "--grid", [&](const std::string&, const std::string& value) { options.Grid = value; } },
    { "--texture", [&](const std::string&, const std::string& value) { options.Texture = value; } },
    { "--acquisition",
      [&](const std::string& name, const std::string& value)
      { options.Acquisition = ParseChoice(name, value, splatexample::AcquisitionModes()); } },
    { "--color",
      [&](const std::string& name, const std::string& value)
      { options.Color = ParseColor(name, value); } },
    { "--background",
      [&](const std::string& name, const std::string& value)
      { options.Background = ParseColor(name, value); } },
    { "--frames",
      [&](const std::string& name, const std::string& value)
      { options.Frames = ParseCount(name, value, 1, 100000); } },
  };

  splatexample::ParseArguments(argc, argv, Usage, handlers, {},
    [&](const std::string& argument)
    {
      if (!options.Input.empty())
      {
        throw UsageError("one input file only, got '" + options.Input + "' and '" + argument + "'");
      }
      options.Input = argument;
    });

  if (options.Input.empty() && options.Output)
  {
    throw UsageError("--output names the image of an input file; the demo scenes (no input "
                     "file) go to --output-dir");
  }
  // The view up must not be parallel to the view direction; only the default one is replaced.
  const Triple direction = options.ViewDirection.value_or(Triple{ 0.0, 0.0, -1.0 });
  const Triple up = options.ViewUp.value_or(Triple{ 0.0, 1.0, 0.0 });
  Triple side;
  vtkMath::Cross(direction.data(), up.data(), side.data());
  if (vtkMath::Norm(side.data()) < 1e-6)
  {
    if (options.ViewUp)
    {
      throw UsageError("--view-up must not be parallel to the view direction");
    }
    options.ViewUp = Triple{ 0.0, 0.0, 1.0 };
  }
  return options;
}
}

#endif
