// SPDX-License-Identifier: BSD-3-Clause
// splat_render's textured meshes: reading an OBJ file (texture coordinates "vt" kept), reading the
// texture image, acquiring the texture onto the surfels with vtkSurfelTextureAcquisition, and the
// demo's textured scene (a texture image the project generates, written as PNG, on a sphere
// written as OBJ and read back like a user's file).
#ifndef SplatTexturedMesh_h
#define SplatTexturedMesh_h

#include "SplatFileReaders.h"
#include "vtkSurfelTextureAcquisition.h"

#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageReader2Factory.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkOBJWriter.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTexturedSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

namespace splatexample
{
// The --acquisition names of vtkSurfelTextureAcquisition's modes.
inline const std::map<std::string, int>& AcquisitionModes()
{
  static const std::map<std::string, int> modes = {
    { "point", vtkSurfelTextureAcquisition::POINT_SAMPLING },
    { "ewa", vtkSurfelTextureAcquisition::VIEW_INDEPENDENT_EWA },
    { "optimal", vtkSurfelTextureAcquisition::OPTIMAL },
  };
  return modes;
}

// A mesh by its extension, .obj (vtkOBJReader: texture coordinates as the active TCoords) added
// to ReadPolyData's formats.
inline vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path)
{
  if (!HasExtension(path, ".obj"))
  {
    return ReadPolyData(path);
  }
  RequireFile(path);
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(path.c_str());
  UpdateReader(reader, path);
  vtkSmartPointer<vtkPolyData> data = reader->GetOutput();
  if (data->GetNumberOfPoints() == 0)
  {
    throw std::runtime_error("'" + path + "' holds no points");
  }
  return data;
}

// A texture image of any format VTK reads (PNG, JPEG, TIFF, BMP, PNM...).
inline vtkSmartPointer<vtkImageData> ReadTextureImage(const std::string& path)
{
  RequireFile(path);
  vtkSmartPointer<vtkImageReader2> reader;
  reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(path.c_str()));
  if (!reader)
  {
    throw std::runtime_error("'" + path + "': not an image format VTK reads (PNG, JPEG, TIFF, "
                                          "BMP, PNM)");
  }
  reader->SetFileName(path.c_str());
  UpdateReader(reader, path);
  vtkSmartPointer<vtkImageData> image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] < 1 || dims[1] < 1 || !image->GetPointData()->GetScalars())
  {
    throw std::runtime_error("'" + path + "' holds no pixels");
  }
  return image;
}

// The texture acquired onto `surfels` (vtkSurfelGenerator's output, with the mesh's texture
// coordinates): an RGB(A) array "TextureColors" made the active scalars. Prints what it did.
inline vtkSmartPointer<vtkPolyData> AcquireTexture(
  vtkPolyData* surfels, vtkImageData* texture, int mode)
{
  if (!surfels->GetPointData()->GetTCoords())
  {
    throw std::runtime_error(
      "--texture: the mesh has no texture coordinates (PLY u,v or s,t; OBJ vt)");
  }
  vtkNew<vtkSurfelTextureAcquisition> acquisition;
  acquisition->SetInputData(surfels);
  acquisition->SetTextureData(texture);
  acquisition->SetMode(mode);
  const auto start = std::chrono::steady_clock::now();
  acquisition->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vtkPolyData* output = acquisition->GetOutput();
  if (!output->GetPointData()->GetArray(acquisition->GetOutputArrayName()))
  {
    throw std::runtime_error("vtkSurfelTextureAcquisition failed (see the error above)");
  }
  const int* dims = texture->GetDimensions();
  const vtkIdType n = output->GetNumberOfPoints();
  std::cout << "  texture:       " << dims[0] << "x" << dims[1] << " acquired by "
            << vtkSurfelTextureAcquisition::GetModeAsString(mode) << " in " << std::fixed
            << std::setprecision(3) << seconds << " s (" << std::setprecision(2)
            << 1e6 * seconds / std::max<vtkIdType>(n, 1) << " us per surfel";
  if (mode == vtkSurfelTextureAcquisition::OPTIMAL)
  {
    std::cout << ", " << acquisition->GetNumberOfIterations() << " CG iterations";
  }
  std::cout << "; " << acquisition->GetNumberOfSkippedPoints() << " surfels skipped, "
            << acquisition->GetNumberOfDegenerateMaps() << " point sampled)" << std::endl;
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(output);
  return result;
}

// The demo's texture, generated: 512x256 RGB, a longitude-latitude map of colored bands (hue
// along the longitude), a fine checkerboard of 32x16 cells and thin dark meridians and parallels
// every 30 degrees, so that blur and aliasing both show.
inline vtkSmartPointer<vtkImageData> DemoTexture()
{
  constexpr int W = 512, H = 256;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(W, H, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* pixels = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int y = 0; y < H; ++y)
  {
    for (int x = 0; x < W; ++x)
    {
      const double hue = 6.0 * x / W;
      const double f = hue - std::floor(hue);
      const int sector = static_cast<int>(hue) % 6;
      const double ramp[6][3] = { { 1, f, 0 }, { 1 - f, 1, 0 }, { 0, 1, f }, { 0, 1 - f, 1 },
        { f, 0, 1 }, { 1, 0, 1 - f } };
      const bool check = ((x / 16) + (y / 16)) % 2 == 0;
      const bool line = (x % (W / 12)) < 2 || (y % (H / 6)) < 2;
      for (int c = 0; c < 3; ++c)
      {
        double v = 0.35 + 0.5 * ramp[sector][c];
        v *= check ? 1.0 : 0.55;
        if (line)
        {
          v = 0.08;
        }
        pixels[3 * (y * W + x) + c] = static_cast<unsigned char>(std::lround(255.0 * v));
      }
    }
  }
  return image;
}

// Writes the demo's texture (PNG) and a textured sphere (OBJ, with texture coordinates) into
// `folder`; returns the two paths.
inline std::pair<std::string, std::string> WriteTexturedDemo(const std::string& folder)
{
  const std::string png = folder + "/texture.png";
  const std::string obj = folder + "/textured_sphere.obj";
  vtkNew<vtkPNGWriter> image;
  image->SetFileName(png.c_str());
  image->SetInputData(DemoTexture());
  image->Write();
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetThetaResolution(360);
  sphere->SetPhiResolution(180);
  vtkNew<vtkOBJWriter> mesh;
  mesh->SetFileName(obj.c_str());
  mesh->SetInputConnection(sphere->GetOutputPort());
  mesh->Write();
  if (image->GetErrorCode() != 0 || mesh->GetErrorCode() != 0)
  {
    throw std::runtime_error("cannot write the textured demo scene into '" + folder + "'");
  }
  return { png, obj };
}
}

#endif
