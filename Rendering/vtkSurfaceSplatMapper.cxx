// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfaceSplatMapper.h"

#include "SplatSurfelCoverage.h"
#include "SplatSurfelKernel.h"
#include "vtkOpenGLImageDepthCompositor.h"
#include "vtkOpenGLSurfaceSplatRasterizer.h"
#include "vtkSurfaceSplatRasterizer.h"
#include "vtkSurfelHierarchy.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkHardwareSelector.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkMath.h"
#include "SplatVTKConversions.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOrderIndependentTranslucentPass.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkTimeStamp.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkSurfaceSplatMapper);

// The surfels of the current input, rebuilt only when it or its coloring changes.
struct vtkSurfaceSplatMapper::SurfelArrays
{
  std::vector<double> Positions;
  std::vector<float> Normals;
  std::vector<float> Axes0;
  std::vector<float> Axes1;
  std::vector<float> Colors;
  std::vector<float> Opacities; // empty when every opacity is 1
  std::vector<float> Curvatures; // differential points' lambda_u, lambda_v; empty for surfels
  // The input point of each surfel, for picking; empty when none was skipped (surfel i is
  // point i), which saves 8 bytes per point on most inputs.
  std::vector<vtkIdType> PointIds;
  bool ColorsFromScalars = false;
  // The property the colors and opacities were taken from: actors sharing the mapper have
  // their own (compared only, never dereferenced).
  const vtkProperty* Property = nullptr;
  vtkTimeStamp BuildTime;
  // Their levels of detail, built on the first CPU frame that draws them.
  vtkNew<vtkSurfelHierarchy> Hierarchy;
  vtkTimeStamp HierarchyTime;

  // The automatic cutoff (vtkSurfaceSplatMapper::ChooseCoverage), for the coverage threshold
  // it was chosen with, and whether it covers at the box filter's threshold too (tested only
  // for frames that could use it).
  double AutomaticCutoff = 0.0;
  double AutomaticThreshold = 0.0;
  bool BoxFilterThresholdTested = false;
  bool CoversAtBoxFilterThreshold = false;
  vtkTimeStamp AutomaticTime;

  const vtkSurfelHierarchy* UpdateHierarchy()
  {
    if (this->HierarchyTime < this->BuildTime)
    {
      this->Hierarchy->Build(this->View());
      this->HierarchyTime.Modified();
    }
    return this->Hierarchy;
  }

  vtkSurfaceSplatRasterizer::Surfels View() const
  {
    return vtkSurfaceSplatRasterizer::Surfels::Of(this->Positions, this->Normals, this->Axes0,
      this->Axes1, this->Colors, this->Opacities, this->Curvatures);
  }
};

namespace
{
using splat::ToGlm;

// The actor's model-to-eye and the camera's projection over the renderer's viewport.
vtkSurfaceSplatRasterizer::Camera ViewOf(vtkRenderer* ren, vtkActor* actor)
{
  int width, height, originX, originY;
  ren->GetTiledSizeAndOrigin(&width, &height, &originX, &originY);
  vtkCamera* camera = ren->GetActiveCamera();
  vtkSurfaceSplatRasterizer::Camera view;
  view.ModelToEye = ToGlm(camera->GetModelViewTransformMatrix()) * ToGlm(actor->GetMatrix());
  view.EyeToClip =
    ToGlm(camera->GetProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1.0, 1.0));
  view.Viewport = glm::ivec2(width, height);
  return view;
}

splat::Material MaterialOf(vtkProperty* property, bool colorsFromScalars)
{
  splat::Material m;
  const double* ambientColor = property->GetAmbientColor();
  const double* specularColor = property->GetSpecularColor();
  m.Ambient = static_cast<float>(property->GetAmbient());
  m.AmbientColor = glm::vec3(ambientColor[0], ambientColor[1], ambientColor[2]);
  m.AmbientFromColor = colorsFromScalars;
  m.Diffuse = static_cast<float>(property->GetDiffuse());
  m.Specular = static_cast<float>(property->GetSpecular()) *
    glm::vec3(specularColor[0], specularColor[1], specularColor[2]);
  m.SpecularPower = static_cast<float>(property->GetSpecularPower());
  return m;
}

// Whether the actor is being drawn by VTK's order-independent translucent pass.
bool InOrderIndependentPass(vtkActor* actor)
{
  vtkInformation* keys = actor->GetPropertyKeys();
  if (!keys || !keys->Has(vtkOpenGLRenderPass::RenderPasses()))
  {
    return false;
  }
  const int count = keys->Length(vtkOpenGLRenderPass::RenderPasses());
  for (int i = 0; i < count; ++i)
  {
    if (vtkOrderIndependentTranslucentPass::SafeDownCast(
          keys->Get(vtkOpenGLRenderPass::RenderPasses(), i)))
    {
      return true;
    }
  }
  return false;
}

bool IsFinite(const double* v, int n)
{
  for (int i = 0; i < n; ++i)
  {
    if (!std::isfinite(v[i]))
    {
      return false;
    }
  }
  return true;
}

// v scaled to unit length, or zero where it has no direction (zero or not finite). Scaled by
// its largest component first: the squares of components below 1e-154 underflow and those
// above 1e154 overflow, which would make a valid normal or axis look zero or infinite.
glm::dvec3 Unit(const glm::dvec3& v)
{
  const double largest = std::max({ std::abs(v.x), std::abs(v.y), std::abs(v.z) });
  if (!(largest > 0.0 && std::isfinite(largest)))
  {
    return glm::dvec3(0.0);
  }
  const glm::dvec3 scaled = v / largest;
  return scaled / glm::length(scaled);
}
}

//------------------------------------------------------------------------------
vtkSurfaceSplatMapper::vtkSurfaceSplatMapper()
  : Surfels(new SurfelArrays)
{
  this->SetRadiusArrayName("Radius");
  this->SetOpacityArrayName("Opacity");
  this->SetTangentAxis0ArrayName("TangentAxis0");
  this->SetTangentAxis1ArrayName("TangentAxis1");
  this->SetPrincipalDirectionUArrayName("PrincipalDirectionU");
  this->SetPrincipalDirectionVArrayName("PrincipalDirectionV");
  this->SetPrincipalCurvaturesArrayName("PrincipalCurvatures");
  this->SetExtentsArrayName("Extents");
}

//------------------------------------------------------------------------------
vtkSurfaceSplatMapper::~vtkSurfaceSplatMapper()
{
  this->SetRadiusArrayName(nullptr);
  this->SetOpacityArrayName(nullptr);
  this->SetTangentAxis0ArrayName(nullptr);
  this->SetTangentAxis1ArrayName(nullptr);
  this->SetPrincipalDirectionUArrayName(nullptr);
  this->SetPrincipalDirectionVArrayName(nullptr);
  this->SetPrincipalCurvaturesArrayName(nullptr);
  this->SetExtentsArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::SetCutoff(double cutoff)
{
  if (!(cutoff >= 0.0))
  {
    vtkErrorMacro("Cutoff must be 0 (automatic) or positive, not " << cutoff << ".");
    return;
  }
  if (cutoff != this->Cutoff)
  {
    this->Cutoff = cutoff;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::SetMagnifiedLowPassVariance(double variance)
{
  if (!(variance == 0.0 || (variance >= splat::BoxFilterVariance && variance <= 1.0)))
  {
    vtkErrorMacro("MagnifiedLowPassVariance must be 0 (automatic) or between 1/12 and 1, not "
      << variance << ".");
    return;
  }
  if (variance != this->MagnifiedLowPassVariance)
  {
    this->MagnifiedLowPassVariance = variance;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::ChooseCoverage(bool boxFilter)
{
  constexpr double Paper = 1.0;
  constexpr double Widest = 4.0;
  // Each tried in turn against a wider reference of what covering is; Widest where none
  // covers. 0.6 is for grids whose radius is their spacing: their disks at 0.5 only touch.
  constexpr std::array<std::array<double, 2>, 5> Ladder = { { { 0.5, Paper }, { 0.6, Paper },
    { Paper, 2.0 }, { 2.0, Widest }, { 3.0, Widest } } };
  // The share of the surface a cutoff may leave uncovered: holes in fewer samples are at the
  // surface's boundary or too small to see.
  constexpr double AcceptedHoles = 0.01;
  const double tau =
    this->CoverageThreshold > 0.0 ? this->CoverageThreshold : splat::PaperCoverageThreshold;
  this->LastCoverageThreshold = tau;
  if (this->Cutoff > 0.0 || this->Primitive != SURFELS)
  {
    this->LastCutoff = this->Cutoff > 0.0 ? this->Cutoff : Paper;
    return;
  }
  SurfelArrays& surfels = *this->Surfels;
  const bool mayRaise = this->CoverageThreshold == 0.0 && boxFilter;
  if (surfels.AutomaticTime < surfels.BuildTime || surfels.AutomaticThreshold != tau ||
    (mayRaise && !surfels.BoxFilterThresholdTested))
  {
    const splat::SurfelCoverage coverage(surfels.View());
    surfels.AutomaticCutoff = Widest;
    for (const auto& step : Ladder)
    {
      if (coverage.UncoveredShare(step[0], step[1], tau) <= AcceptedHoles)
      {
        surfels.AutomaticCutoff = step[0];
        break;
      }
    }
    // What the cutoff covers at tau, still covered at the box filter's threshold.
    const double cutoff = surfels.AutomaticCutoff;
    surfels.BoxFilterThresholdTested = mayRaise;
    surfels.CoversAtBoxFilterThreshold = mayRaise &&
      coverage.UncoveredShare(cutoff, cutoff, splat::BoxFilterCoverageThreshold, tau) <=
        AcceptedHoles;
    surfels.AutomaticThreshold = tau;
    surfels.AutomaticTime.Modified();
  }
  this->LastCutoff = surfels.AutomaticCutoff;
  if (mayRaise && surfels.CoversAtBoxFilterThreshold)
  {
    this->LastCoverageThreshold = splat::BoxFilterCoverageThreshold;
  }
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::SetMinifiedVariance(double variance)
{
  if (variance != this->Rasterizer->GetMinifiedVariance())
  {
    this->Rasterizer->SetMinifiedVariance(variance);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
double vtkSurfaceSplatMapper::GetMinifiedVariance()
{
  return this->Rasterizer->GetMinifiedVariance();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::SetDepthThreshold(double threshold)
{
  if (threshold != this->Rasterizer->GetDepthThreshold())
  {
    this->Rasterizer->SetDepthThreshold(threshold);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
double vtkSurfaceSplatMapper::GetDepthThreshold()
{
  return this->Rasterizer->GetDepthThreshold();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::SetNumberOfLayers(int layers)
{
  if (layers != this->Rasterizer->GetNumberOfLayers())
  {
    this->Rasterizer->SetNumberOfLayers(layers);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::SetNumberOfLayersToPaper()
{
  this->SetNumberOfLayers(vtkSurfaceSplatRasterizer::PaperLayers);
}

//------------------------------------------------------------------------------
int vtkSurfaceSplatMapper::GetNumberOfLayers()
{
  return this->Rasterizer->GetNumberOfLayers();
}

//------------------------------------------------------------------------------
int vtkSurfaceSplatMapper::GetLastNumberOfLayers()
{
  return this->LastBackend == vtkSplatBackend::OPENGL
    ? this->OpenGLRasterizer->GetLastNumberOfLayers()
    : this->Rasterizer->GetLastNumberOfLayers();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::SetEdgeAntialiasing(bool antialiasing)
{
  if (antialiasing != this->Rasterizer->GetEdgeAntialiasing())
  {
    this->Rasterizer->SetEdgeAntialiasing(antialiasing);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
bool vtkSurfaceSplatMapper::GetEdgeAntialiasing()
{
  return this->Rasterizer->GetEdgeAntialiasing();
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceSplatMapper::GetNumberOfRenderedSplats()
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1 : this->Rasterizer->GetSplattedCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceSplatMapper::GetNumberOfMergedSplats()
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1 : this->Rasterizer->GetMergedCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceSplatMapper::GetNumberOfCulledSplats()
{
  if (this->LastBackend == vtkSplatBackend::OPENGL)
  {
    return -1;
  }
  return this->Rasterizer->GetFrustumCulledCount() + this->Rasterizer->GetBackfaceCulledCount() +
    this->Rasterizer->GetNegligibleCount() + this->Rasterizer->GetHiddenCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceSplatMapper::GetNumberOfFrustumCulledSplats()
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1 : this->Rasterizer->GetFrustumCulledCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceSplatMapper::GetNumberOfBackfaceCulledSplats()
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1 : this->Rasterizer->GetBackfaceCulledCount();
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfaceSplatMapper::GetNumberOfNegligibleSplats()
{
  return this->LastBackend == vtkSplatBackend::OPENGL ? -1 : this->Rasterizer->GetNegligibleCount();
}

//------------------------------------------------------------------------------
bool vtkSurfaceSplatMapper::UpdateSurfels(vtkActor* actor)
{
  vtkPolyData* input = this->GetInput();
  vtkProperty* property = actor->GetProperty();
  const vtkMTimeType changed = std::max(
    { input->GetMTime(), this->GetMTime(), property->GetMTime(), this->LookupTable
        ? this->LookupTable->GetMTime()
        : vtkMTimeType(0) });
  SurfelArrays& s = *this->Surfels;
  if (s.BuildTime.GetMTime() > changed && s.Property == property)
  {
    return true;
  }

  vtkPointData* pointData = input->GetPointData();
  auto namedArray = [pointData](const char* name, int components) -> vtkDataArray*
  {
    vtkDataArray* array = name ? pointData->GetArray(name) : nullptr;
    return array && array->GetNumberOfComponents() == components ? array : nullptr;
  };
  const bool differential = this->Primitive == DIFFERENTIAL_POINTS;
  vtkDataArray* axis0 = namedArray(
    differential ? this->PrincipalDirectionUArrayName : this->TangentAxis0ArrayName, 3);
  vtkDataArray* axis1 = namedArray(
    differential ? this->PrincipalDirectionVArrayName : this->TangentAxis1ArrayName, 3);
  vtkDataArray* curvatures =
    differential ? namedArray(this->PrincipalCurvaturesArrayName, 2) : nullptr;
  vtkDataArray* extents = differential ? namedArray(this->ExtentsArrayName, 2) : nullptr;
  if (differential && !(axis0 && axis1 && curvatures && extents))
  {
    auto name = [](const char* n) { return n ? n : "(none)"; };
    vtkErrorMacro("Differential points need the point-data arrays '"
      << name(this->PrincipalDirectionUArrayName) << "' and '"
      << name(this->PrincipalDirectionVArrayName) << "' (3 components), '"
      << name(this->PrincipalCurvaturesArrayName) << "' and '" << name(this->ExtentsArrayName)
      << "' (2 components); vtkDifferentialPointGenerator makes them.");
    return false;
  }
  if (!axis0 || !axis1)
  {
    axis0 = axis1 = nullptr;
  }
  vtkDataArray* normals = pointData->GetNormals();
  if (normals && normals->GetNumberOfComponents() != 3)
  {
    normals = nullptr;
  }
  if (!normals && !axis0)
  {
    vtkErrorMacro("vtkSurfaceSplatMapper needs point normals (3 components) or tangent axes on "
                  "its input; vtkSurfelGenerator or vtkPolyDataNormals compute normals.");
    return false;
  }
  vtkDataArray* radii =
    this->RadiusArrayName ? input->GetPointData()->GetArray(this->RadiusArrayName) : nullptr;
  if (radii && radii->GetNumberOfComponents() != 1)
  {
    vtkWarningMacro("Radius array '" << this->RadiusArrayName
                                     << "' has several components; using the global Radius.");
    radii = nullptr;
  }
  vtkDataArray* opacities =
    this->OpacityArrayName ? pointData->GetArray(this->OpacityArrayName) : nullptr;
  if (opacities && opacities->GetNumberOfComponents() != 1)
  {
    vtkWarningMacro("Opacity array '" << this->OpacityArrayName
                                      << "' has several components; it is ignored.");
    opacities = nullptr;
  }
  const double actorOpacity = property->GetOpacity();
  int cellFlag = 0;
  vtkUnsignedCharArray* scalarColors = this->MapScalars(input, 1.0, cellFlag);
  if (scalarColors && cellFlag != 0)
  {
    vtkWarningMacro("Splats are points: cell scalars are ignored; color by point data instead.");
    scalarColors = nullptr;
  }
  s.ColorsFromScalars = scalarColors != nullptr;
  const double* diffuseColor = property->GetDiffuseColor();

  const vtkIdType n = input->GetNumberOfPoints();
  s.Positions.clear();
  s.Normals.clear();
  s.Axes0.clear();
  s.Axes1.clear();
  s.Colors.clear();
  s.Opacities.clear();
  s.Curvatures.clear();
  s.PointIds.clear();
  bool translucent = false;
  for (auto* v : { &s.Normals, &s.Axes0, &s.Axes1, &s.Colors })
  {
    v->reserve(3 * n);
  }
  s.Positions.reserve(3 * n);
  // Reserved, not grown: growing copies the array into one up to twice as large, a peak of up
  // to three times its size.
  s.Opacities.reserve(n);
  s.Curvatures.reserve(differential ? 2 * n : 0);
  vtkIdType skipped = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    glm::dvec3 normal(0.0), t0, t1;
    bool valid = IsFinite(p, 3);
    double curvature[2] = { 0.0, 0.0 };
    if (axis0)
    {
      axis0->GetTuple(i, &t0.x);
      axis1->GetTuple(i, &t1.x);
      if (differential)
      {
        // Principal directions scaled by the rectangle's half-widths.
        double extent[2];
        extents->GetTuple(i, extent);
        curvatures->GetTuple(i, curvature);
        valid = valid && extent[0] > 0.0 && extent[1] > 0.0 && IsFinite(extent, 2) &&
          IsFinite(curvature, 2);
        t0 = Unit(t0) * extent[0];
        t1 = Unit(t1) * extent[1];
      }
      const glm::dvec3 cross = glm::cross(Unit(t0), Unit(t1));
      valid = valid && IsFinite(&t0.x, 3) && IsFinite(&t1.x, 3) && glm::length(cross) > 0.0;
      if (normals)
      {
        normals->GetTuple(i, &normal.x);
      }
      else
      {
        normal = cross;
      }
    }
    else
    {
      normals->GetTuple(i, &normal.x);
    }
    const glm::dvec3 unitNormal = Unit(normal);
    valid = valid && IsFinite(&normal.x, 3) && unitNormal != glm::dvec3(0.0);
    if (valid && !axis0)
    {
      const double radius = radii ? radii->GetComponent(i, 0) : this->Radius;
      valid = radius > 0.0 && std::isfinite(radius);
      splat::TangentFrame(unitNormal, t0, t1);
      t0 *= radius;
      t1 *= radius;
    }
    if (!valid)
    {
      if (skipped++ == 0)
      {
        // The first skipped point: the ids stop being the surfels' indices.
        s.PointIds.resize(s.Normals.size() / 3);
        std::iota(s.PointIds.begin(), s.PointIds.end(), vtkIdType(0));
        s.PointIds.reserve(n);
      }
      continue;
    }
    unsigned char rgba[4] = { 0, 0, 0, 255 };
    if (scalarColors)
    {
      scalarColors->GetTypedTuple(i, rgba);
    }
    // NaN or out-of-range opacities are clamped: an invalid opacity must not skip a point.
    const double pointOpacity = opacities ? opacities->GetComponent(i, 0) : 1.0;
    const double opacity = actorOpacity * (rgba[3] / 255.0) *
      (std::isnan(pointOpacity) ? 1.0 : std::min(std::max(pointOpacity, 0.0), 1.0));
    s.Opacities.push_back(static_cast<float>(opacity));
    if (skipped > 0)
    {
      s.PointIds.push_back(i);
    }
    if (differential)
    {
      s.Curvatures.push_back(static_cast<float>(curvature[0]));
      s.Curvatures.push_back(static_cast<float>(curvature[1]));
    }
    translucent = translucent || opacity < 1.0;
    for (int c = 0; c < 3; ++c)
    {
      s.Positions.push_back(p[c]);
      s.Normals.push_back(static_cast<float>(unitNormal[c]));
      s.Axes0.push_back(static_cast<float>(t0[c]));
      s.Axes1.push_back(static_cast<float>(t1[c]));
      s.Colors.push_back(
        scalarColors ? rgba[c] / 255.0f : static_cast<float>(diffuseColor[c]));
    }
  }
  if (!translucent)
  {
    // Freed, not only cleared: an opaque input keeps no opacities.
    std::vector<float>().swap(s.Opacities);
  }
  this->NumberOfSkippedPoints = skipped;
  if (skipped > 0)
  {
    vtkWarningMacro(<< skipped << " of " << n
                    << " points skipped: non-finite position, normal, radius, axis or "
                       "curvature, zero normal, non-positive radius or extent, or parallel "
                       "axes.");
  }
  s.Property = property;
  s.BuildTime.Modified();
  return true;
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::RenderPiece(vtkRenderer* ren, vtkActor* actor)
{
  const auto start = std::chrono::steady_clock::now();
  vtkPolyData* input = this->GetInput();
  if (!input)
  {
    vtkErrorMacro("No input.");
    return;
  }
  this->InvokeEvent(vtkCommand::StartEvent, nullptr);
  if (!this->Static)
  {
    this->GetInputAlgorithm()->Update();
  }
  this->InvokeEvent(vtkCommand::EndEvent, nullptr);
  input = this->GetInput();
  if (!input || input->GetNumberOfPoints() == 0 || !this->UpdateSurfels(actor))
  {
    return;
  }

  vtkProperty* property = actor->GetProperty();
  this->NumberOfSplats = static_cast<vtkIdType>(this->Surfels->Normals.size() / 3);
  // Both backends read the settings from the CPU rasterizer; it has no approximate filter.
  this->Rasterizer->SetFilter(this->FilterMode == APPROXIMATE
      ? splat::KernelFilter::EWA
      : static_cast<splat::KernelFilter>(this->FilterMode));
  this->Rasterizer->SetBackfaceCulling(property->GetBackfaceCulling());

  // The automatic low-pass of one color is a pixel's box filter, minified surfels included;
  // differential points, whose rectangles need not overlap, keep the paper's where minified.
  const bool boxFilter =
    this->MagnifiedLowPassVariance == 0.0 && !this->Surfels->ColorsFromScalars;
  this->ChooseCoverage(boxFilter);
  this->Rasterizer->SetCutoff(this->LastCutoff);
  this->Rasterizer->SetCoverageThreshold(this->LastCoverageThreshold);
  // Colors that change from splat to splat keep the paper's cutoff where the low-pass matters.
  this->Rasterizer->SetAntialiasingCutoff(
    this->Cutoff == 0.0 && this->Primitive == SURFELS && this->Surfels->ColorsFromScalars
      ? 1.0
      : 0.0);
  this->LastMagnifiedLowPassVariance = this->MagnifiedLowPassVariance > 0.0
    ? this->MagnifiedLowPassVariance
    : boxFilter ? splat::BoxFilterVariance : 1.0;
  this->Rasterizer->SetMagnifiedLowPassVariance(this->LastMagnifiedLowPassVariance);
  this->LastMinifiedLowPassVariance =
    boxFilter && this->Primitive == SURFELS ? splat::BoxFilterVariance : 1.0;
  this->Rasterizer->SetMinifiedLowPassVariance(this->LastMinifiedLowPassVariance);

  this->Compositor->MoveGraphicsResources(ren, this);
  // Picking draws with OpenGL whatever the backend: the selector reads the framebuffer.
  if (vtkHardwareSelector* selector = ren->GetSelector())
  {
    this->RenderSelection(ren, actor, selector);
    return;
  }

  const vtkSurfaceSplatRasterizer::Camera view = ViewOf(ren, actor);
  const glm::dmat4 worldToEye = ToGlm(ren->GetActiveCamera()->GetModelViewTransformMatrix());

  this->LastBackend = vtkSplatBackend::Resolve(this->Backend, ren->GetRenderWindow());
  const std::vector<splat::Light> lights =
    property->GetLighting() ? splat::EyeLights(ren, worldToEye) : std::vector<splat::Light>();
  const splat::Material material = MaterialOf(property, this->Surfels->ColorsFromScalars);
  // Translucent splats behind opaque geometry drawn before them must be dropped fragment by
  // fragment, not only where the nearest one is hidden: they need the scene's depth.
  const bool translucent = !this->Surfels->Opacities.empty();
  std::vector<float> sceneDepths;
  if (translucent)
  {
    this->Compositor->ReadDepths(ren, sceneDepths);
  }
  using Blending = vtkOpenGLImageDepthCompositor::Blending;
  const Blending blending = !translucent ? Blending::Opaque
    : InOrderIndependentPass(actor)      ? Blending::OrderIndependent
                                         : Blending::Translucent;
  if (this->LastBackend == vtkSplatBackend::OPENGL)
  {
    this->OpenGLRasterizer->SetApproximateFilter(this->FilterMode == APPROXIMATE);
    this->OpenGLRasterizer->SetSurfels(
      this->Surfels->View(), this->Surfels->BuildTime.GetMTime());
    this->OpenGLRasterizer->Render(ren, view, lights, material, this->Rasterizer, sceneDepths);
    this->Compositor->DrawTextures(ren, this->OpenGLRasterizer->GetColorTexture(),
      this->OpenGLRasterizer->GetDepthTexture(), blending);
  }
  else
  {
    vtkSurfaceSplatRasterizer::Surfels surfels = this->Surfels->View();
    if (this->LevelOfDetail && !translucent && this->Primitive == SURFELS &&
      this->Rasterizer->GetFilter() == splat::KernelFilter::EWA &&
      this->Rasterizer->GetMinifiedVariance() > 0.0)
    {
      surfels.Hierarchy = this->Surfels->UpdateHierarchy();
    }
    this->Rasterizer->SetSceneDepths(std::move(sceneDepths));
    this->Rasterizer->Render(surfels, view, lights, material);
    this->Compositor->DrawRegion(ren, view.Viewport.x, view.Viewport.y,
      this->Rasterizer->GetColors().data(), this->Rasterizer->GetDepths().data(),
      this->Rasterizer->GetCoveredRegion(), blending);
  }

  this->LastRenderTimeInMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::RenderSelection(
  vtkRenderer* ren, vtkActor* actor, vtkHardwareSelector* selector)
{
  std::vector<vtkIdType> identity;
  if (this->Surfels->PointIds.empty())
  {
    identity.resize(this->Surfels->Normals.size() / 3);
    std::iota(identity.begin(), identity.end(), vtkIdType(0));
  }
  const std::vector<vtkIdType>& pointIds =
    identity.empty() ? this->Surfels->PointIds : identity;
  selector->BeginRenderProp();
  if (selector->GetCurrentPass() == vtkHardwareSelector::COMPOSITE_INDEX_PASS)
  {
    selector->RenderCompositeIndex(1);
  }
  if (!pointIds.empty())
  {
    // The selector needs the largest id to know whether the high 24 bits are needed.
    selector->UpdateMaximumPointId(pointIds.back());
    selector->UpdateMaximumCellId(pointIds.back());
  }
  this->OpenGLRasterizer->SetApproximateFilter(this->FilterMode == APPROXIMATE);
  this->OpenGLRasterizer->SetSurfels(this->Surfels->View(), this->Surfels->BuildTime.GetMTime());
  this->OpenGLRasterizer->RenderSelection(
    ren, selector, ViewOf(ren, actor), this->Rasterizer, pointIds);
  selector->EndRenderProp();
}

//------------------------------------------------------------------------------
double vtkSurfaceSplatMapper::LargestSurfelRadius()
{
  vtkPointData* pointData = this->GetInput()->GetPointData();
  double radius = this->Radius;
  vtkDataArray* radii = this->RadiusArrayName ? pointData->GetArray(this->RadiusArrayName) : nullptr;
  if (radii && radii->GetNumberOfComponents() == 1)
  {
    radius = std::max(radii->GetFiniteRange(0)[1], 0.0);
  }
  for (const char* name : { this->TangentAxis0ArrayName, this->TangentAxis1ArrayName })
  {
    vtkDataArray* axis = name ? pointData->GetArray(name) : nullptr;
    if (axis && axis->GetNumberOfComponents() == 3)
    {
      const double norm = axis->GetMaxNorm();
      radius = std::isfinite(norm) ? std::max(radius, norm) : radius;
    }
  }
  return radius;
}

//------------------------------------------------------------------------------
double vtkSurfaceSplatMapper::LargestDifferentialExtent()
{
  vtkDataArray* extents =
    this->ExtentsArrayName ? this->GetInput()->GetPointData()->GetArray(this->ExtentsArrayName)
                           : nullptr;
  if (!extents || extents->GetNumberOfComponents() != 2)
  {
    return 0.0;
  }
  // The filtered footprint reaches sqrt(2) half-widths along each direction.
  const double norm = std::sqrt(2.0) * extents->GetMaxNorm();
  return std::isfinite(norm) ? norm : 0.0;
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::ComputeBounds()
{
  // Finite ranges only: a NaN or Inf point is skipped at render time and must not spoil the
  // camera reset and the clipping range either.
  vtkMath::UninitializeBounds(this->Bounds);
  vtkPolyData* input = this->GetInput();
  if (!input || !input->GetPoints() || input->GetNumberOfPoints() == 0)
  {
    return;
  }
  vtkDataArray* points = input->GetPoints()->GetData();
  const double radius = this->Primitive == DIFFERENTIAL_POINTS ? this->LargestDifferentialExtent()
                                                               : this->LargestSurfelRadius();
  for (int axis = 0; axis < 3; ++axis)
  {
    double range[2];
    points->GetFiniteRange(range, axis);
    if (!(range[0] <= range[1]))
    {
      vtkMath::UninitializeBounds(this->Bounds);
      return;
    }
    this->Bounds[2 * axis] = range[0] - radius;
    this->Bounds[2 * axis + 1] = range[1] + radius;
  }
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Compositor->ReleaseGraphicsResources(window);
  this->OpenGLRasterizer->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "RadiusArrayName: " << (this->RadiusArrayName ? this->RadiusArrayName : "(none)")
     << "\n";
  os << indent << "OpacityArrayName: " << (this->OpacityArrayName ? this->OpacityArrayName : "(none)")
     << "\n";
  os << indent << "NumberOfLayers: " << this->Rasterizer->GetNumberOfLayers() << "\n";
  os << indent << "LastNumberOfLayers: " << this->GetLastNumberOfLayers() << "\n";
  os << indent << "EdgeAntialiasing: " << this->Rasterizer->GetEdgeAntialiasing() << "\n";
  os << indent << "CoverageThreshold: " << this->CoverageThreshold << "\n";
  os << indent << "LastCoverageThreshold: " << this->LastCoverageThreshold << "\n";
  os << indent << "TangentAxis0ArrayName: "
     << (this->TangentAxis0ArrayName ? this->TangentAxis0ArrayName : "(none)") << "\n";
  os << indent << "TangentAxis1ArrayName: "
     << (this->TangentAxis1ArrayName ? this->TangentAxis1ArrayName : "(none)") << "\n";
  os << indent << "FilterMode: " << this->FilterMode << "\n";
  os << indent << "Primitive: " << (this->Primitive == SURFELS ? "Surfels" : "DifferentialPoints")
     << "\n";
  for (const auto& named : { std::make_pair("PrincipalDirectionUArrayName",
                               this->PrincipalDirectionUArrayName),
         std::make_pair("PrincipalDirectionVArrayName", this->PrincipalDirectionVArrayName),
         std::make_pair("PrincipalCurvaturesArrayName", this->PrincipalCurvaturesArrayName),
         std::make_pair("ExtentsArrayName", this->ExtentsArrayName) })
  {
    os << indent << named.first << ": " << (named.second ? named.second : "(none)") << "\n";
  }
  os << indent << "Backend: " << vtkSplatBackend::GetBackendAsString(this->Backend) << "\n";
  os << indent << "LastBackend: " << vtkSplatBackend::GetBackendAsString(this->LastBackend)
     << "\n";
  os << indent << "Cutoff: " << this->Cutoff << (this->Cutoff > 0.0 ? "\n" : " (automatic)\n");
  os << indent << "LastCutoff: " << this->LastCutoff << "\n";
  os << indent << "MagnifiedLowPassVariance: " << this->MagnifiedLowPassVariance
     << (this->MagnifiedLowPassVariance > 0.0 ? "\n" : " (automatic)\n");
  os << indent << "LastMagnifiedLowPassVariance: " << this->LastMagnifiedLowPassVariance << "\n";
  os << indent << "LastMinifiedLowPassVariance: " << this->LastMinifiedLowPassVariance << "\n";
  os << indent << "MinifiedVariance: " << this->Rasterizer->GetMinifiedVariance() << "\n";
  os << indent << "LevelOfDetail: " << this->LevelOfDetail << "\n";
  os << indent << "DepthThreshold: " << this->Rasterizer->GetDepthThreshold() << "\n";
  os << indent << "NumberOfSplats: " << this->NumberOfSplats << "\n";
  os << indent << "NumberOfSkippedPoints: " << this->NumberOfSkippedPoints << "\n";
  os << indent << "LastRenderTimeInMilliseconds: " << this->LastRenderTimeInMilliseconds << "\n";
}
