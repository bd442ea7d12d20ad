// SPDX-License-Identifier: BSD-3-Clause
#include "vtkVolumeSplatMapper.h"

#include "SplatCaptureKernel.h"
#include "SplatFloat8.h"
#include "SplatMortonCode.h"
#include "SplatSphericalHarmonics.h"
#include "SplatVolumeKernel.h"
#include "vtkOpenGLImageDepthCompositor.h"
#include "vtkOpenGLVolumeSplatRasterizer.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatRasterizer.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "SplatVTKConversions.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkTimeStamp.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkVolumeSplatMapper);

namespace
{
// The points' ids in the order of a Z curve through their bounds (21 bits an axis; a
// coordinate that is not finite counts as the lowest). Kernels built in this order lie near the
// kernels they share a screen tile with: the CPU capture rasterizer reads each tile's kernels
// in their depth order, and from an input in no spatial order (a trained capture's densified
// Gaussians, the bench's generated one) its compositing spent a third of its time waiting on
// those reads.
std::vector<vtkIdType> ZCurveOrder(vtkPointSet* input)
{
  const vtkIdType n = input->GetNumberOfPoints();
  double bounds[6];
  input->GetPoints()->GetBounds(bounds);
  std::vector<std::pair<std::uint64_t, vtkIdType>> codes(n);
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        double p[3];
        input->GetPoint(i, p);
        std::uint64_t code = 0;
        for (int c = 0; c < 3; ++c)
        {
          const double extent = bounds[2 * c + 1] - bounds[2 * c];
          const double t = extent > 0.0 ? (p[c] - bounds[2 * c]) / extent : 0.0;
          const double cell = std::isfinite(t) ? std::min(std::max(t, 0.0), 1.0) * 0x1fffff : 0.0;
          code |= splat::SpreadBits(static_cast<std::uint64_t>(cell)) << c;
        }
        codes[i] = { code, i };
      }
    });
  vtkSMPTools::Sort(codes.begin(), codes.end());
  std::vector<vtkIdType> order(n);
  std::transform(codes.begin(), codes.end(), order.begin(), [](const auto& c) { return c.second; });
  return order;
}

// The splat::FootprintFilter the rasterizer draws with for the mapper's `filter`: AUTOMATIC is
// the dilation for captures and the band limit for density kernels; captures take the band
// limit as the low-pass (see SetFootprintFilter).
int RasterizerFilter(int filter, bool capture)
{
  if (filter == vtkVolumeSplatMapper::AUTOMATIC_FILTER)
  {
    filter = capture ? vtkVolumeSplatMapper::DILATION_FILTER
                     : vtkVolumeSplatMapper::BAND_LIMIT_FILTER;
  }
  if (filter != vtkVolumeSplatMapper::BAND_LIMIT_FILTER)
  {
    return filter;
  }
  return static_cast<int>(
    capture ? splat::FootprintFilter::LowPass : splat::FootprintFilter::BandLimit);
}
}

// The kernels of the current input, rebuilt only when it, the mapper or the volume property
// changes.
struct vtkVolumeSplatMapper::KernelArrays
{
  std::vector<double> Positions;
  std::vector<float> Covariances; // empty for image data (one shared covariance)
  std::vector<float> Colors;
  std::vector<float> Strengths;
  std::vector<float> Normals; // shaded kernels only
  std::vector<float> SphericalHarmonics; // view-dependent colors only
  int SphericalHarmonicsDegree = 0;
  std::vector<vtkIdType> GridIds; // image data only
  vtkVolumeSplatRasterizer::Kernels View;
  vtkVolumeProperty* Property = nullptr; // the property they were built with (not dereferenced)
  std::string Settings; // the mapper's settings they were built with (KernelSettings)
  vtkTimeStamp BuildTime;

  void Clear()
  {
    for (auto* v : { &this->Covariances, &this->Colors, &this->Strengths, &this->Normals,
           &this->SphericalHarmonics })
    {
      v->clear();
    }
    this->Positions.clear();
    this->GridIds.clear();
    this->View = vtkVolumeSplatRasterizer::Kernels();
  }

  /// The kernels are voxels of a lattice (GridIds set): its axes, voxel 0's position and size.
  void SetLattice(const glm::dmat3& indexToModel, const glm::dvec3& origin, const glm::ivec3& dims)
  {
    this->View.SharedCovariance = splat::VoxelCovariance(indexToModel);
    this->View.PeakOpacity = false;
    // The lists' axes: the index axes, unit length.
    for (int axis = 0; axis < 3; ++axis)
    {
      this->View.ListFrame[axis] = glm::normalize(indexToModel[axis]);
    }
    this->View.GridDimensions = dims;
    this->View.GridAxes = indexToModel;
    this->View.GridOrigin = origin;
  }

  /// Points the rasterizer's view at the arrays.
  void Publish()
  {
    this->View.Count = this->Strengths.size();
    this->View.Positions = this->Positions.data();
    this->View.Covariances = this->Covariances.empty() ? nullptr : this->Covariances.data();
    this->View.Colors = this->Colors.data();
    this->View.Strengths = this->Strengths.data();
    this->View.GridIds = this->GridIds.empty() ? nullptr : this->GridIds.data();
    this->View.Normals = this->Normals.empty() ? nullptr : this->Normals.data();
    this->View.SphericalHarmonics =
      this->SphericalHarmonics.empty() ? nullptr : this->SphericalHarmonics.data();
    this->View.SphericalHarmonicsDegree = this->SphericalHarmonicsDegree;
  }
};

namespace
{
using splat::ToGlm;

// The transfer functions of component 0 sampled over the scalar range: one entry per integer
// for integer scalars with at most 65536 values (exact), 65536 entries otherwise.
class TransferTables
{
public:
  TransferTables(vtkVolumeProperty* property, vtkDataArray* scalars)
  {
    double range[2];
    scalars->GetFiniteRange(range, 0);
    if (!(range[0] <= range[1]))
    {
      range[0] = range[1] = 0.0;
    }
    this->Low = range[0];
    const double span = range[1] - range[0];
    const bool integers =
      scalars->GetDataType() != VTK_FLOAT && scalars->GetDataType() != VTK_DOUBLE;
    const int size = integers && span < 65536.0 ? static_cast<int>(span) + 1 : 65536;
    this->Scale = span > 0.0 ? (size - 1) / span : 0.0;
    this->Extinction.resize(size);
    this->Colors.resize(3 * size);
    property->GetScalarOpacity(0)->GetTable(range[0], range[1], size, this->Extinction.data());
    const double unitDistance = property->GetScalarOpacityUnitDistance(0);
    for (double& tau : this->Extinction)
    {
      // Opacity per unit distance to extinction per unit length, as VTK's ray casters correct
      // opacity for their sample distance: alpha(ds) = 1 - (1 - alpha)^(ds / unitDistance).
      tau = -std::log1p(-std::min(std::max(tau, 0.0), 0.999)) / unitDistance;
    }
    if (property->GetColorChannels(0) == 1)
    {
      std::vector<double> gray(size);
      property->GetGrayTransferFunction(0)->GetTable(range[0], range[1], size, gray.data());
      for (int i = 0; i < size; ++i)
      {
        std::fill_n(this->Colors.begin() + 3 * i, 3, gray[i]);
      }
    }
    else
    {
      property->GetRGBTransferFunction(0)->GetTable(range[0], range[1], size, this->Colors.data());
    }
  }

  /// The entry of a finite scalar value.
  std::size_t Index(double s) const
  {
    const double t = std::round((s - this->Low) * this->Scale);
    return static_cast<std::size_t>(
      std::min(std::max(t, 0.0), static_cast<double>(this->Extinction.size() - 1)));
  }

  std::vector<double> Extinction;
  std::vector<double> Colors;

private:
  double Low = 0.0;
  double Scale = 0.0;
};

// Whether the symmetric matrix is positive semi-definite, to the precision of float input: all
// principal minors non-negative within a relative 1e-6.
bool IsPositiveSemiDefinite(const glm::dmat3& V)
{
  const double scale = std::abs(V[0][0]) + std::abs(V[1][1]) + std::abs(V[2][2]);
  const double tolerance = 1e-6;
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return false;
  }
  for (int i = 0; i < 3; ++i)
  {
    const int j = (i + 1) % 3;
    if (V[i][i] < -tolerance * scale ||
      V[i][i] * V[j][j] - V[i][j] * V[i][j] < -tolerance * scale * scale)
    {
      return false;
    }
  }
  return glm::determinant(V) >= -tolerance * scale * scale * scale;
}

// The input's point-data array of that name with that many components, or null.
vtkDataArray* ArrayOf(vtkDataSet* input, const char* name, int components)
{
  vtkDataArray* array = name ? input->GetPointData()->GetArray(name) : nullptr;
  return array && array->GetNumberOfComponents() == components ? array : nullptr;
}

// The kernels are built in Render: their progress is reported as VTK's volume mappers report
// render progress, not as the pipeline's vtkCommand::ProgressEvent. ParaView relays the
// ProgressEvent of its proxies' objects to the GUI's progress bar, which repaints Qt widgets
// right away: in the middle of the frame, that made Qt's OpenGL context current (vtkOpenGLState
// cache errors) and the view came out without the volume.
void ReportKernelProgress(vtkObject* mapper, double progress)
{
  mapper->InvokeEvent(vtkCommand::VolumeMapperRenderProgressEvent, &progress);
}

bool IsFinite(const double* v, int n)
{
  return std::all_of(v, v + n, [](double x) { return std::isfinite(x); });
}

// The volume property's lighting terms for component 0, as VTK's volume mappers apply them: the
// ambient and diffuse terms scale the transfer function's color, the specular one is white.
splat::Material MaterialOf(vtkVolumeProperty* property)
{
  splat::Material m;
  m.Ambient = static_cast<float>(property->GetAmbient(0));
  m.AmbientFromColor = true;
  m.Diffuse = static_cast<float>(property->GetDiffuse(0));
  m.Specular = glm::vec3(static_cast<float>(property->GetSpecular(0)));
  m.SpecularPower = static_cast<float>(property->GetSpecularPower(0));
  return m;
}

// The unit normal of the scalar field at voxel `index` (value s) in model coordinates: minus
// the gradient by central differences (one-sided where a neighbor is missing or not finite:
// valueAt(index, value) says whether it is there and gives its value), through the inverse
// transpose of the index-to-model matrix; zero where the gradient is. It points from high to
// low values, out of bright structures.
template <typename ValueAt>
glm::vec3 VoxelNormal(
  const ValueAt& valueAt, const glm::ivec3& index, double s, const glm::dmat3& gradientToModel)
{
  glm::dvec3 gradient(0.0);
  for (int axis = 0; axis < 3; ++axis)
  {
    auto neighbor = [&](int step, double& value)
    {
      glm::ivec3 at = index;
      at[axis] += step;
      return valueAt(at, value) && std::isfinite(value);
    };
    double low = s, high = s;
    const bool hasLow = neighbor(-1, low);
    const bool hasHigh = neighbor(1, high);
    const int span = (hasLow ? 1 : 0) + (hasHigh ? 1 : 0);
    gradient[axis] = span > 0 ? ((hasHigh ? high : s) - (hasLow ? low : s)) / span : 0.0;
  }
  const glm::dvec3 normal = -(gradientToModel * gradient);
  const double length = glm::length(normal);
  return length > 0.0 && std::isfinite(length) ? glm::vec3(normal / length) : glm::vec3(0.0f);
}

// A point set's voxel lattice (vtkOpenVDBReader's fog): a 3-component integer array
// "VoxelIndex" and the 16-component field-data array "IndexToWorld" (row-major, column
// vectors) of a non-singular affine map. Indices is null where the input has none.
struct Lattice
{
  vtkDataArray* Indices = nullptr;
  glm::dmat3 Axes{ 1.0 };
  glm::dvec3 Origin{ 0.0 };
};

Lattice LatticeOf(vtkPointSet* input)
{
  Lattice lattice;
  vtkDataArray* indices = ArrayOf(input, "VoxelIndex", 3);
  vtkDataArray* matrix = input->GetFieldData()->GetArray("IndexToWorld");
  if (!indices || indices->GetDataType() == VTK_FLOAT ||
    indices->GetDataType() == VTK_DOUBLE || !matrix ||
    matrix->GetNumberOfComponents() != 16 || matrix->GetNumberOfTuples() < 1)
  {
    return lattice;
  }
  double m[16];
  matrix->GetTuple(0, m);
  for (int column = 0; column < 3; ++column)
  {
    lattice.Origin[column] = m[4 * column + 3];
    for (int row = 0; row < 3; ++row)
    {
      lattice.Axes[column][row] = m[4 * row + column];
    }
  }
  const double volume = std::abs(glm::determinant(lattice.Axes));
  if (IsFinite(m, 16) && volume > 0.0 && std::isfinite(volume))
  {
    lattice.Indices = indices;
  }
  return lattice;
}
}

//------------------------------------------------------------------------------
vtkVolumeSplatMapper::vtkVolumeSplatMapper()
  : Kernels(new KernelArrays)
{
  this->SetCovarianceArrayName("Covariance");
  this->SetScaleArrayName("Scale");
  this->SetRotationArrayName("Rotation");
  this->SetColorArrayName("Color");
  this->SetOpacityArrayName("Opacity");
  this->SetSampleVolumeArrayName("SampleVolume");
  this->SetSphericalHarmonicsArrayName("SphericalHarmonics");
}

//------------------------------------------------------------------------------
vtkVolumeSplatMapper::~vtkVolumeSplatMapper()
{
  this->SetCovarianceArrayName(nullptr);
  this->SetScaleArrayName(nullptr);
  this->SetRotationArrayName(nullptr);
  this->SetColorArrayName(nullptr);
  this->SetOpacityArrayName(nullptr);
  this->SetSampleVolumeArrayName(nullptr);
  this->SetSphericalHarmonicsArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::SetOrderingMode(int mode)
{
  mode = std::min(std::max(mode, static_cast<int>(BLENDED)), static_cast<int>(AUTOMATIC));
  if (mode != this->OrderingMode)
  {
    this->OrderingMode = mode;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::SetFootprintFilter(int filter)
{
  filter = std::min(
    std::max(filter, static_cast<int>(LOW_PASS_FILTER)), static_cast<int>(BAND_LIMIT_FILTER));
  if (filter != this->FootprintFilter)
  {
    this->FootprintFilter = filter;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::SetBlendThreshold(double h)
{
  if (h != this->Rasterizer->GetBlendThreshold())
  {
    this->Rasterizer->SetBlendThreshold(h);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
double vtkVolumeSplatMapper::GetBlendThreshold()
{
  return this->Rasterizer->GetBlendThreshold();
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::SetSheetResampling(bool on)
{
  if (on != this->Rasterizer->GetSheetResampling())
  {
    this->Rasterizer->SetSheetResampling(on);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatMapper::GetSheetResampling()
{
  return this->Rasterizer->GetSheetResampling();
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatMapper::GetSheetsUsed()
{
  return this->LastBackend == vtkSplatBackend::CPU && this->Rasterizer->GetSheetsUsed();
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::SetSheetMerging(bool on)
{
  if (on != this->Rasterizer->GetSheetMerging())
  {
    this->Rasterizer->SetSheetMerging(on);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatMapper::GetSheetMerging()
{
  return this->Rasterizer->GetSheetMerging();
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::SetCutoff(double cutoff)
{
  if (cutoff != this->Rasterizer->GetCutoff())
  {
    this->Rasterizer->SetCutoff(cutoff);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
double vtkVolumeSplatMapper::GetCutoff()
{
  return this->Rasterizer->GetCutoff();
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::SetMaximumSphericalHarmonicsDegree(int degree)
{
  // Not a kernel setting: the lists stay, the colors are evaluated per frame.
  const int old = this->Rasterizer->GetMaximumSphericalHarmonicsDegree();
  this->Rasterizer->SetMaximumSphericalHarmonicsDegree(degree);
  if (this->Rasterizer->GetMaximumSphericalHarmonicsDegree() != old)
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkVolumeSplatMapper::GetMaximumSphericalHarmonicsDegree()
{
  return this->Rasterizer->GetMaximumSphericalHarmonicsDegree();
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatMapper::GetListTraversed(int axis)
{
  return this->LastBackend == vtkSplatBackend::OPENGL
    ? this->OpenGLRasterizer->GetListTraversed(axis)
    : this->Rasterizer->GetListTraversed(axis);
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatMapper::GetNumberOfProjectedKernels(int axis)
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1
                                                     : this->Rasterizer->GetProjectedCount(axis);
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatMapper::GetNumberOfProjectedKernels()
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1
                                                     : this->Rasterizer->GetProjectedCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatMapper::GetNumberOfNearPlaneKernels()
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1
                                                     : this->Rasterizer->GetNearPlaneCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatMapper::GetNumberOfFrustumCulledKernels()
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1
                                                     : this->Rasterizer->GetFrustumCulledCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatMapper::GetNumberOfSorts()
{
  return this->Rasterizer->GetSortCount() + this->OpenGLRasterizer->GetSortCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatMapper::GetNumberOfListBuilds()
{
  return this->Rasterizer->GetListBuildCount();
}

//------------------------------------------------------------------------------
std::string vtkVolumeSplatMapper::KernelSettings()
{
  std::ostringstream settings;
  for (const char* name : { this->CovarianceArrayName, this->ScaleArrayName,
         this->RotationArrayName, this->ColorArrayName, this->OpacityArrayName,
         this->SampleVolumeArrayName, this->SphericalHarmonicsArrayName, this->ArrayName })
  {
    settings << (name ? name : "") << '\n';
  }
  settings << this->ScalarMode << ' ' << this->ArrayAccessMode << ' ' << this->ArrayId;
  return settings.str();
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatMapper::UpdateKernels(vtkVolumeProperty* property)
{
  vtkDataSet* input = this->GetDataSetInput();
  // Ordering, cutoff and backend do not change the kernels: their lists stay.
  const vtkMTimeType changed = std::max(input->GetMTime(), property->GetMTime());
  const std::string settings = this->KernelSettings();
  KernelArrays& k = *this->Kernels;
  if (k.BuildTime.GetMTime() > changed && k.Property == property && k.Settings == settings)
  {
    return true;
  }
  k.Clear();
  ++this->NumberOfKernelBuilds;
  this->NumberOfKernels = this->NumberOfTransparentKernels = this->NumberOfInvalidKernels = 0;
  bool ok = false;
  if (input->GetNumberOfPoints() == 0)
  {
    ok = true; // nothing to draw, and statistics of zero
  }
  else if (auto* image = vtkImageData::SafeDownCast(input))
  {
    ok = this->BuildImageKernels(image, property);
  }
  else if (auto* points = vtkPointSet::SafeDownCast(input))
  {
    ok = LatticeOf(points).Indices ? this->BuildLatticeKernels(points, property)
                                   : this->BuildPointKernels(points, property);
  }
  else
  {
    vtkErrorMacro("vtkVolumeSplatMapper renders vtkImageData and vtkPointSet inputs, not "
      << input->GetClassName() << ".");
  }
  if (!ok)
  {
    k.Clear();
  }
  k.Publish();
  this->NumberOfKernels = static_cast<vtkIdType>(k.View.Count);
  this->Rasterizer->SetKernels(k.View);
  k.Property = property;
  k.Settings = settings;
  k.BuildTime.Modified();
  if (this->NumberOfInvalidKernels > 0)
  {
    vtkWarningMacro(<< this->NumberOfInvalidKernels
                    << " kernels skipped: non-finite position, scalar, covariance, scale, "
                       "rotation or opacity, spherical-harmonic coefficients not finite or "
                       "beyond +-65504, zero rotation quaternion, or a covariance that is not "
                       "positive semi-definite.");
  }
  return ok;
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatMapper::BuildImageKernels(vtkImageData* image, vtkVolumeProperty* property)
{
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(image, this->ScalarMode,
    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  if (!scalars || cellFlag != 0)
  {
    vtkErrorMacro("vtkVolumeSplatMapper needs point scalars on its image data input.");
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  const TransferTables tables(property, scalars);
  glm::dmat3 indexToModel;
  const double* spacing = image->GetSpacing();
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  for (int column = 0; column < 3; ++column)
  {
    for (int row = 0; row < 3; ++row)
    {
      indexToModel[column][row] = direction->GetElement(row, column) * spacing[column];
    }
  }
  // Voxel (x, y, z) counts from the extent's first point, which need not be index 0.
  const int* extent = image->GetExtent();
  glm::dvec3 origin;
  image->TransformIndexToPhysicalPoint(extent[0], extent[2], extent[4], &origin.x);
  const double voxelVolume = std::abs(glm::determinant(indexToModel));
  if (!(voxelVolume > 0.0) || !std::isfinite(voxelVolume))
  {
    vtkErrorMacro("The image's voxels have no volume: spacing ("
      << spacing[0] << ", " << spacing[1] << ", " << spacing[2]
      << ") and direction matrix give a singular or non-finite index-to-world transform "
         "(determinant "
      << voxelVolume << "); nothing is drawn.");
    return false;
  }
  const bool shaded = property->GetShade(0) != 0;
  const glm::dmat3 gradientToModel = glm::transpose(glm::inverse(indexToModel));
  auto valueAt = [&](const glm::ivec3& at, double& value)
  {
    if (glm::any(glm::lessThan(at, glm::ivec3(0))) ||
      glm::any(glm::greaterThanEqual(at, glm::ivec3(dims[0], dims[1], dims[2]))))
    {
      return false;
    }
    const vtkIdType id = at.x + dims[0] * (at.y + static_cast<vtkIdType>(dims[1]) * at.z);
    value = scalars->GetComponent(id, 0);
    return true;
  };

  // Two passes over the k-slices in parallel: count the visible voxels, then fill, so that the
  // kernels stay in voxel-id order (the Z list) whatever the number of threads.
  const vtkIdType nx = dims[0], ny = dims[1], nz = dims[2];
  std::vector<vtkIdType> offsets(nz + 1, 0);
  std::vector<vtkIdType> invalid(nz, 0);
  vtkSMPTools::For(0, nz,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType z = begin; z < end; ++z)
      {
        for (vtkIdType id = z * nx * ny; id < (z + 1) * nx * ny; ++id)
        {
          const double s = scalars->GetComponent(id, 0);
          if (!std::isfinite(s))
          {
            ++invalid[z];
          }
          else if (tables.Extinction[tables.Index(s)] > 0.0)
          {
            ++offsets[z + 1];
          }
        }
      }
    });
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  ReportKernelProgress(this, 0.5);
  KernelArrays& k = *this->Kernels;
  const vtkIdType n = offsets[nz];
  k.Positions.resize(3 * n);
  k.Colors.resize(3 * n);
  k.Strengths.resize(n);
  k.GridIds.resize(n);
  k.Normals.resize(shaded ? 3 * n : 0);
  vtkSMPTools::For(0, nz,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType z = begin; z < end; ++z)
      {
        vtkIdType out = offsets[z];
        for (vtkIdType y = 0; y < ny; ++y)
        {
          for (vtkIdType x = 0; x < nx; ++x)
          {
            const vtkIdType id = x + nx * (y + ny * z);
            const double s = scalars->GetComponent(id, 0);
            if (!std::isfinite(s))
            {
              continue;
            }
            const std::size_t entry = tables.Index(s);
            const double tau = tables.Extinction[entry];
            if (!(tau > 0.0))
            {
              continue;
            }
            const glm::dvec3 p = origin + indexToModel * glm::dvec3(x, y, z);
            for (int c = 0; c < 3; ++c)
            {
              k.Positions[3 * out + c] = p[c];
              k.Colors[3 * out + c] = static_cast<float>(tables.Colors[3 * entry + c]);
            }
            k.Strengths[out] = static_cast<float>(tau * voxelVolume);
            k.GridIds[out] = id;
            if (shaded)
            {
              const glm::vec3 normal =
                VoxelNormal(valueAt, glm::ivec3(x, y, z), s, gradientToModel);
              std::copy_n(&normal.x, 3, k.Normals.begin() + 3 * out);
            }
            ++out;
          }
        }
      }
    });
  ReportKernelProgress(this, 1.0);
  this->NumberOfInvalidKernels = std::accumulate(invalid.begin(), invalid.end(), vtkIdType(0));
  this->NumberOfTransparentKernels = nx * ny * nz - n - this->NumberOfInvalidKernels;
  k.SetLattice(indexToModel, origin, glm::ivec3(dims[0], dims[1], dims[2]));
  return true;
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatMapper::BuildLatticeKernels(vtkPointSet* input, vtkVolumeProperty* property)
{
  const Lattice lattice = LatticeOf(input);
  vtkDataArray* indices = lattice.Indices;
  const glm::dmat3& indexToModel = lattice.Axes;
  const glm::dvec3& indexOrigin = lattice.Origin;
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(input, this->ScalarMode,
    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  if (!scalars || cellFlag != 0)
  {
    vtkErrorMacro("vtkVolumeSplatMapper needs point scalars on its voxel lattice input.");
    return false;
  }
  const vtkIdType count = input->GetNumberOfPoints();
  glm::dvec3 lowest, highest;
  for (int axis = 0; axis < 3; ++axis)
  {
    double range[2];
    indices->GetRange(range, axis);
    lowest[axis] = range[0];
    highest[axis] = range[1];
  }
  // The kernels' box of the lattice is the grid: ids over it, sorted, hold the sheets, and the
  // sheets' tables have an entry per line of it along each axis. Kernels so scattered that the
  // lines outnumber them by far (or indices beyond int) are drawn one by one instead.
  const glm::dvec3 span = highest - lowest + 1.0;
  const double lines = std::max({ span.x * span.y, span.y * span.z, span.z * span.x });
  if (!(lines <= 8.0 * static_cast<double>(count) + (1 << 22)) ||
    glm::any(glm::lessThan(lowest, glm::dvec3(std::numeric_limits<int>::min()))) ||
    glm::any(glm::greaterThan(highest, glm::dvec3(std::numeric_limits<int>::max()))))
  {
    vtkWarningMacro("The VoxelIndex box of " << count << " kernels has " << lines
                                             << " lines along an axis: the kernels are drawn "
                                                "one by one, off the lattice.");
    return this->BuildPointKernels(input, property);
  }
  const glm::ivec3 low(lowest), high(highest);
  const glm::ivec3 dims = high - low + 1;
  const vtkIdType nx = dims.x, ny = dims.y;
  auto idOf = [&](const glm::ivec3& at)
  { return (at.x - low.x) + nx * ((at.y - low.y) + ny * (at.z - low.z)); };
  auto indexOf = [&](vtkIdType i)
  {
    double index[3];
    indices->GetTuple(i, index);
    return glm::ivec3(index[0], index[1], index[2]);
  };
  std::vector<std::pair<vtkIdType, vtkIdType>> voxels; // (id, point) of the finite values
  voxels.reserve(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    if (std::isfinite(scalars->GetComponent(i, 0)))
    {
      voxels.emplace_back(idOf(indexOf(i)), i);
    }
  }
  this->NumberOfInvalidKernels = count - static_cast<vtkIdType>(voxels.size());
  vtkSMPTools::Sort(voxels.begin(), voxels.end());
  ReportKernelProgress(this, 0.5);

  const TransferTables tables(property, scalars);
  const double voxelVolume = std::abs(glm::determinant(indexToModel));
  const glm::dvec3 origin = indexOrigin + indexToModel * glm::dvec3(low);
  const bool shaded = property->GetShade(0) != 0;
  const glm::dmat3 gradientToModel = glm::transpose(glm::inverse(indexToModel));
  auto valueAt = [&](const glm::ivec3& at, double& value)
  {
    if (glm::any(glm::lessThan(at, low)) || glm::any(glm::greaterThan(at, high)))
    {
      return false;
    }
    const auto it = std::lower_bound(voxels.begin(), voxels.end(),
      std::make_pair(idOf(at), vtkIdType(0)));
    if (it == voxels.end() || it->first != idOf(at))
    {
      return false;
    }
    value = scalars->GetComponent(it->second, 0);
    return true;
  };
  KernelArrays& k = *this->Kernels;
  for (const auto& voxel : voxels)
  {
    const double s = scalars->GetComponent(voxel.second, 0);
    const std::size_t entry = tables.Index(s);
    const double tau = tables.Extinction[entry];
    if (!(tau > 0.0))
    {
      ++this->NumberOfTransparentKernels;
      continue;
    }
    const glm::ivec3 at = indexOf(voxel.second);
    const glm::dvec3 p = indexOrigin + indexToModel * glm::dvec3(at);
    for (int c = 0; c < 3; ++c)
    {
      k.Positions.push_back(p[c]);
      k.Colors.push_back(static_cast<float>(tables.Colors[3 * entry + c]));
    }
    k.Strengths.push_back(static_cast<float>(tau * voxelVolume));
    k.GridIds.push_back(voxel.first);
    if (shaded)
    {
      const glm::vec3 normal = VoxelNormal(valueAt, at, s, gradientToModel);
      k.Normals.insert(k.Normals.end(), &normal.x, &normal.x + 3);
    }
  }
  ReportKernelProgress(this, 1.0);
  k.SetLattice(indexToModel, origin, dims);
  return true;
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatMapper::BuildPointKernels(vtkPointSet* input, vtkVolumeProperty* property)
{
  vtkDataArray* covariances = ArrayOf(input, this->CovarianceArrayName, 6);
  vtkDataArray* scales = ArrayOf(input, this->ScaleArrayName, 3);
  vtkDataArray* rotations = ArrayOf(input, this->RotationArrayName, 4);
  if (!covariances && !(scales && rotations))
  {
    vtkErrorMacro("vtkVolumeSplatMapper needs a 6-component covariance array '"
      << (this->CovarianceArrayName ? this->CovarianceArrayName : "") << "' or a 3-component "
      << "scale array '" << (this->ScaleArrayName ? this->ScaleArrayName : "")
      << "' and a 4-component rotation array '"
      << (this->RotationArrayName ? this->RotationArrayName : "") << "' on its point set input.");
    return false;
  }
  vtkDataArray* colors = ArrayOf(input, this->ColorArrayName, 3);
  colors = colors ? colors : ArrayOf(input, this->ColorArrayName, 4);
  vtkDataArray* opacities = ArrayOf(input, this->OpacityArrayName, 1);
  vtkDataArray* sampleVolumes = ArrayOf(input, this->SampleVolumeArrayName, 1);
  vtkDataArray* harmonics = this->SphericalHarmonicsArrayName
    ? input->GetPointData()->GetArray(this->SphericalHarmonicsArrayName)
    : nullptr;
  const int degree =
    harmonics ? splat::SphericalHarmonicsDegreeOf(harmonics->GetNumberOfComponents()) : -1;
  if (harmonics && degree < 0)
  {
    vtkErrorMacro("The spherical-harmonics array '"
      << this->SphericalHarmonicsArrayName << "' has " << harmonics->GetNumberOfComponents()
      << " components, not 3 (degree + 1)^2 for a degree of 0 to 3 (3, 12, 27 or 48); it is "
         "ignored.");
    harmonics = nullptr;
  }
  // View-dependent colors take precedence over the color array and the transfer function.
  colors = harmonics ? nullptr : colors;
  vtkDataArray* normals = nullptr;
  if (property->GetShade(0))
  {
    normals = input->GetPointData()->GetNormals();
    if (!normals || normals->GetNumberOfComponents() != 3)
    {
      normals = nullptr;
      vtkWarningMacro("Shading a point set needs point normals (vtkPointData::SetNormals); the "
                      "kernels are drawn unshaded.");
    }
  }
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(input, this->ScalarMode,
    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  scalars = cellFlag == 0 ? scalars : nullptr;
  if ((!(colors || harmonics) || !opacities) && !scalars)
  {
    vtkErrorMacro("vtkVolumeSplatMapper needs point scalars for the transfer functions, or a "
                  "color (or spherical-harmonics) array and an opacity array, on its point set "
                  "input.");
    return false;
  }
  std::unique_ptr<TransferTables> tables(scalars ? new TransferTables(property, scalars) : nullptr);
  const double colorScale = colors && colors->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
  KernelArrays& k = *this->Kernels;
  const vtkIdType n = input->GetNumberOfPoints();
  k.Positions.reserve(3 * n);
  k.Colors.reserve(3 * n);
  k.Covariances.reserve(6 * n);
  k.Strengths.reserve(n);
  k.Normals.reserve(normals ? 3 * n : 0);
  const int coefficientCount = harmonics ? harmonics->GetNumberOfComponents() : 0;
  k.SphericalHarmonics.reserve(coefficientCount * n);
  k.SphericalHarmonicsDegree = std::max(degree, 0);
  std::vector<double> tuple(coefficientCount);
  std::vector<float> coefficients(coefficientCount);
  const std::vector<vtkIdType> order = opacities ? ZCurveOrder(input) : std::vector<vtkIdType>();
  // In the curve's order, the rows come from all over the arrays: the rows of arrays in VTK's
  // standard layout are asked for 16 kernels ahead (per array, its first row and row bytes).
  vtkDataArray* const read[] = { input->GetPoints()->GetData(), covariances, scales, rotations,
    opacities, harmonics, colors, normals, scalars, sampleVolumes };
  std::vector<std::pair<const char*, int>> rows;
  for (vtkDataArray* array : read)
  {
    if (!order.empty() && array && array->HasStandardMemoryLayout())
    {
      rows.emplace_back(static_cast<const char*>(array->GetVoidPointer(0)),
        array->GetNumberOfComponents() * array->GetDataTypeSize());
    }
  }
  for (vtkIdType j = 0; j < n; ++j)
  {
    for (const auto& row : rows)
    {
      if (j + 16 < n)
      {
        splat::PrefetchBytes(row.first + order[j + 16] * row.second, row.second);
      }
    }
    if (j % 65536 == 0)
    {
      ReportKernelProgress(this, static_cast<double>(j) / n);
    }
    const vtkIdType i = order.empty() ? j : order[j];
    double p[3];
    input->GetPoint(i, p);
    glm::dmat3 V(0.0);
    double mass = 0.0; // the integral of the unnormalized Gaussian, (2 pi)^(3/2) sqrt|V|
    bool valid = IsFinite(p, 3);
    if (covariances)
    {
      double c[6];
      covariances->GetTuple(i, c);
      V = splat::SymmetricFromComponents(c);
      valid = valid && IsFinite(c, 6) && IsPositiveSemiDefinite(V);
      mass = splat::TwoPiToThreeHalves * std::sqrt(std::max(glm::determinant(V), 0.0));
    }
    else
    {
      glm::dvec3 s;
      glm::dvec4 q;
      scales->GetTuple(i, &s.x);
      rotations->GetTuple(i, &q.x);
      // Any nonzero finite quaternion is a rotation (CovarianceFromScaleRotation scales it
      // before normalizing); scales whose squares overflow give a non-finite covariance.
      const double largest =
        std::max({ std::abs(q.x), std::abs(q.y), std::abs(q.z), std::abs(q.w) });
      valid = valid && IsFinite(&s.x, 3) && IsFinite(&q.x, 4) && largest > 0.0;
      if (valid)
      {
        V = splat::CovarianceFromScaleRotation(s, q);
        mass = splat::TwoPiToThreeHalves * std::abs(s.x * s.y * s.z);
        valid = IsFinite(&V[0][0], 9) && std::isfinite(mass);
      }
    }
    const double scalar = scalars ? scalars->GetComponent(i, 0) : 0.0;
    std::size_t entry = 0;
    double strength;
    if (opacities)
    {
      strength = opacities->GetComponent(i, 0);
      valid = valid && std::isfinite(strength);
      strength = std::min(strength, 1.0);
    }
    else
    {
      valid = valid && std::isfinite(scalar);
      entry = valid ? tables->Index(scalar) : 0;
      // A field's sample stands for its volume; a free kernel's density peaks at tau.
      const double volume = sampleVolumes ? sampleVolumes->GetComponent(i, 0) : mass;
      valid = valid && std::isfinite(volume) && volume >= 0.0;
      strength = tables->Extinction[entry] * volume;
      valid = valid && std::isfinite(strength);
    }
    double rgb[4] = { 1.0, 1.0, 1.0, 1.0 };
    if (harmonics)
    {
      // Within the half-float range of the OpenGL backend's buffer (it also keeps the sums
      // finite); the Colors hold the degree-0 (view-independent) color.
      harmonics->GetTuple(i, tuple.data());
      valid = valid &&
        std::all_of(tuple.begin(), tuple.end(), [](double c) { return std::abs(c) <= 65504.0; });
      std::copy(tuple.begin(), tuple.end(), coefficients.begin());
      const glm::vec3 base =
        splat::SphericalHarmonicsColor(coefficients.data(), 0, glm::vec3(0.0f));
      std::copy_n(&base.x, 3, rgb);
    }
    else if (colors)
    {
      colors->GetTuple(i, rgb);
      valid = valid && IsFinite(rgb, 3);
    }
    else if (valid)
    {
      std::copy_n(tables->Colors.begin() + 3 * entry, 3, rgb);
    }
    if (!valid)
    {
      ++this->NumberOfInvalidKernels;
      continue;
    }
    if (!(strength > 0.0))
    {
      ++this->NumberOfTransparentKernels;
      continue;
    }
    const double components[6] = { V[0][0], V[1][0], V[2][0], V[1][1], V[2][1], V[2][2] };
    for (int c = 0; c < 6; ++c)
    {
      k.Covariances.push_back(static_cast<float>(components[c]));
    }
    for (int c = 0; c < 3; ++c)
    {
      k.Positions.push_back(p[c]);
      k.Colors.push_back(static_cast<float>(std::min(std::max(rgb[c] * colorScale, 0.0), 1.0)));
    }
    k.Strengths.push_back(static_cast<float>(strength));
    if (normals)
    {
      // Non-finite normals shade like zero ones: ambient only.
      double normal[3];
      normals->GetTuple(i, normal);
      const bool finite = IsFinite(normal, 3);
      for (int c = 0; c < 3; ++c)
      {
        k.Normals.push_back(finite ? static_cast<float>(normal[c]) : 0.0f);
      }
    }
    k.SphericalHarmonics.insert(
      k.SphericalHarmonics.end(), coefficients.begin(), coefficients.end());
  }
  ReportKernelProgress(this, 1.0);
  k.View.PeakOpacity = opacities != nullptr;
  k.View.ListFrame = glm::dmat3(1.0);
  return true;
}

//------------------------------------------------------------------------------
int vtkVolumeSplatMapper::SelectBackend(vtkRenderer* ren)
{
  return vtkSplatBackend::Resolve(this->Backend, ren->GetRenderWindow());
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::Render(vtkRenderer* ren, vtkVolume* volume)
{
  const auto start = std::chrono::steady_clock::now();
  if (!this->GetDataSetInput())
  {
    vtkErrorMacro("No input.");
    return;
  }
  this->GetInputAlgorithm()->Update();
  vtkDataSet* input = this->GetDataSetInput();
  vtkVolumeProperty* property = volume->GetProperty();
  // Hardware picking of volume splats is not implemented (in either backend).
  if (!input || ren->GetSelector() || !property || !this->UpdateKernels(property))
  {
    return;
  }
  this->Compositor->MoveGraphicsResources(ren, this);
  this->LastBackend = this->SelectBackend(ren);
  // The automatic settings follow the kind of kernels: captures are drawn as they were trained.
  const bool capture = this->Kernels->View.PeakOpacity;
  this->LastOrderingMode = this->OrderingMode != AUTOMATIC ? this->OrderingMode
                                                           : (capture ? DEPTH_SORTED : BLENDED);
  this->Rasterizer->SetOrderingMode(this->LastOrderingMode);
  this->Rasterizer->SetFootprintFilter(RasterizerFilter(this->FootprintFilter, capture));

  int width, height, originX, originY;
  ren->GetTiledSizeAndOrigin(&width, &height, &originX, &originY);
  vtkCamera* camera = ren->GetActiveCamera();
  vtkVolumeSplatRasterizer::Camera view;
  view.ModelToEye = ToGlm(camera->GetModelViewTransformMatrix()) * ToGlm(volume->GetMatrix());
  view.EyeToClip =
    ToGlm(camera->GetProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1.0, 1.0));
  view.Viewport = glm::ivec2(width, height);
  if (this->Kernels->View.Normals)
  {
    const glm::dmat4 worldToEye = ToGlm(camera->GetModelViewTransformMatrix());
    this->Rasterizer->SetLighting(
      splat::EyeLights(ren, worldToEye), MaterialOf(property), ren->GetTwoSidedLighting() != 0);
  }

  // The opaque geometry is drawn: its depth ends each pixel's integration.
  std::vector<float> sceneDepths;
  this->Compositor->ReadDepths(ren, sceneDepths);
  // Depth 0 passes the compositor's depth test everywhere: occlusion is already applied, and
  // the volume writes no depth.
  if (this->LastBackend == vtkSplatBackend::OPENGL)
  {
    this->OpenGLRasterizer->SetKernels(this->Kernels->View, this->Kernels->BuildTime.GetMTime());
    this->OpenGLRasterizer->Render(ren, view, this->Rasterizer, sceneDepths);
    this->Compositor->DrawTextures(ren, this->OpenGLRasterizer->GetColorTexture(),
      this->OpenGLRasterizer->GetDepthTexture(),
      vtkOpenGLImageDepthCompositor::Blending::Translucent);
  }
  else
  {
    this->Rasterizer->SetSceneDepths(std::move(sceneDepths));
    this->Rasterizer->Render(view);
    const std::vector<float> depths(static_cast<std::size_t>(width) * height, 0.0f);
    this->Compositor->Draw(ren, width, height, this->Rasterizer->GetColors().data(),
      depths.data(), vtkOpenGLImageDepthCompositor::Blending::Translucent);
  }

  this->LastRenderTimeInMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

//------------------------------------------------------------------------------
double* vtkVolumeSplatMapper::GetBounds()
{
  vtkMath::UninitializeBounds(this->Bounds);
  vtkDataSet* input = this->GetDataSetInput();
  if (!input || input->GetNumberOfPoints() == 0)
  {
    return this->Bounds;
  }
  this->GetInputAlgorithm()->Update();
  // The largest standard deviation along each model axis, grown to the cutoff's extent.
  glm::dvec3 sigma(0.0);
  double bounds[6];
  if (auto* image = vtkImageData::SafeDownCast(input))
  {
    image->GetBounds(bounds);
    const double* spacing = image->GetSpacing();
    // Negative spacings mirror the grid: their magnitude is the voxel's extent.
    const double largest =
      std::max({ std::abs(spacing[0]), std::abs(spacing[1]), std::abs(spacing[2]) });
    sigma = glm::dvec3(splat::VoxelKernelSigma * largest);
  }
  else if (auto* points = vtkPointSet::SafeDownCast(input))
  {
    vtkDataArray* data = points->GetPoints()->GetData();
    for (int axis = 0; axis < 3; ++axis)
    {
      data->GetFiniteRange(bounds + 2 * axis, axis);
    }
    if (vtkDataArray* covariances = ArrayOf(input, this->CovarianceArrayName, 6))
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        const int component = axis == 0 ? 0 : (axis == 1 ? 3 : 5);
        sigma[axis] = std::sqrt(std::max(covariances->GetFiniteRange(component)[1], 0.0));
      }
    }
    else if (vtkDataArray* scales = ArrayOf(input, this->ScaleArrayName, 3))
    {
      double largest = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double* range = scales->GetFiniteRange(c);
        largest = std::max({ largest, std::abs(range[0]), std::abs(range[1]) });
      }
      // Scales whose squares overflow make their kernels invalid (skipped): they must not
      // stretch the bounds, and with them the camera's clipping range, over the valid ones.
      const double limit = std::sqrt(std::numeric_limits<double>::max());
      if (largest >= limit)
      {
        largest = 0.0;
        for (vtkIdType i = 0; i < scales->GetNumberOfValues(); ++i)
        {
          const double s = std::abs(scales->GetComponent(i / 3, static_cast<int>(i % 3)));
          largest = s < limit ? std::max(largest, s) : largest;
        }
      }
      sigma = glm::dvec3(largest);
    }
  }
  else
  {
    return this->Bounds;
  }
  const double reach = std::sqrt(2.0 * this->GetCutoff());
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!(bounds[2 * axis] <= bounds[2 * axis + 1]))
    {
      vtkMath::UninitializeBounds(this->Bounds);
      return this->Bounds;
    }
    this->Bounds[2 * axis] = bounds[2 * axis] - reach * sigma[axis];
    this->Bounds[2 * axis + 1] = bounds[2 * axis + 1] + reach * sigma[axis];
  }
  return this->Bounds;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Compositor->ReleaseGraphicsResources(window);
  this->OpenGLRasterizer->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkVolumeSplatMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto name = [](const char* s) { return s ? s : "(none)"; };
  os << indent << "OrderingMode: " << this->OrderingMode << "\n";
  os << indent << "LastOrderingMode: " << this->LastOrderingMode << "\n";
  os << indent << "FootprintFilter: " << this->FootprintFilter << "\n";
  os << indent << "BlendThreshold: " << this->GetBlendThreshold() << "\n";
  os << indent << "SheetResampling: " << this->GetSheetResampling() << "\n";
  os << indent << "SheetMerging: " << this->GetSheetMerging() << "\n";
  os << indent << "Cutoff: " << this->GetCutoff() << "\n";
  os << indent << "Backend: " << vtkSplatBackend::GetBackendAsString(this->Backend) << "\n";
  os << indent << "LastBackend: " << vtkSplatBackend::GetBackendAsString(this->LastBackend)
     << "\n";
  os << indent << "CovarianceArrayName: " << name(this->CovarianceArrayName) << "\n";
  os << indent << "ScaleArrayName: " << name(this->ScaleArrayName) << "\n";
  os << indent << "RotationArrayName: " << name(this->RotationArrayName) << "\n";
  os << indent << "ColorArrayName: " << name(this->ColorArrayName) << "\n";
  os << indent << "OpacityArrayName: " << name(this->OpacityArrayName) << "\n";
  os << indent << "SampleVolumeArrayName: " << name(this->SampleVolumeArrayName) << "\n";
  os << indent << "SphericalHarmonicsArrayName: " << name(this->SphericalHarmonicsArrayName)
     << "\n";
  os << indent << "MaximumSphericalHarmonicsDegree: " << this->GetMaximumSphericalHarmonicsDegree()
     << "\n";
  os << indent << "NumberOfKernels: " << this->NumberOfKernels << "\n";
  os << indent << "NumberOfTransparentKernels: " << this->NumberOfTransparentKernels << "\n";
  os << indent << "NumberOfInvalidKernels: " << this->NumberOfInvalidKernels << "\n";
  os << indent << "NumberOfKernelBuilds: " << this->NumberOfKernelBuilds << "\n";
  os << indent << "LastRenderTimeInMilliseconds: " << this->LastRenderTimeInMilliseconds << "\n";
  os << indent << "Rasterizer:\n";
  this->Rasterizer->PrintSelf(os, indent.GetNextIndent());
  os << indent << "OpenGLRasterizer:\n";
  this->OpenGLRasterizer->PrintSelf(os, indent.GetNextIndent());
}
