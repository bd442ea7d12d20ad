// SPDX-License-Identifier: BSD-3-Clause
// splat_write_test_vdb PATH: writes the OpenVDB file the plugin reader test opens (Debian has
// OpenVDB's C++ library but no Python module for pvpython to write one with). Its grids, in file
// order (TestPluginReaders.py checks these figures):
// - "mask": a bool grid of 3 voxels, a type the reader does not support, so that the default
//   grid is not the first one;
// - "density": a fog volume of voxel size 0.5, 4 x 3 x 2 = 24 voxels at (i, j, k), i < 4, j < 3,
//   k < 2, of value 1 + i + 2j + 4k, and one active 8^3 tile of value 2 at (64, 0, 0);
// - "surface": a level-set sphere of radius 1 and voxel size 0.1;
// - "cloud": a point data grid of 5 points with a float attribute "height" (the point's z).
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/PointIndexGrid.h>

#include <exception>
#include <iostream>
#include <vector>

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::cerr << "usage: splat_write_test_vdb PATH\n";
    return 2;
  }
  try
  {
    openvdb::initialize();

    auto mask = openvdb::BoolGrid::create(false);
    mask->setName("mask");
    for (int i = 0; i < 3; ++i)
    {
      mask->tree().setValue(openvdb::Coord(i, 0, 0), true);
    }

    auto density = openvdb::FloatGrid::create(0.0f);
    density->setName("density");
    density->setGridClass(openvdb::GRID_FOG_VOLUME);
    density->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
    auto accessor = density->getAccessor();
    for (int k = 0; k < 2; ++k)
    {
      for (int j = 0; j < 3; ++j)
      {
        for (int i = 0; i < 4; ++i)
        {
          accessor.setValue(openvdb::Coord(i, j, k), 1.0f + i + 2.0f * j + 4.0f * k);
        }
      }
    }
    density->tree().addTile(1, openvdb::Coord(64, 0, 0), 2.0f, true);

    auto surface = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      1.0f, openvdb::Vec3f(0.0f), 0.1f);
    surface->setName("surface");

    const std::vector<openvdb::Vec3R> positions = { { 0, 0, 0 }, { 1, 0, 0.5 }, { 0, 1, 1 },
      { -1, 0, 1.5 }, { 0, -1, 2 } };
    auto transform = openvdb::math::Transform::createLinearTransform(0.25);
    openvdb::points::PointAttributeVector<openvdb::Vec3R> wrapper(positions);
    auto index =
      openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(wrapper, *transform);
    auto cloud = openvdb::points::createPointDataGrid<openvdb::points::NullCodec,
      openvdb::points::PointDataGrid>(*index, wrapper, *transform);
    cloud->setName("cloud");
    std::vector<float> heights;
    for (const auto& p : positions)
    {
      heights.push_back(static_cast<float>(p.z()));
    }
    openvdb::points::appendAttribute<float>(cloud->tree(), "height");
    openvdb::points::PointAttributeVector<float> heightWrapper(heights);
    openvdb::points::populateAttribute(cloud->tree(), index->tree(), "height", heightWrapper);

    openvdb::io::File file(argv[1]);
    file.write({ mask, density, surface, cloud });
    file.close();
  }
  catch (const std::exception& e)
  {
    std::cerr << "splat_write_test_vdb: " << argv[1] << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
