// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenGLVolumeSplatRasterizer.h"

#include "SplatCaptureKernel.h"
#include "SplatOpenGLUtilities.h"
#include "SplatSphericalHarmonics.h"
#include "SplatVolumeKernel.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkSplatSphericalHarmonics.h"
#include "vtkVolumeSplatFS.h"
#include "vtkVolumeSplatMergeFS.h"
#include "vtkVolumeSplatVS.h"
#include "vtkVolumeSplatWeightsFS.h"

#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

vtkStandardNewMacro(vtkOpenGLVolumeSplatRasterizer);

namespace
{
using Rasterizer = vtkVolumeSplatRasterizer;
constexpr int DepthList = Rasterizer::DepthList;

using splat::SetNearest;

// The volume vertex shader with the lighting and spherical-harmonics code put in.
std::string VolumeVertexShader()
{
  std::string source = splat::WithLighting(vtkVolumeSplatVS);
  vtkShaderProgram::Substitute(
    source, "//VTK::SplatSphericalHarmonics::Dec", vtkSplatSphericalHarmonics);
  return source;
}

// An open (strict) or closed half-plane A x + B y + C > 0 (>= 0) of pixel positions.
struct HalfPlane
{
  glm::dvec3 Coefficients;
  bool Strict;
};

// Whether some pixel center (i + 0.5, j + 0.5) of a width x height viewport lies in every
// half-plane: row by row, the half-planes bound the row's pixel indices.
bool AnyPixel(const std::vector<HalfPlane>& planes, int width, int height)
{
  for (int j = 0; j < height; ++j)
  {
    const double y = j + 0.5;
    double first = 0.0;
    double last = width - 1.0;
    for (const HalfPlane& plane : planes)
    {
      const double a = plane.Coefficients.x;
      const double c = plane.Coefficients.y * y + plane.Coefficients.z;
      if (a == 0.0)
      {
        if (!(plane.Strict ? c > 0.0 : c >= 0.0))
        {
          last = -1.0;
        }
        continue;
      }
      // Pixel i is in the half-plane where a (i + 0.5) + c > 0 (>= 0).
      const double bound = -c / a - 0.5;
      if (a > 0.0)
      {
        first = std::max(first, plane.Strict ? std::floor(bound) + 1.0 : std::ceil(bound));
      }
      else
      {
        last = std::min(last, plane.Strict ? std::ceil(bound) - 1.0 : std::floor(bound));
      }
    }
    if (first <= last)
    {
      return true;
    }
  }
  return false;
}

// Which lists, in which directions, some pixel of the frame uses (vtkVolumeSplatRasterizer's
// step 1, as regions of the pixel plane): the ray direction d(x, y) = listRays (x, y, 1) is
// affine in the pixel position, so each list's region for one sign of d_a is an intersection
// of half-planes. needed[list][0] ascending (d_a > 0), needed[list][1] descending.
std::array<std::array<bool, 2>, 3> NeededLists(
  const glm::dmat3& listRays, int mode, double h, int centralList, int width, int height)
{
  // d_a as the coefficients of (x, y, 1).
  auto component = [&listRays](int axis)
  { return glm::dvec3(listRays[0][axis], listRays[1][axis], listRays[2][axis]); };
  std::array<std::array<bool, 2>, 3> needed{};
  for (int list = 0; list < 3; ++list)
  {
    if (mode == Rasterizer::SINGLE_AXIS && list != centralList)
    {
      continue;
    }
    for (int direction = 0; direction < 2; ++direction)
    {
      const glm::dvec3 da = (direction == 0 ? 1.0 : -1.0) * component(list);
      std::vector<HalfPlane> planes = { { da, true } }; // |d_a| = s d_a > 0
      for (int other = 0; other < 3; ++other)
      {
        if (other == list || mode == Rasterizer::SINGLE_AXIS)
        {
          continue;
        }
        // BLENDED: |d_a| > h |d_b|. CLIPPED: a is the dominant axis, the first of the largest.
        const double scale = mode == Rasterizer::BLENDED ? h : 1.0;
        const bool strict = mode == Rasterizer::BLENDED || other < list;
        planes.push_back({ da - scale * component(other), strict });
        planes.push_back({ da + scale * component(other), strict });
      }
      needed[list][direction] = AnyPixel(planes, width, height);
    }
  }
  return needed;
}
}

struct vtkOpenGLVolumeSplatRasterizer::Internals
{
  vtkNew<vtkOpenGLBufferObject> KernelBuffer;
  vtkNew<vtkTextureObject> KernelTexture;
  // Spherical-harmonic coefficients of degree 1 and more, HarmonicsStride RGBA16F texels per
  // kernel (none for degree 0: the kernels' colors are then the degree-0 colors).
  vtkNew<vtkOpenGLBufferObject> HarmonicsBuffer;
  vtkNew<vtkTextureObject> HarmonicsTexture;
  int HarmonicsDegree = 0;
  int HarmonicsStride = 0;
  std::array<vtkNew<vtkOpenGLBufferObject>, 4> OrderBuffers;
  std::array<vtkNew<vtkTextureObject>, 4> OrderTextures;
  std::array<vtkMTimeType, 4> OrderVersions{};
  vtkNew<vtkOpenGLVertexArrayObject> Array; // no attributes: everything comes from the buffers
  vtkMTimeType Version = 0;
  vtkMTimeType KernelTextureVersion = 0; // the upload the kernel texture refers to
  int KernelStride = 2;
  bool SharedCovariance = true;
  bool Shaded = false;
  GLsizei Count = 0;
  // What the shaders need of the kernels besides the buffers.
  Rasterizer::Kernels Input;
  std::vector<glm::dvec3> Positions; // for the per-frame depth sort
  glm::dvec3 Shift{ 0.0 };

  vtkNew<vtkTextureObject> SceneDepth;
  vtkNew<vtkTextureObject> PixelWeights;
  std::array<vtkNew<vtkTextureObject>, 3> ListColors;
  vtkNew<vtkTextureObject> Result;
  vtkNew<vtkTextureObject> ZeroDepth;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> Weights;
  std::unique_ptr<vtkOpenGLQuadHelper> Merge;
  int Width = 0;
  int Height = 0;

  void Allocate(vtkOpenGLRenderWindow* window, int width, int height);
  /// A list's kernel indices into its texture buffer.
  void UploadOrder(vtkOpenGLRenderWindow* window, int list, const std::vector<vtkIdType>& order)
  {
    this->UploadIndices(window, list, std::vector<std::int32_t>(order.begin(), order.end()));
  }
  void UploadIndices(vtkOpenGLRenderWindow* window, int list, std::vector<std::int32_t> indices);
  /// Draws into `target` with the bound framebuffer, after clearing it.
  void Target(vtkOpenGLState* state, vtkTextureObject* target);
};

//------------------------------------------------------------------------------
void vtkOpenGLVolumeSplatRasterizer::Internals::Allocate(
  vtkOpenGLRenderWindow* window, int width, int height)
{
  if (width == this->Width && height == this->Height && this->Result->GetHandle() != 0)
  {
    return;
  }
  for (vtkTextureObject* color : { this->PixelWeights.Get(), this->ListColors[0].Get(),
         this->ListColors[1].Get(), this->ListColors[2].Get(), this->Result.Get() })
  {
    SetNearest(color, window);
    color->Allocate2D(width, height, 4, VTK_FLOAT);
  }
  SetNearest(this->ZeroDepth, window);
  std::vector<float> zeros(static_cast<std::size_t>(width) * height, 0.0f);
  this->ZeroDepth->Create2DFromRaw(width, height, 1, VTK_FLOAT, zeros.data());
  this->Framebuffer->SetContext(window);
  this->Width = width;
  this->Height = height;
}

//------------------------------------------------------------------------------
void vtkOpenGLVolumeSplatRasterizer::Internals::UploadIndices(
  vtkOpenGLRenderWindow* window, int list, std::vector<std::int32_t> indices)
{
  // At least one entry: an empty buffer cannot back a texture.
  if (indices.empty())
  {
    indices.push_back(0);
  }
  this->OrderBuffers[list]->Upload(indices, vtkOpenGLBufferObject::TextureBuffer);
  vtkTextureObject* texture = this->OrderTextures[list];
  texture->SetContext(window);
  texture->SetInternalFormat(GL_R32I);
  texture->CreateTextureBuffer(
    static_cast<unsigned int>(indices.size()), 1, VTK_INT, this->OrderBuffers[list]);
}

//------------------------------------------------------------------------------
void vtkOpenGLVolumeSplatRasterizer::Internals::Target(
  vtkOpenGLState* state, vtkTextureObject* target)
{
  this->Framebuffer->Bind();
  this->Framebuffer->AddColorAttachment(0, target);
  this->Framebuffer->ActivateDrawBuffers(1);
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
}

//------------------------------------------------------------------------------
vtkOpenGLVolumeSplatRasterizer::vtkOpenGLVolumeSplatRasterizer()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkOpenGLVolumeSplatRasterizer::~vtkOpenGLVolumeSplatRasterizer() = default;

//------------------------------------------------------------------------------
void vtkOpenGLVolumeSplatRasterizer::SetKernels(
  const vtkVolumeSplatRasterizer::Kernels& kernels, vtkMTimeType version)
{
  Internals& internal = *this->Internal;
  if (version == internal.Version && internal.KernelBuffer->GetHandle() != 0)
  {
    return;
  }
  const std::size_t n = kernels.Count;
  internal.Positions.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = kernels.Positions + 3 * i;
    internal.Positions[i] = glm::dvec3(p[0], p[1], p[2]);
  }
  internal.Shift = splat::BoundsCenter(kernels.Positions, n);
  const int normalTexel = kernels.Covariances ? 4 : 2;
  internal.KernelStride = normalTexel + (kernels.Normals ? 1 : 0);
  const std::size_t stride = 4 * internal.KernelStride;
  // At least one texel: an empty buffer cannot back a texture.
  std::vector<float> data(std::max<std::size_t>(stride * n, 4), 0.0f);
  for (std::size_t i = 0; i < n; ++i)
  {
    float* d = &data[stride * i];
    for (int c = 0; c < 3; ++c)
    {
      d[c] = static_cast<float>(internal.Positions[i][c] - internal.Shift[c]);
      d[4 + c] = kernels.Colors[3 * i + c];
    }
    d[3] = kernels.Strengths[i];
    if (kernels.Covariances)
    {
      std::copy_n(kernels.Covariances + 6 * i, 6, d + 8);
    }
    if (kernels.Normals)
    {
      std::copy_n(kernels.Normals + 3 * i, 3, d + 4 * normalTexel);
    }
  }
  internal.KernelBuffer->Upload(data, vtkOpenGLBufferObject::TextureBuffer);
  internal.HarmonicsDegree =
    kernels.SphericalHarmonics && n > 0 ? kernels.SphericalHarmonicsDegree : 0;
  internal.HarmonicsStride = splat::SphericalHarmonicsCoefficients(internal.HarmonicsDegree);
  if (internal.HarmonicsDegree > 0)
  {
    // Half floats, one RGB coefficient per texel: the mapper keeps them within the half range.
    const vtkIdType coefficients = static_cast<vtkIdType>(n) * internal.HarmonicsStride;
    std::vector<std::uint16_t> halves(4 * coefficients, 0);
    vtkSMPTools::For(0, coefficients,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            halves[4 * i + c] = glm::packHalf1x16(kernels.SphericalHarmonics[3 * i + c]);
          }
        }
      });
    internal.HarmonicsBuffer->Upload(halves, vtkOpenGLBufferObject::TextureBuffer);
  }
  internal.Input = kernels;
  internal.Input.Positions = nullptr; // not kept: the arrays may go
  internal.Input.Covariances = nullptr;
  internal.Input.Colors = nullptr;
  internal.Input.Strengths = nullptr;
  internal.Input.GridIds = nullptr;
  internal.SharedCovariance = kernels.Covariances == nullptr;
  internal.Shaded = kernels.Normals != nullptr;
  internal.Input.Normals = nullptr;
  internal.Input.SphericalHarmonics = nullptr;
  internal.Count = static_cast<GLsizei>(n);
  internal.Version = version;
  internal.OrderVersions.fill(0);
}

//------------------------------------------------------------------------------
void vtkOpenGLVolumeSplatRasterizer::Render(vtkRenderer* renderer,
  const vtkVolumeSplatRasterizer::Camera& camera, vtkVolumeSplatRasterizer* settings,
  const std::vector<float>& sceneDepths)
{
  Internals& internal = *this->Internal;
  this->Traversed.fill(false);
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  const int width = camera.Viewport.x;
  const int height = camera.Viewport.y;
  if (!window || width <= 0 || height <= 0)
  {
    return;
  }
  GLint largestBuffer = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &largestBuffer);
  const int largestStride = std::max(internal.KernelStride, internal.HarmonicsStride);
  if (static_cast<double>(internal.Count) * largestStride > largestBuffer)
  {
    vtkErrorMacro(<< internal.Count << " kernels exceed this OpenGL's texture buffers ("
                  << largestBuffer << " texels); use the CPU backend.");
    return;
  }
  const int mode = settings->GetOrderingMode();
  const glm::dvec2 viewport(width, height);

  // GPU times of the steps, for vtkRenderWindow::GetRenderTimer() (when its logging is on).
  // Timer queries bracket GPU work only: the CPU's depth sort is not in "orders".
  vtkRenderTimerLog* timer = window->GetRenderTimer();
  VTK_SCOPED_RENDER_EVENT2("vtkOpenGLVolumeSplatRasterizer orders", timer, orderEvent);

  // 1. The lists the frame needs, and their orders on the GPU.
  const splat::PixelRays rays = splat::MakePixelRays(camera.EyeToClip, viewport);
  const glm::dmat3 eyeToList =
    glm::transpose(internal.Input.ListFrame) * glm::inverse(glm::dmat3(camera.ModelToEye));
  const glm::dmat3 listRays = eyeToList * rays.Direction;
  const glm::dvec3 central = listRays * glm::dvec3(0.5 * width, 0.5 * height, 1.0);
  const glm::dvec3 a = glm::abs(central);
  const int centralList = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  std::array<std::array<bool, 2>, 3> needed{};
  if (mode == Rasterizer::DEPTH_SORTED)
  {
    needed[0][0] = true; // drawn into the first list buffer
    this->Traversed[DepthList] = true;
    // Front to back by the eye depth of the centers, as the CPU sorts its kept kernels: in
    // single precision, equal depths in input order. Keys of depth and index sort in parallel
    // (at 1 M kernels, std::stable_sort on one core took longer than the GPU's drawing).
    const vtkIdType n = static_cast<vtkIdType>(internal.Positions.size());
    const glm::dvec4 depthRow = glm::row(camera.ModelToEye, 2);
    std::vector<std::uint64_t> keys(n);
    vtkSMPTools::For(0, n,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          const float depth =
            static_cast<float>(-glm::dot(depthRow, glm::dvec4(internal.Positions[i], 1.0)));
          keys[i] = splat::DepthOrderKey(depth, static_cast<std::uint32_t>(i));
        }
      });
    vtkSMPTools::Sort(keys.begin(), keys.end());
    // The texture buffer's indices straight from the keys (not through a vtkIdType order and
    // a serial copy).
    std::vector<std::int32_t> order(n);
    vtkSMPTools::For(0, n,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          order[i] = static_cast<std::int32_t>(keys[i] & 0xffffffffu);
        }
      });
    ++this->SortCount;
    internal.UploadIndices(window, DepthList, std::move(order));
  }
  else
  {
    needed = NeededLists(
      listRays, mode, settings->GetBlendThreshold(), centralList, width, height);
    for (int list = 0; list < 3; ++list)
    {
      this->Traversed[list] = needed[list][0] || needed[list][1];
      if (this->Traversed[list] && internal.OrderVersions[list] != internal.Version)
      {
        internal.UploadOrder(window, list, settings->GetList(list));
        internal.OrderVersions[list] = internal.Version;
      }
    }
  }
  if (internal.KernelTextureVersion != internal.Version)
  {
    internal.KernelTexture->SetContext(window);
    internal.KernelTexture->SetInternalFormat(GL_RGBA32F);
    internal.KernelTexture->CreateTextureBuffer(
      static_cast<unsigned int>(std::max<GLsizei>(internal.Count, 1) * internal.KernelStride), 4,
      VTK_FLOAT, internal.KernelBuffer);
    if (internal.HarmonicsDegree > 0)
    {
      internal.HarmonicsTexture->SetContext(window);
      internal.HarmonicsTexture->SetInternalFormat(GL_RGBA16F);
      internal.HarmonicsTexture->CreateTextureBuffer(
        static_cast<unsigned int>(internal.Count * internal.HarmonicsStride), 4,
        VTK_UNSIGNED_SHORT, internal.HarmonicsBuffer);
    }
    internal.KernelTextureVersion = internal.Version;
  }

  orderEvent.Stop();

  vtkOpenGLState* state = window->GetState();
  state->PushFramebufferBindings();
  internal.Allocate(window, width, height);
  vtkOpenGLState::ScopedglViewport viewportScope(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglColorMask colorMask(state);
  vtkOpenGLState::ScopedglClearColor clearColor(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  state->vtkglViewport(0, 0, width, height);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  state->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);

  // 2. Per pixel: the list weights and the opaque scene's eye depth.
  vtkShaderProgram* weights = splat::ReadyQuad(internal.Weights, window, vtkVolumeSplatWeightsFS);
  if (!weights)
  {
    vtkErrorMacro("The volume splatting weights shader did not compile.");
    state->PopFramebufferBindings();
    return;
  }
  const bool sceneTest = sceneDepths.size() == static_cast<std::size_t>(width) * height;
  if (sceneTest)
  {
    const std::vector<float> eyeDepths =
      splat::EyeDepthsOfWindowDepths(glm::inverse(camera.EyeToClip), sceneDepths);
    SetNearest(internal.SceneDepth, window);
    internal.SceneDepth->Create2DFromRaw(
      width, height, 1, VTK_FLOAT, const_cast<float*>(eyeDepths.data()));
    internal.SceneDepth->Activate();
    weights->SetUniformi("sceneDepth", internal.SceneDepth->GetTextureUnit());
  }
  glm::mat3 listRaysF(listRays);
  weights->SetUniformMatrix3x3("listRays", glm::value_ptr(listRaysF));
  weights->SetUniformi("orderingMode", mode);
  weights->SetUniformi("centralList", centralList);
  weights->SetUniformf("blendThreshold", static_cast<float>(settings->GetBlendThreshold()));
  weights->SetUniformi("sceneTest", sceneTest);
  internal.Target(state, internal.PixelWeights);
  VTK_SCOPED_RENDER_EVENT2("weights", timer, weightsEvent);
  internal.Weights->Render();
  weightsEvent.Stop();
  if (sceneTest)
  {
    internal.SceneDepth->Deactivate();
  }

  // 3. Each list into its own buffer, front to back in each direction some pixel needs.
  static const std::string vertexSource = VolumeVertexShader();
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(vertexSource.c_str(), vtkVolumeSplatFS, "");
  if (!program || !program->GetCompiled())
  {
    vtkErrorMacro("The volume splatting shaders did not compile.");
    state->PopFramebufferBindings();
    return;
  }
  // The shift is folded in double precision: the float matrix only holds the offsets between
  // the data and the camera.
  const glm::dmat4 modelToEye = camera.ModelToEye * glm::translate(glm::dmat4(1.0), internal.Shift);
  const glm::mat4 modelToEyeF(modelToEye);
  const glm::mat4 eyeToClipF(camera.EyeToClip);
  const glm::dmat3 linear(camera.ModelToEye);
  const glm::mat3 sharedEyeCovariance(
    linear * internal.Input.SharedCovariance * glm::transpose(linear));
  const float viewportSize[2] = { static_cast<float>(width), static_cast<float>(height) };
  const double cutoff = settings->GetCutoff();
  program->SetUniformMatrix4x4("modelToEye", const_cast<float*>(glm::value_ptr(modelToEyeF)));
  program->SetUniformMatrix4x4("eyeToClip", const_cast<float*>(glm::value_ptr(eyeToClipF)));
  program->SetUniform2f("viewportSize", viewportSize);
  program->SetUniformf("nearDistance",
    static_cast<float>(splat::NearPlaneDistance(camera.EyeToClip)));
  program->SetUniformf(
    "farDistance", static_cast<float>(splat::FarPlaneDistance(camera.EyeToClip)));
  program->SetUniformf("cutoff", static_cast<float>(cutoff));
  program->SetUniformf("compensation", static_cast<float>(splat::TruncationCompensation(cutoff)));
  program->SetUniformi("perspective", rays.Perspective ? 1 : 0);
  program->SetUniformi("peakOpacity", internal.Input.PeakOpacity ? 1 : 0);
  // The rules captures were trained with, where the CPU draws them by
  // vtkGaussianSplatRasterizer.
  const auto filter = static_cast<splat::FootprintFilter>(settings->GetFootprintFilter());
  program->SetUniformi(
    "captureRules", internal.Input.PeakOpacity && mode == Rasterizer::DEPTH_SORTED ? 1 : 0);
  program->SetUniformf("filterVariance", static_cast<float>(splat::FilterVariance(filter)));
  program->SetUniformi("antialiased", filter == splat::FootprintFilter::Antialiased ? 1 : 0);
  program->SetUniformi("bandLimit", filter == splat::FootprintFilter::BandLimit ? 1 : 0);
  program->SetUniformi("sharedCovariance", internal.SharedCovariance ? 1 : 0);
  program->SetUniformMatrix3x3(
    "sharedEyeCovariance", const_cast<float*>(glm::value_ptr(sharedEyeCovariance)));
  program->SetUniformi("shaded", internal.Shaded ? 1 : 0);
  if (internal.Shaded)
  {
    glm::mat3 normalToEye(glm::transpose(glm::inverse(linear)));
    program->SetUniformMatrix3x3("normalToEye", glm::value_ptr(normalToEye));
    program->SetUniformi("twoSidedLighting", settings->GetTwoSidedLighting() ? 1 : 0);
    splat::SetLightingUniforms(
      program, settings->GetLights(), settings->GetMaterial(), camera.EyeToClip);
  }
  program->SetUniformi("kernelStride", internal.KernelStride);
  program->SetUniformi("count", internal.Count);
  internal.KernelTexture->Activate();
  internal.PixelWeights->Activate();
  program->SetUniformi("kernels", internal.KernelTexture->GetTextureUnit());
  const int harmonicsDegree =
    std::min(internal.HarmonicsDegree, settings->GetMaximumSphericalHarmonicsDegree());
  program->SetUniformi("sphericalHarmonicsDegree", harmonicsDegree);
  program->SetUniformi("sphericalHarmonicsStride", internal.HarmonicsStride);
  // Without harmonics the sampler names the kernels' buffer: a sampler of the same type.
  if (harmonicsDegree > 0)
  {
    internal.HarmonicsTexture->Activate();
  }
  program->SetUniformi("sphericalHarmonics",
    (harmonicsDegree > 0 ? internal.HarmonicsTexture : internal.KernelTexture)
      ->GetTextureUnit());
  // The view point in the shifted coordinates of the kernels' positions, or the view axis.
  const glm::dmat4 eyeToModel = glm::inverse(modelToEye);
  const glm::vec3 viewPoint(eyeToModel * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  const glm::vec3 viewAxis(
    glm::normalize(glm::dvec3(eyeToModel * glm::dvec4(0.0, 0.0, -1.0, 0.0))));
  program->SetUniform3f("viewPoint", glm::value_ptr(viewPoint));
  program->SetUniform3f("viewAxis", glm::value_ptr(viewAxis));
  program->SetUniformi("pixelWeights", internal.PixelWeights->GetTextureUnit());
  state->vtkglBlendFuncSeparate(
    GL_ONE_MINUS_DST_ALPHA, GL_ONE, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  for (int list = 0; list < 3; ++list)
  {
    if (!needed[list][0] && !needed[list][1])
    {
      continue;
    }
    vtkTextureObject* order =
      internal.OrderTextures[mode == Rasterizer::DEPTH_SORTED ? DepthList : list];
    state->vtkglDisable(GL_BLEND);
    internal.Target(state, internal.ListColors[list]);
    state->vtkglEnable(GL_BLEND);
    window->GetShaderCache()->ReadyShaderProgram(program);
    internal.Array->Bind();
    order->Activate();
    program->SetUniformi("order", order->GetTextureUnit());
    program->SetUniformi("list", list);
    VTK_SCOPED_RENDER_EVENT("list " << list, timer);
    for (int direction = 0; direction < 2; ++direction)
    {
      if (needed[list][direction] && internal.Count > 0)
      {
        program->SetUniformi("descending", direction);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, internal.Count);
      }
    }
    order->Deactivate();
    internal.Array->Release();
  }
  if (harmonicsDegree > 0)
  {
    internal.HarmonicsTexture->Deactivate();
  }
  internal.KernelTexture->Deactivate();

  // 4. The merge, with the squared weights, into the result.
  state->vtkglDisable(GL_BLEND);
  vtkShaderProgram* merge = splat::ReadyQuad(internal.Merge, window, vtkVolumeSplatMergeFS);
  if (!merge)
  {
    vtkErrorMacro("The volume splatting merge shader did not compile.");
    internal.PixelWeights->Deactivate();
    state->PopFramebufferBindings();
    return;
  }
  merge->SetUniformi("pixelWeights", internal.PixelWeights->GetTextureUnit());
  float traversed[3];
  for (int list = 0; list < 3; ++list)
  {
    const bool drawn = needed[list][0] || needed[list][1];
    traversed[list] = drawn ? 1.0f : 0.0f;
    // Lists not drawn sample the weights instead (never used: their weight is masked).
    vtkTextureObject* source =
      drawn ? internal.ListColors[list].Get() : internal.PixelWeights.Get();
    if (drawn)
    {
      source->Activate();
    }
    const std::string name = "list" + std::to_string(list);
    merge->SetUniformi(name.c_str(), source->GetTextureUnit());
  }
  merge->SetUniform3f("traversed", traversed);
  internal.Target(state, internal.Result);
  VTK_SCOPED_RENDER_EVENT2("merge", timer, mergeEvent);
  internal.Merge->Render();
  mergeEvent.Stop();
  for (int list = 0; list < 3; ++list)
  {
    if (needed[list][0] || needed[list][1])
    {
      internal.ListColors[list]->Deactivate();
    }
  }
  internal.PixelWeights->Deactivate();
  state->PopFramebufferBindings();
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkOpenGLVolumeSplatRasterizer::GetColorTexture()
{
  return this->Internal->Result;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkOpenGLVolumeSplatRasterizer::GetDepthTexture()
{
  return this->Internal->ZeroDepth;
}

//------------------------------------------------------------------------------
bool vtkOpenGLVolumeSplatRasterizer::GetListTraversed(int list) const
{
  return list >= 0 && list <= DepthList && this->Traversed[list];
}

//------------------------------------------------------------------------------
void vtkOpenGLVolumeSplatRasterizer::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& internal = *this->Internal;
  internal.KernelBuffer->ReleaseGraphicsResources();
  internal.KernelTexture->ReleaseGraphicsResources(window);
  internal.HarmonicsBuffer->ReleaseGraphicsResources();
  internal.HarmonicsTexture->ReleaseGraphicsResources(window);
  for (int list = 0; list < 4; ++list)
  {
    internal.OrderBuffers[list]->ReleaseGraphicsResources();
    internal.OrderTextures[list]->ReleaseGraphicsResources(window);
  }
  internal.OrderVersions.fill(0);
  internal.Array->ReleaseGraphicsResources();
  internal.Version = internal.KernelTextureVersion = 0;
  for (vtkTextureObject* texture :
    { internal.SceneDepth.Get(), internal.PixelWeights.Get(), internal.ListColors[0].Get(),
      internal.ListColors[1].Get(), internal.ListColors[2].Get(), internal.Result.Get(),
      internal.ZeroDepth.Get() })
  {
    texture->ReleaseGraphicsResources(window);
  }
  internal.Framebuffer->ReleaseGraphicsResources(window);
  internal.Width = internal.Height = 0;
  for (auto* quad : { &internal.Weights, &internal.Merge })
  {
    if (*quad)
    {
      (*quad)->ReleaseGraphicsResources(window);
      quad->reset();
    }
  }
}

//------------------------------------------------------------------------------
void vtkOpenGLVolumeSplatRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Kernels: " << this->Internal->Count << "\n";
  os << indent << "SphericalHarmonicsDegree: " << this->Internal->HarmonicsDegree << "\n";
  for (int list = 0; list <= DepthList; ++list)
  {
    os << indent << "List " << list << " traversed: " << this->Traversed[list] << "\n";
  }
  os << indent << "SortCount: " << this->SortCount << "\n";
}
