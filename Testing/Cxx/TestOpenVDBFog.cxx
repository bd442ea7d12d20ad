// SPDX-License-Identifier: BSD-3-Clause
// Fog grids through vtkOpenVDBReader and vtkVolumeSplatMapper:
// - a known extinction field on a rotated, non-uniformly scaled grid renders like the same
//   field given to the mapper as vtkImageData with the grid's direction matrix and spacing
//   (MAX_FIELD_RMSE); without the reader's SampleVolume array (kernels peaking at the
//   extinction instead of reconstructing it) it does not (MIN_PEAK_RMSE);
// - its kernels carry their voxel lattice (vtkOpenVDBReader's VoxelIndex and IndexToWorld), so
//   the mapper draws them through the sheets, as image data; without the lattice (the
//   per-kernel path) the image agrees within MAX_LATTICE_RMSE, and shaded (normals from the
//   sparse grid's neighbors) it agrees with the shaded image data as closely;
// - kernels whose VoxelIndex box is far too large for sheet tables take the per-kernel path;
// - a grid with active tiles renders like its voxelized copy (MAX_TILE_RMSE) with at most
//   MAX_TILE_KERNEL_RATIO of its kernels for TileSubdivision 2, and exactly like it with the
//   default 8 (leaf-sized tiles become their voxels);
// - the first view of a smoke plume (splat_render's: Examples/SplatVdbScenes.h's FogProperty,
//   the camera reset on the kernels) shows it: at least MIN_FOG_COVERAGE of the image, at most
//   MAX_FOG_OPAQUE of that nearly opaque, a core of at least MIN_FOG_PEAK.
#include "SplatTestUtilities.h"
#include "SplatVdbScenes.h"
#include "SplatVolumeTestUtilities.h"
#include "vtkOpenVDBReader.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkCamera.h"
#include "vtkMatrix3x3.h"
#include "vtkPNGWriter.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cstdio>

namespace
{
int failures = 0;
void Check(bool ok, const char* what, double measured)
{
  std::printf("%s: %g\n", what, measured);
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s (%g)\n", what, measured);
    ++failures;
  }
}

const double Color[3] = { 1.0, 0.8, 0.5 };
const double MaxExtinction = 4.0; // per world unit
const double UnitDistance = 0.1;

/// Rotated about two axes, scaled 0.05, 0.035, 0.07 along the index axes, translated.
openvdb::math::Transform::Ptr Transform()
{
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  m.preScale(openvdb::Vec3d(0.05, 0.035, 0.07));
  m.postRotate(openvdb::math::Z_AXIS, 0.6);
  m.postRotate(openvdb::math::X_AXIS, -0.4);
  m.postTranslate(openvdb::Vec3d(0.3, -0.2, 0.1));
  return openvdb::math::Transform::createLinearTransform(m);
}

/// The field, in index coordinates: an anisotropic Gaussian with a ripple.
double Field(int i, int j, int k)
{
  const double x = (i - 10) / 6.0, y = (j - 2) / 8.0, z = (k - 5) / 5.0;
  const double r2 = x * x + y * y + z * z;
  return r2 < 4.0 ? MaxExtinction * std::exp(-r2) * (0.8 + 0.2 * std::cos(1.3 * i)) : 0.0;
}

std::string Write(const std::string& dir, const std::string& name, openvdb::GridBase::Ptr grid)
{
  const std::string path = dir + "/TestOpenVDBFog_" + name + ".vdb";
  openvdb::io::File file(path);
  file.write({ grid });
  file.close();
  return path;
}

std::string ImageDirectory; // -T: where the images are written for a look

/// Renders `mapper`'s input at 256^2 from a fixed oblique camera direction, looking at
/// `center` from `distance` times 3 world units.
std::vector<double> Render(vtkVolumeSplatMapper* mapper, const openvdb::Vec3d& center,
  double distance, const std::string& name, bool shaded = false)
{
  auto window = splattest::MakeRenderWindow(256, 256);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  renderer->SetBackground(0.0, 0.0, 0.0);
  auto property = splattest::ExtinctionProperty(MaxExtinction, UnitDistance, Color);
  property->SetShade(shaded);
  splattest::AddVolume(renderer, mapper, property);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(center[0], center[1], center[2]);
  camera->SetPosition(center[0] + 1.6 * distance, center[1] + 1.1 * distance,
    center[2] + 2.4 * distance);
  camera->SetViewUp(0.0, 1.0, 0.0);
  renderer->ResetCameraClippingRange(-20, 20, -20, 20, -20, 20);
  window->Render();
  auto image = splattest::Capture(window);
  if (!ImageDirectory.empty())
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName((ImageDirectory + "/TestOpenVDBFog_" + name + ".png").c_str());
    writer->SetInputData(image);
    writer->Write();
  }
  return splattest::ToRGB(image);
}

/// How RenderFile draws the reader's output.
struct Options
{
  int TileSubdivision = 8;
  bool SampleVolume = true; // off: the SampleVolume array removed
  bool Lattice = true;      // off: the VoxelIndex array removed
  bool Scattered = false;   // on: one kernel's VoxelIndex moved a million voxels away
  bool Shaded = false;
  vtkIdType* Kernels = nullptr; // the reader's kernels
  bool* SheetsUsed = nullptr;   // whether the frame went through the sheets
};

std::vector<double> RenderFile(const std::string& path, const openvdb::Vec3d& center,
  double distance, const std::string& name, const Options& options = Options())
{
  vtkNew<vtkOpenVDBReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetTileSubdivision(options.TileSubdivision);
  reader->Update();
  vtkNew<vtkPolyData> data;
  data->ShallowCopy(reader->GetOutput());
  if (!options.SampleVolume)
  {
    data->GetPointData()->RemoveArray("SampleVolume");
  }
  if (!options.Lattice)
  {
    data->GetPointData()->RemoveArray("VoxelIndex");
  }
  if (options.Scattered)
  {
    vtkSmartPointer<vtkDataArray> indices;
    indices.TakeReference(data->GetPointData()->GetArray("VoxelIndex")->NewInstance());
    indices->DeepCopy(data->GetPointData()->GetArray("VoxelIndex"));
    indices->SetComponent(0, 1, indices->GetComponent(0, 1) + 1e6);
    indices->SetComponent(0, 2, indices->GetComponent(0, 2) - 1e6);
    data->GetPointData()->AddArray(indices);
  }
  if (options.Kernels)
  {
    *options.Kernels = data->GetNumberOfPoints();
  }
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetInputData(data);
  std::vector<double> rgb = Render(mapper, center, distance, name, options.Shaded);
  if (options.SheetsUsed)
  {
    *options.SheetsUsed = mapper->GetSheetsUsed();
  }
  return rgb;
}
}

int main(int argc, char* argv[])
{
  openvdb::initialize();
  ImageDirectory = splattest::Argument(argc, argv, "-T");
  const std::string temp = ImageDirectory.empty() ? "." : ImageDirectory;

  // The field as a sparse fog grid: voxels where it is not zero.
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(Transform());
  const int lo[3] = { -4, -16, -6 }, hi[3] = { 24, 20, 16 };
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
        if (Field(i, j, k) > 0.0)
          grid->tree().setValue(openvdb::Coord(i, j, k), static_cast<float>(Field(i, j, k)));
  const openvdb::Vec3d center = grid->transform().indexToWorld(openvdb::Vec3d(10, 2, 5));
  const std::string fogPath = Write(temp, "field", grid);

  // The same field as image data: the grid's index axes as direction matrix and spacing.
  const openvdb::math::MapBase& map = *grid->transform().baseMap();
  vtkNew<vtkImageData> image;
  image->SetExtent(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
  vtkNew<vtkMatrix3x3> direction;
  double spacing[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    openvdb::Vec3d unit(0.0);
    unit[axis] = 1.0;
    const openvdb::Vec3d column = map.applyJacobian(unit);
    spacing[axis] = column.length();
    for (int row = 0; row < 3; ++row)
    {
      direction->SetElement(row, axis, column[row] / spacing[axis]);
    }
  }
  const openvdb::Vec3d origin = map.applyMap(openvdb::Vec3d(0.0));
  image->SetSpacing(spacing);
  image->SetOrigin(origin[0], origin[1], origin[2]);
  image->SetDirectionMatrix(direction);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfTuples(image->GetNumberOfPoints());
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
      {
        int ijk[3] = { i, j, k };
        scalars->SetValue(image->ComputePointId(ijk), static_cast<float>(Field(i, j, k)));
      }
  image->GetPointData()->SetScalars(scalars);
  vtkNew<vtkVolumeSplatMapper> imageMapper;
  imageMapper->SetInputData(image);
  const std::vector<double> reference = Render(imageMapper, center, 1.0, "image_data");

  vtkIdType kernels = 0;
  bool sheets = false;
  Options lattice;
  lattice.Kernels = &kernels;
  lattice.SheetsUsed = &sheets;
  const std::vector<double> fromGrid = RenderFile(fogPath, center, 1.0, "grid", lattice);
  Check(sheets, "the grid's lattice drawn through the sheets", sheets);
  Check(kernels == static_cast<vtkIdType>(grid->activeVoxelCount()), "kernels = active voxels",
    static_cast<double>(kernels));
  double energy = 0.0;
  for (double v : reference)
  {
    energy += v * v;
  }
  const double rms = std::sqrt(energy / reference.size());
  Check(rms > 0.1, "reference image RMS (not blank)", rms);
  const double fieldRMSE = splattest::RMSE(fromGrid, reference);
  Check(fieldRMSE <= MAX_FIELD_RMSE, "grid vs image data RMSE", fieldRMSE);
  Options peak;
  peak.SampleVolume = peak.Lattice = false;
  const double peakRMSE =
    splattest::RMSE(RenderFile(fogPath, center, 1.0, "peak", peak), reference);
  Check(peakRMSE >= MIN_PEAK_RMSE, "without SampleVolume, RMSE", peakRMSE);

  // The lattice against every kernel splatted on its own.
  Options perKernel;
  perKernel.Lattice = false;
  perKernel.SheetsUsed = &sheets;
  const std::vector<double> kernelImage =
    RenderFile(fogPath, center, 1.0, "per_kernel", perKernel);
  Check(!sheets, "without VoxelIndex, the per-kernel path", sheets);
  // Indices whose box would need 10^12 lines of sheet tables: the per-kernel path, unchanged.
  Options scattered;
  scattered.Scattered = true;
  scattered.SheetsUsed = &sheets;
  const double scatteredRMSE = splattest::RMSE(
    RenderFile(fogPath, center, 1.0, "scattered", scattered), kernelImage);
  Check(!sheets && scatteredRMSE <= 1e-6,
    "VoxelIndex scattered a million voxels apart: per-kernel path, RMSE", scatteredRMSE);
  const double latticeRMSE = splattest::RMSE(fromGrid, kernelImage);
  Check(latticeRMSE <= MAX_LATTICE_RMSE, "lattice vs per-kernel RMSE", latticeRMSE);
  // Shaded: normals from the sparse grid's neighbors, against those of the image data.
  Options shaded;
  shaded.Shaded = true;
  const double shadedRMSE =
    splattest::RMSE(RenderFile(fogPath, center, 1.0, "grid_shaded", shaded),
      Render(imageMapper, center, 1.0, "image_data_shaded", true));
  Check(shadedRMSE <= MAX_LATTICE_RMSE, "shaded lattice vs image data RMSE", shadedRMSE);

  // A box of constant extinction with leaf-sized tiles inside, and its voxelized copy.
  auto tiled = openvdb::FloatGrid::create(0.0f);
  tiled->setName("density");
  tiled->setTransform(Transform());
  // 64^3 voxels from -3: 7^3 leaf-sized tiles and the voxels of the unaligned faces.
  tiled->fill(openvdb::CoordBBox(-3, -3, -3, 60, 60, 60), 0.1f * MaxExtinction, true);
  auto voxelized = tiled->deepCopy();
  voxelized->tree().voxelizeActiveTiles();
  const openvdb::Vec3d boxCenter =
    tiled->transform().indexToWorld(openvdb::Vec3d(28.5, 28.5, 28.5));
  vtkIdType voxelKernels = 0;
  Options voxelOptions;
  voxelOptions.Kernels = &voxelKernels;
  const std::vector<double> voxels =
    RenderFile(Write(temp, "voxelized", voxelized), boxCenter, 4.0, "voxelized", voxelOptions);
  const std::string tiledPath = Write(temp, "tiled", tiled);
  for (int k : { 1, 2, 4, 8 })
  {
    vtkIdType tileKernels = 0;
    Options tileOptions;
    tileOptions.TileSubdivision = k;
    tileOptions.Kernels = &tileKernels;
    const double rmse = splattest::RMSE(
      RenderFile(tiledPath, boxCenter, 4.0, "tiled" + std::to_string(k), tileOptions), voxels);
    std::printf("TileSubdivision %d: %lld kernels (voxelized %lld), RMSE %g\n", k,
      static_cast<long long>(tileKernels), static_cast<long long>(voxelKernels), rmse);
    if (k == 2)
    {
      Check(rmse <= MAX_TILE_RMSE, "tiled vs voxelized RMSE", rmse);
      const double ratio = static_cast<double>(tileKernels) / voxelKernels;
      Check(ratio <= MAX_TILE_KERNEL_RATIO, "tiled / voxelized kernels", ratio);
    }
    if (k == 8)
    {
      Check(tileKernels == voxelKernels && rmse == 0.0, "TileSubdivision 8 vs voxelized RMSE",
        rmse);
    }
  }

  // The first view of a fog: white emission on black, so a pixel's value is its opacity.
  {
    vtkNew<vtkOpenVDBReader> reader;
    const std::string smokePath = temp + "/TestOpenVDBFog_smoke.vdb";
    splatexample::WriteSmokeVdb(smokePath, 40000);
    reader->SetFileName(smokePath.c_str());
    reader->Update();
    vtkNew<vtkVolumeSplatMapper> mapper;
    mapper->SetInputConnection(reader->GetOutputPort());
    auto window = splattest::MakeRenderWindow(256, 256);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    renderer->SetBackground(0.0, 0.0, 0.0);
    splattest::AddVolume(renderer, mapper, splatexample::FogProperty(reader->GetOutput()));
    renderer->ResetCamera();
    window->Render();
    auto image = splattest::Capture(window);
    if (!ImageDirectory.empty())
    {
      vtkNew<vtkPNGWriter> writer;
      writer->SetFileName((ImageDirectory + "/TestOpenVDBFog_smoke.png").c_str());
      writer->SetInputData(image);
      writer->Write();
    }
    const std::vector<double> rgb = splattest::ToRGB(image);
    std::size_t covered = 0, opaque = 0;
    double peak = 0.0;
    for (std::size_t p = 0; p < rgb.size(); p += 3)
    {
      const double value = rgb[p + 1];
      covered += value > 0.02;
      opaque += value > 0.97;
      peak = std::max(peak, value);
    }
    const double coverage = static_cast<double>(covered) / (rgb.size() / 3);
    Check(coverage >= MIN_FOG_COVERAGE, "smoke's first view: image covered", coverage);
    const double opaqueShare = covered ? static_cast<double>(opaque) / covered : 1.0;
    Check(opaqueShare <= MAX_FOG_OPAQUE, "smoke's first view: covered pixels nearly opaque",
      opaqueShare);
    Check(peak >= MIN_FOG_PEAK, "smoke's first view: densest pixel", peak);
  }
  return failures == 0 ? 0 : 1;
}
