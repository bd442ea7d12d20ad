// SPDX-License-Identifier: BSD-3-Clause
// A cloud as an OpenVDB fog volume, for the demo, the benchmark and the report: a cumulus of a
// few overlapping spheres (tools::createLevelSetSphere, tools::csgUnion) turned into fog by
// tools::sdfToFogVolume (density 1 inside, a ramp across a soft shell, the deep interior as
// active tiles), its shell modulated by VTK's Perlin noise, on a rotated and non-uniformly
// scaled grid. WriteCloudVdb writes it to a .vdb file (read it with vtkOpenVDBReader) and returns
// transfer functions and a camera for it. Also a plume of smoke (WriteSmokeVdb), and the
// transfer functions of a fog's first view (FogProperty).
#ifndef SplatVdbScenes_h
#define SplatVdbScenes_h

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPerlinNoise.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkVolumeProperty.h"

#include "SplatFogOpacity.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace splatexample
{
struct VdbScene
{
  vtkIdType ActiveVoxels = 0; ///< voxels and tile voxels of the fog
  vtkIdType LeafVoxels = 0;   ///< of which stored as voxels
  vtkIdType Tiles = 0;
  vtkSmartPointer<vtkVolumeProperty> Property;
  double FocalPoint[3] = { 0.0, 0.0, 0.0 };
  double Position[3] = { 0.0, 0.0, 1.0 };
  double ViewUp[3] = { 0.0, 1.0, 0.0 };

  void PlaceCamera(vtkCamera* camera) const
  {
    camera->SetFocalPoint(this->FocalPoint);
    camera->SetPosition(this->Position);
    camera->SetViewUp(this->ViewUp);
  }
};

namespace detail
{
/// The cloud of spheres of base radius r voxels (index space): its fog grid, grid "density".
inline openvdb::FloatGrid::Ptr CloudFog(double r)
{
  // Centers and radii in units of r: a wide base and a few rising puffs.
  const double puffs[6][4] = { { 0.0, 0.0, 0.0, 1.0 }, { 1.1, -0.2, 0.3, 0.75 },
    { -1.0, -0.1, -0.2, 0.8 }, { 0.3, 0.8, 0.1, 0.7 }, { -0.4, 0.6, 0.4, 0.55 },
    { 0.5, -0.1, -0.9, 0.6 } };
  const float shell = static_cast<float>(std::max(3.0, 0.25 * r)); // soft edge, in voxels
  openvdb::FloatGrid::Ptr cloud;
  for (const auto& p : puffs)
  {
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      static_cast<float>(p[3] * r), openvdb::Vec3f(p[0] * r, p[1] * r, p[2] * r), 1.0f, shell);
    if (cloud)
    {
      openvdb::tools::csgUnion(*cloud, *sphere);
    }
    else
    {
      cloud = sphere;
    }
  }
  openvdb::tools::sdfToFogVolume(*cloud, shell);
  // Noise on the soft shell only: the deep interior stays 1, like the tiles it touches.
  vtkNew<vtkPerlinNoise> noise;
  noise->SetFrequency(3.0 / r, 3.0 / r, 3.0 / r);
  for (auto voxel = cloud->tree().beginLeaf(); voxel; ++voxel)
  {
    for (auto v = voxel->beginValueOn(); v; ++v)
    {
      if (*v < 1.0f)
      {
        const openvdb::Vec3d x = v.getCoord().asVec3d();
        const double n = noise->EvaluateFunction(x[0], x[1], x[2]); // in [-1, 1]
        v.setValue(static_cast<float>(*v * std::min(1.0, std::max(0.0, 0.7 + 0.6 * n))));
      }
    }
  }
  cloud->setName("density");
  return cloud;
}
}

/**
 * Writes a plume of smoke of about `activeVoxels` active voxels to `path` as the fog grid
 * "density" (uniform voxels of 0.01, the class and values of a simulation's export): a column
 * rising along y from a source at the origin, bent by a wind along x, widening with height,
 * its density falling off across the column and with height and torn by Perlin noise, and a wide
 * faint fringe (densities down to 1e-3 of the core's) that makes most of the active voxels,
 * as in real exports. Returns the active voxel count.
 */
inline vtkIdType WriteSmokeVdb(const std::string& path, vtkIdType activeVoxels)
{
  openvdb::initialize();
  // The plume's bounding box is about 1.1 w x 2.5 w x 0.7 w voxels for a base width w, about
  // half of it active: pick w for the count.
  const int w = std::max(8, static_cast<int>(std::cbrt(activeVoxels / 0.95)));
  const int height = static_cast<int>(2.5 * w);
  vtkNew<vtkPerlinNoise> noise;
  noise->SetFrequency(6.0 / w, 6.0 / w, 6.0 / w);
  auto grid = openvdb::FloatGrid::create(0.0f);
  auto accessor = grid->getAccessor();
  for (int j = 0; j < height; ++j)
  {
    const double h = static_cast<double>(j) / height;       // 0 at the source, 1 at the top
    const double radius = w * (0.06 + 0.22 * h);            // the column's 1/e radius
    const double axis = 0.45 * w * h * h;                   // bent downwind
    const double strength = std::exp(-2.0 * h) * (1.0 - h); // thins as it rises
    const int reach = static_cast<int>(std::ceil(2.6 * radius));
    for (int k = -reach; k <= reach; ++k)
    {
      for (int i = static_cast<int>(axis) - reach; i <= static_cast<int>(axis) + reach; ++i)
      {
        const double r2 = ((i - axis) * (i - axis) + k * k) / (radius * radius);
        const double n = noise->EvaluateFunction(i, j, k); // in [-1, 1]
        const double d = strength * std::exp(-r2) * std::min(1.0, std::max(0.0, 0.6 + 0.8 * n));
        if (d > 1e-3)
        {
          accessor.setValue(openvdb::Coord(i, j, k), static_cast<float>(d));
        }
      }
    }
  }
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.01));
  openvdb::io::File file(path);
  file.write({ grid });
  file.close();
  return static_cast<vtkIdType>(grid->activeVoxelCount());
}

/**
 * The first view of a fog grid read by vtkOpenVDBReader: white emission and the opacity of
 * SplatFogOpacity.h, from the reader's "DensityStatistics" (clear without them).
 */
inline vtkSmartPointer<vtkVolumeProperty> FogProperty(vtkDataSet* kernels)
{
  splat::FogStatistics statistics;
  if (vtkDataArray* array = kernels->GetFieldData()->GetArray("DensityStatistics"))
  {
    if (array->GetNumberOfComponents() == 3 && array->GetNumberOfTuples() == 1)
    {
      statistics = { array->GetComponent(0, 0), array->GetComponent(0, 1),
        array->GetComponent(0, 2) };
    }
  }
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  property->SetColor(color);
  vtkNew<vtkPiecewiseFunction> opacity;
  splat::FogOpacity fog;
  if (splat::MakeFogOpacity(statistics, fog))
  {
    for (int i = 1; i < splat::FogOpacity::Samples; ++i)
    {
      opacity->AddPoint(fog.Density[i], fog.Alpha[i]);
    }
    property->SetScalarOpacityUnitDistance(fog.UnitDistance);
  }
  opacity->AddPoint(0.0, 0.0);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  return property;
}

/**
 * Writes a cloud of about `activeVoxels` active voxels (tiles included) to `path` as the fog
 * grid "density" and returns its transfer functions and camera. The grid is rotated and scaled
 * non-uniformly (voxels 1 x 0.8 x 1.2 world units / 100 of the cloud's width, roughly).
 */
inline VdbScene WriteCloudVdb(const std::string& path, vtkIdType activeVoxels)
{
  openvdb::initialize();
  // The spheres' union holds about 5.2 r^3 voxels: pick r for the count, then correct once.
  double r = std::cbrt(static_cast<double>(activeVoxels) / 5.2);
  openvdb::FloatGrid::Ptr cloud = detail::CloudFog(r);
  r *= std::cbrt(static_cast<double>(activeVoxels) / std::max<openvdb::Index64>(
                   cloud->activeVoxelCount(), 1));
  cloud = detail::CloudFog(r);

  const double h = 1.0 / r; // the base puff has radius 1 world unit
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  m.preScale(openvdb::Vec3d(h, 0.8 * h, 1.2 * h));
  m.postRotate(openvdb::math::Y_AXIS, 0.5);
  m.postRotate(openvdb::math::X_AXIS, 0.2);
  cloud->setTransform(openvdb::math::Transform::createLinearTransform(m));
  cloud->setGridClass(openvdb::GRID_FOG_VOLUME);
  openvdb::io::File file(path);
  file.write({ cloud });
  file.close();

  VdbScene scene;
  scene.ActiveVoxels = static_cast<vtkIdType>(cloud->activeVoxelCount());
  scene.LeafVoxels = static_cast<vtkIdType>(cloud->tree().activeLeafVoxelCount());
  scene.Tiles = static_cast<vtkIdType>(cloud->tree().activeTileCount());
  // White, slightly blue in the thin parts; opacity per 0.05 world units (the cloud is ~4 wide).
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.75, 0.82, 0.95);
  color->AddRGBPoint(1.0, 1.0, 1.0, 1.0);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.05, 0.0);
  opacity->AddPoint(1.0, 0.25);
  scene.Property = vtkSmartPointer<vtkVolumeProperty>::New();
  scene.Property->SetColor(color);
  scene.Property->SetScalarOpacity(opacity);
  scene.Property->SetScalarOpacityUnitDistance(0.05);
  scene.Property->SetInterpolationTypeToLinear();
  const openvdb::Vec3d center = cloud->transform().indexToWorld(openvdb::Vec3d(0.0, 0.2 * r, 0.0));
  for (int c = 0; c < 3; ++c)
  {
    scene.FocalPoint[c] = center[c];
  }
  scene.Position[0] = center[0] + 2.0;
  scene.Position[1] = center[1] + 1.5;
  scene.Position[2] = center[2] + 7.0;
  return scene;
}
}

#endif
