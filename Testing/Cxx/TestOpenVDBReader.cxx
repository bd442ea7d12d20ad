// SPDX-License-Identifier: BSD-3-Clause
// vtkOpenVDBReader on grids written here with OpenVDB: the metadata listing, fog kernels (with an
// affine transform, tiles and half-float storage), vector and point data grids, the dense image,
// and the errors (not a VDB, truncated, empty, unsupported, missing grid).
#include "vtkOpenVDBReader.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
std::string TempPath(const std::string& name)
{
  return std::string(SPLAT_TEST_OUTPUT_DIR) + "/TestOpenVDBReader_" + name;
}

/// A rotated, non-uniformly scaled and translated index-to-world map.
openvdb::math::Transform::Ptr AffineTransform()
{
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  m.preScale(openvdb::Vec3d(0.1, 0.05, 0.2));
  m.postRotate(openvdb::math::Z_AXIS, 0.5);
  m.postRotate(openvdb::math::X_AXIS, -0.3);
  m.postTranslate(openvdb::Vec3d(1.0, -2.0, 0.5));
  return openvdb::math::Transform::createLinearTransform(m);
}

/// A fog grid of 10 x 12 x 14 voxels with value (i + 2 j + 3 k) / 100.
openvdb::FloatGrid::Ptr FogGrid()
{
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(AffineTransform());
  auto accessor = grid->getAccessor();
  for (int k = 0; k < 14; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 10; ++i)
        accessor.setValue(openvdb::Coord(i - 3, j, k + 5), (i + 2.0f * j + 3.0f * k) / 100.0f);
  return grid;
}

void Write(const std::string& path, const openvdb::GridPtrVec& grids, bool half = false)
{
  openvdb::io::File file(path);
  for (const auto& grid : grids)
  {
    grid->setSaveFloatAsHalf(half);
  }
  file.write(grids);
  file.close();
}

/// Records the reader's error messages.
struct Errors
{
  std::string Text;
  vtkNew<vtkCallbackCommand> Command;
  explicit Errors(vtkObject* object)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback([](vtkObject*, unsigned long, void* self, void* message)
      { static_cast<Errors*>(self)->Text += static_cast<const char*>(message); });
    object->AddObserver(vtkCommand::ErrorEvent, this->Command);
  }
};

/// Reads `grid` of `path`; the output and the errors for the error tests.
struct Read
{
  vtkNew<vtkOpenVDBReader> Reader;
  Errors Messages{ Reader };
  Read(const std::string& path, const char* grid = nullptr)
  {
    this->Reader->SetFileName(path.c_str());
    this->Reader->SetGridName(grid);
    this->Reader->Update();
  }
  vtkPolyData* Output() { return this->Reader->GetOutput(); }
};

/// Every kernel against the grid it came from: position, covariance, sample volume, value.
void ExpectVoxelKernels(vtkPolyData* output, const openvdb::FloatGrid& grid, double tolerance)
{
  const openvdb::math::Transform& transform = grid.transform();
  const openvdb::Mat3d A = transform.baseMap()->getAffineMap()->getMat4().getMat3().transpose();
  const openvdb::Mat3d expected = 0.36 * A * A.transpose(); // sigma 0.6 voxel
  vtkDataArray* covariance = output->GetPointData()->GetArray("Covariance");
  vtkDataArray* volume = output->GetPointData()->GetArray("SampleVolume");
  vtkDataArray* scalars = output->GetPointData()->GetScalars();
  ASSERT_TRUE(covariance && volume && scalars);
  EXPECT_STREQ(scalars->GetName(), grid.getName().c_str());
  // One vertex cell per kernel, in 32-bit ids (ParaView's Surface shows them).
  EXPECT_EQ(output->GetNumberOfVerts(), output->GetNumberOfPoints());
  EXPECT_EQ(output->GetNumberOfCells(), output->GetNumberOfPoints());
  EXPECT_FALSE(output->GetVerts()->IsStorage64Bit());
  auto accessor = grid.getConstAccessor();
  for (vtkIdType id = 0; id < output->GetNumberOfPoints(); ++id)
  {
    double p[3], c[6];
    output->GetPoint(id, p);
    const openvdb::Vec3d xyz = transform.worldToIndex(openvdb::Vec3d(p[0], p[1], p[2]));
    const openvdb::Coord ijk = openvdb::Coord::round(xyz);
    ASSERT_LT((xyz - ijk.asVec3d()).length(), 1e-4) << "kernel " << id << " off a voxel center";
    ASSERT_TRUE(accessor.isValueOn(ijk));
    EXPECT_NEAR(scalars->GetComponent(id, 0), accessor.getValue(ijk), tolerance);
    covariance->GetTuple(id, c);
    const double e[6] = { expected(0, 0), expected(0, 1), expected(0, 2), expected(1, 1),
      expected(1, 2), expected(2, 2) };
    for (int i = 0; i < 6; ++i)
    {
      EXPECT_NEAR(c[i], e[i], 1e-6);
    }
    EXPECT_NEAR(volume->GetComponent(id, 0), std::abs(A.det()), 1e-7);
  }
}
} // namespace

//------------------------------------------------------------------------------
TEST(OpenVDBReader, ListsGridsFromMetadata)
{
  auto mask = openvdb::BoolGrid::create(false);
  mask->setName("mask");
  mask->tree().setValueOn(openvdb::Coord(1, 2, 3), true);
  auto fog = FogGrid();
  auto velocity = openvdb::Vec3fGrid::create();
  velocity->setName("velocity");
  velocity->tree().setValueOn(openvdb::Coord(0, 0, 0), openvdb::Vec3f(1, 2, 2));
  const std::string path = TempPath("metadata.vdb");
  Write(path, { mask, fog, velocity });

  vtkNew<vtkOpenVDBReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  // OpenVDB lists the grids by name.
  ASSERT_EQ(reader->GetNumberOfGrids(), 3);
  EXPECT_STREQ(reader->GetGridName(0), "density");
  EXPECT_STREQ(reader->GetGridName(1), "mask");
  EXPECT_STREQ(reader->GetGridName(2), "velocity");
  EXPECT_STREQ(reader->GetGridClass(0), "fog volume");
  EXPECT_STREQ(reader->GetGridValueType(0), "float");
  EXPECT_STREQ(reader->GetGridValueType(1), "bool");
  EXPECT_STREQ(reader->GetGridValueType(2), "vec3s");
  EXPECT_STREQ(reader->GetGridTransformType(0), "AffineMap");
  EXPECT_STREQ(reader->GetGridTransformType(1), "UniformScaleMap");
  EXPECT_EQ(reader->GetGridActiveVoxelCount(0), static_cast<vtkIdType>(fog->activeVoxelCount()));
  EXPECT_EQ(reader->GetGridActiveVoxelCount(2), 1);
  EXPECT_EQ(reader->GetGridName(3), nullptr);
  // The values GridName can take (ParaView's grid drop-down): the bool grid is left out.
  vtkStringArray* supported = reader->GetSupportedGridNames();
  ASSERT_EQ(supported->GetNumberOfValues(), 2);
  EXPECT_EQ(supported->GetValue(0), "density");
  EXPECT_EQ(supported->GetValue(1), "velocity");
  double m[16];
  ASSERT_TRUE(reader->GetGridIndexToWorld(0, m));
  const openvdb::Vec3d ijk(3, -4, 7);
  const openvdb::Vec3d world = fog->transform().indexToWorld(ijk);
  for (int row = 0; row < 3; ++row)
  {
    EXPECT_NEAR(m[4 * row] * ijk[0] + m[4 * row + 1] * ijk[1] + m[4 * row + 2] * ijk[2] +
        m[4 * row + 3], world[row], 1e-12);
  }
  std::ostringstream printed;
  reader->Print(printed);
  EXPECT_NE(printed.str().find("'velocity': unknown, vec3s, 1 active voxels"), std::string::npos)
    << printed.str();
  EXPECT_NE(printed.str().find("(not supported)"), std::string::npos);

  // No GridName: the first supported grid.
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 10 * 12 * 14);
  ExpectVoxelKernels(reader->GetOutput(), *fog, 1e-7);
}

//------------------------------------------------------------------------------
TEST(OpenVDBReader, HalfFloatFile)
{
  auto fog = FogGrid();
  const std::string path = TempPath("half.vdb");
  Write(path, { fog }, true);
  Read read(path, "density");
  EXPECT_EQ(read.Output()->GetNumberOfPoints(), 10 * 12 * 14);
  // Values up to 0.61 stored as half: within 2^-11 relative.
  ExpectVoxelKernels(read.Output(), *fog, 0.61 / 2048);
}

//------------------------------------------------------------------------------
TEST(OpenVDBReader, TilesAreFewKernelsOfTheSameMass)
{
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("box");
  grid->setTransform(AffineTransform());
  // 80^3 voxels from -3: 9^3 leaf-sized tiles inside, voxels along the unaligned faces.
  grid->fill(openvdb::CoordBBox(-3, -3, -3, 76, 76, 76), 0.5f, true);
  const std::string path = TempPath("tiles.vdb");
  Write(path, { grid });
  const auto tiles = static_cast<vtkIdType>(grid->tree().activeTileCount());
  ASSERT_GT(tiles, 0);
  for (int k : { 1, 2, 4 })
  {
    vtkNew<vtkOpenVDBReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetTileSubdivision(k);
    reader->Update();
    vtkPolyData* output = reader->GetOutput();
    EXPECT_EQ(reader->GetNumberOfTiles(), tiles);
    EXPECT_EQ(reader->GetNumberOfVoxelKernels(),
      static_cast<vtkIdType>(grid->tree().activeLeafVoxelCount()));
    EXPECT_EQ(output->GetNumberOfPoints(), reader->GetNumberOfVoxelKernels() + tiles * k * k * k);
    EXPECT_LT(output->GetNumberOfPoints(), static_cast<vtkIdType>(grid->activeVoxelCount()) / 2);
    // The sample volumes add up to the active volume: the field's mass is kept.
    vtkDataArray* volume = output->GetPointData()->GetArray("SampleVolume");
    double total = 0.0;
    for (vtkIdType i = 0; i < volume->GetNumberOfTuples(); ++i)
    {
      total += volume->GetComponent(i, 0);
    }
    const double voxel = grid->transform().baseMap()->determinant();
    EXPECT_NEAR(total / (std::abs(voxel) * grid->activeVoxelCount()), 1.0, 1e-5);
  }
}

//------------------------------------------------------------------------------
TEST(OpenVDBReader, LeafTilesBecomeVoxelsOfTheLattice)
{
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("box");
  grid->setTransform(AffineTransform());
  grid->fill(openvdb::CoordBBox(-3, -3, -3, 20, 20, 20), 0.5f, true);
  ASSERT_GT(grid->tree().activeTileCount(), 0u);
  const std::string path = TempPath("lattice.vdb");
  Write(path, { grid });
  // The default TileSubdivision (8) makes the leaf-sized tiles voxels: one kernel per active
  // voxel, each with its index, and the map that places them.
  Read read(path);
  vtkPolyData* output = read.Output();
  ASSERT_EQ(output->GetNumberOfPoints(), static_cast<vtkIdType>(grid->activeVoxelCount()));
  ExpectVoxelKernels(output, *grid, 0.0);
  vtkDataArray* indices = output->GetPointData()->GetArray("VoxelIndex");
  vtkDataArray* matrix = output->GetFieldData()->GetArray("IndexToWorld");
  ASSERT_TRUE(indices && matrix);
  ASSERT_EQ(indices->GetNumberOfComponents(), 3);
  ASSERT_EQ(matrix->GetNumberOfComponents(), 16);
  double m[16], expected[16];
  matrix->GetTuple(0, m);
  ASSERT_TRUE(read.Reader->GetGridIndexToWorld(0, expected));
  for (int i = 0; i < 16; ++i)
  {
    EXPECT_NEAR(m[i], expected[i], 1e-12);
  }
  for (vtkIdType id = 0; id < output->GetNumberOfPoints(); ++id)
  {
    double p[3], ijk[3];
    output->GetPoint(id, p);
    indices->GetTuple(id, ijk);
    for (int row = 0; row < 3; ++row)
    {
      const double world = m[4 * row] * ijk[0] + m[4 * row + 1] * ijk[1] +
        m[4 * row + 2] * ijk[2] + m[4 * row + 3];
      ASSERT_NEAR(p[row], world, 1e-5) << "kernel " << id;
    }
  }
  // Tiles as coarser kernels are off the lattice: no indices.
  read.Reader->SetTileSubdivision(2);
  read.Reader->Update();
  EXPECT_LT(output->GetNumberOfPoints(), static_cast<vtkIdType>(grid->activeVoxelCount()));
  EXPECT_EQ(output->GetPointData()->GetArray("VoxelIndex"), nullptr);
  EXPECT_EQ(output->GetFieldData()->GetArray("IndexToWorld"), nullptr);
}

//------------------------------------------------------------------------------
TEST(OpenVDBReader, DensityStatisticsOnlyForDensities)
{
  // Densities 0 (clear air, left out of the statistics), 1, 2 and 6 in voxels of volume |det A|.
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setTransform(AffineTransform());
  auto accessor = grid->getAccessor();
  const float values[4] = { 0.0f, 1.0f, 2.0f, 6.0f };
  for (int i = 0; i < 4; ++i)
  {
    accessor.setValue(openvdb::Coord(3 * i, i, -i), values[i]);
  }
  const std::string path = TempPath("densities.vdb");
  Write(path, { grid });
  Read read(path);
  vtkDataArray* statistics = read.Output()->GetFieldData()->GetArray("DensityStatistics");
  ASSERT_NE(statistics, nullptr);
  ASSERT_EQ(statistics->GetNumberOfComponents(), 3);
  ASSERT_EQ(statistics->GetNumberOfTuples(), 1);
  const double voxel = std::abs(grid->transform().baseMap()->determinant());
  EXPECT_NEAR(statistics->GetComponent(0, 0), 3.0, 1e-12);
  EXPECT_NEAR(statistics->GetComponent(0, 1), 6.0, 1e-12);
  EXPECT_NEAR(statistics->GetComponent(0, 2), 3.0 * voxel, 1e-6 * voxel);
  // A negative value: not densities, no statistics.
  accessor.setValue(openvdb::Coord(20, 0, 0), -1.0f);
  const std::string signedPath = TempPath("signed.vdb");
  Write(signedPath, { grid });
  Read signedRead(signedPath);
  EXPECT_EQ(signedRead.Output()->GetNumberOfPoints(), 5);
  EXPECT_EQ(signedRead.Output()->GetFieldData()->GetArray("DensityStatistics"), nullptr);
}

//------------------------------------------------------------------------------
TEST(OpenVDBReader, VectorGridMagnitudeAndVectors)
{
  auto grid = openvdb::Vec3dGrid::create();
  grid->setName("velocity");
  auto accessor = grid->getAccessor();
  for (int i = 0; i < 20; ++i)
  {
    accessor.setValue(openvdb::Coord(i, 2 * i, -i), openvdb::Vec3d(i, -2.0, 0.5 * i));
  }
  const std::string path = TempPath("vector.vdb");
  Write(path, { grid });
  Read read(path);
  vtkPolyData* output = read.Output();
  ASSERT_EQ(output->GetNumberOfPoints(), 20);
  vtkDataArray* vectors = output->GetPointData()->GetVectors();
  vtkDataArray* magnitude = output->GetPointData()->GetScalars();
  ASSERT_TRUE(vectors && magnitude);
  EXPECT_STREQ(vectors->GetName(), "velocity");
  EXPECT_STREQ(magnitude->GetName(), "velocity_magnitude");
  for (vtkIdType id = 0; id < 20; ++id)
  {
    double p[3], v[3];
    output->GetPoint(id, p);
    vectors->GetTuple(id, v);
    const openvdb::Vec3d expected = accessor.getValue(openvdb::Coord::round(
      grid->transform().worldToIndex(openvdb::Vec3d(p[0], p[1], p[2]))));
    EXPECT_EQ(openvdb::Vec3d(v[0], v[1], v[2]), expected);
    EXPECT_NEAR(magnitude->GetComponent(id, 0), expected.length(), 1e-12);
  }
}

//------------------------------------------------------------------------------
TEST(OpenVDBReader, PointDataGridPositionsAndAttributes)
{
  std::vector<openvdb::Vec3R> positions;
  for (int i = 0; i < 500; ++i)
  {
    positions.emplace_back(std::sin(0.1 * i), std::cos(0.37 * i), 0.01 * i);
  }
  auto transform = openvdb::math::Transform::createLinearTransform(0.25);
  openvdb::points::PointAttributeVector<openvdb::Vec3R> wrapper(positions);
  auto index = openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(
    wrapper, *transform);
  auto grid = openvdb::points::createPointDataGrid<openvdb::points::NullCodec,
    openvdb::points::PointDataGrid>(*index, wrapper, *transform);
  grid->setName("cloud");
  // "height" = the point's z, through OpenVDB's own attribute population.
  std::vector<float> heights;
  for (const auto& p : positions)
  {
    heights.push_back(static_cast<float>(p.z()));
  }
  openvdb::points::appendAttribute<float>(grid->tree(), "height");
  openvdb::points::PointAttributeVector<float> heightWrapper(heights);
  openvdb::points::populateAttribute(grid->tree(), index->tree(), "height", heightWrapper);
  const std::string path = TempPath("points.vdb");
  Write(path, { grid });

  Read read(path);
  vtkPolyData* output = read.Output();
  ASSERT_EQ(output->GetNumberOfPoints(), 500);
  EXPECT_EQ(output->GetNumberOfVerts(), 500);
  vtkDataArray* height = output->GetPointData()->GetArray("height");
  ASSERT_TRUE(height);
  for (vtkIdType id = 0; id < 500; ++id)
  {
    double p[3];
    output->GetPoint(id, p);
    EXPECT_NEAR(height->GetComponent(id, 0), p[2], 1e-6);
    // On the curve the points were taken from: z = 0.01 i.
    const int i = static_cast<int>(std::lround(p[2] / 0.01));
    EXPECT_NEAR(p[0], std::sin(0.1 * i), 1e-6);
    EXPECT_NEAR(p[1], std::cos(0.37 * i), 1e-6);
  }
}

//------------------------------------------------------------------------------
TEST(OpenVDBReader, DenseImageOfTheGrid)
{
  auto fog = FogGrid();
  const std::string path = TempPath("dense.vdb");
  Write(path, { fog });
  vtkNew<vtkOpenVDBReader> reader;
  reader->SetFileName(path.c_str());
  reader->ProduceDenseOutputOn();
  reader->SetDenseIndexBounds(-4, 7, 0, 11, 5, 18); // one voxel of background before x
  reader->Update();
  vtkImageData* image = reader->GetDenseOutput();
  int extent[6];
  image->GetExtent(extent);
  EXPECT_EQ(extent[0], -4);
  EXPECT_EQ(extent[1], 7);
  EXPECT_EQ(extent[5], 18);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  ASSERT_TRUE(scalars);
  auto accessor = fog->getConstAccessor();
  for (int k = extent[4]; k <= extent[5]; ++k)
    for (int j = extent[2]; j <= extent[3]; ++j)
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        const int ijk[3] = { i, j, k };
        const vtkIdType id = image->ComputePointId(const_cast<int*>(ijk));
        ASSERT_EQ(scalars->GetComponent(id, 0), accessor.getValue(openvdb::Coord(i, j, k)));
        double p[3];
        image->TransformIndexToPhysicalPoint(i, j, k, p);
        const openvdb::Vec3d world = fog->transform().indexToWorld(openvdb::Coord(i, j, k));
        ASSERT_LT((world - openvdb::Vec3d(p[0], p[1], p[2])).length(), 1e-12);
      }
}

//------------------------------------------------------------------------------
TEST(OpenVDBReader, Errors)
{
  // Not a VDB file.
  const std::string text = TempPath("not_a_vdb.vdb");
  std::ofstream(text) << "this is not an OpenVDB file\n";
  {
    Read read(text);
    EXPECT_NE(read.Messages.Text.find(text), std::string::npos) << read.Messages.Text;
    EXPECT_EQ(read.Output()->GetNumberOfPoints(), 0);
  }
  // A missing file.
  {
    Read read(TempPath("missing.vdb"));
    EXPECT_NE(read.Messages.Text.find("missing.vdb"), std::string::npos);
  }
  // A missing grid name: the message names it and lists the grids.
  auto fog = FogGrid();
  const std::string valid = TempPath("valid.vdb");
  Write(valid, { fog });
  {
    Read read(valid, "temperature");
    EXPECT_NE(read.Messages.Text.find("'temperature'"), std::string::npos) << read.Messages.Text;
    EXPECT_NE(read.Messages.Text.find("'density'"), std::string::npos);
    EXPECT_EQ(read.Output()->GetNumberOfPoints(), 0);
  }
  // Truncated anywhere in the voxel data: an error, never a partial output.
  std::ifstream in(valid, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (double fraction : { 0.2, 0.5, 0.9, 0.99 })
  {
    const std::string truncated = TempPath("truncated.vdb");
    std::ofstream(truncated, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(fraction * bytes.size()));
    Read read(truncated, "density");
    EXPECT_NE(read.Messages.Text.find(truncated), std::string::npos) << fraction;
    EXPECT_EQ(read.Output()->GetNumberOfPoints(), 0) << fraction;
  }
  // An empty grid.
  auto empty = openvdb::FloatGrid::create(0.0f);
  empty->setName("nothing");
  const std::string emptyPath = TempPath("empty.vdb");
  Write(emptyPath, { empty });
  {
    Read read(emptyPath);
    EXPECT_NE(read.Messages.Text.find("'nothing'"), std::string::npos) << read.Messages.Text;
    EXPECT_EQ(read.Output()->GetNumberOfPoints(), 0);
  }
  // Unsupported types: by name, and as the only grid.
  auto mask = openvdb::BoolGrid::create(false);
  mask->setName("mask");
  mask->tree().setValueOn(openvdb::Coord(0, 0, 0), true);
  const std::string maskPath = TempPath("mask.vdb");
  Write(maskPath, { mask });
  for (const char* name : { "mask", "" })
  {
    Read read(maskPath, name);
    EXPECT_NE(read.Messages.Text.find("bool"), std::string::npos) << read.Messages.Text;
    EXPECT_NE(read.Messages.Text.find("'mask'"), std::string::npos);
    EXPECT_EQ(read.Output()->GetNumberOfPoints(), 0);
  }
  // A failed read after a good one leaves nothing of the good one.
  {
    Read read(valid, "density");
    EXPECT_GT(read.Output()->GetNumberOfPoints(), 0);
    read.Reader->SetGridName("temperature");
    read.Reader->Update();
    EXPECT_EQ(read.Output()->GetNumberOfPoints(), 0);
  }
}

int main(int argc, char** argv)
{
  openvdb::initialize();
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
