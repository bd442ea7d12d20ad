// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenGLSurfaceSplatRasterizer.h"

#include "SplatOpenGLUtilities.h"
#include "SplatSurfaceFragment.h"
#include "vtkHardwareSelector.h"
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
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTransformFeedback.h"
#include "vtk_glew.h"

#include "vtkSurfaceSplatFS.h"
#include "vtkSurfaceSplatResolveFS.h"
#include "vtkSurfaceSplatSetupVS.h"
#include "vtkSurfaceSplatVS.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <string>

vtkStandardNewMacro(vtkOpenGLSurfaceSplatRasterizer);

namespace
{
// A vertex attribute of floats, in a buffer of such attributes packed one after the other.
struct Attribute
{
  const char* Name;
  int Size;
};

template <std::size_t N>
constexpr int Floats(const std::array<Attribute, N>& attributes)
{
  int floats = 0;
  for (const Attribute& attribute : attributes)
  {
    floats += attribute.Size;
  }
  return floats;
}

// The surfels' attributes: position, two axes, normal, RGBA, and the principal curvatures of
// differential points (0 for surfels).
constexpr std::array<Attribute, 6> SurfelFields = { { { "position", 3 }, { "axis0", 3 },
  { "axis1", 3 }, { "normal", 3 }, { "color", 4 }, { "curvature", 2 } } };
constexpr int SplatStride = Floats(SurfelFields);
// The splat's record: what the setup pass's vertex shader writes per splat (its outputs, in
// this order, captured interleaved) and the strip pass's vertex shader reads per instance
// (vtkSurfaceSplatSetupVS.glsl says what each holds).
constexpr std::array<Attribute, 8> RecordFields = { { { "recordBox", 4 }, { "recordCenter", 4 },
  { "recordConic", 4 }, { "recordPoint", 4 }, { "recordNormal", 4 }, { "recordAxis0", 4 },
  { "recordAxis1", 4 }, { "recordColor", 4 } } };
constexpr std::size_t RecordBytes = Floats(RecordFields) * sizeof(float);
// The setup pass draws with the rasterizer off, but a program needs a fragment shader.
constexpr const char* SetupFS = "//VTK::System::Dec\nvoid main()\n{\n}\n";
constexpr int ApproximateFilterMode = 3;
// The splatting shader's passes (vtkSurfaceSplatFS.glsl).
enum SplatPass
{
  VisibilityPass = 0,
  AttributePass = 1,
  SelectionPass = 2
};

using splat::SetNearest;

// Binds `fields`, packed in this order in each element of `buffer` (a vertex, or with a divisor
// of 1 an instance), to the attributes of the same names of `program` (current), in the bound
// vertex array `array`.
template <std::size_t N>
void AddAttributes(vtkOpenGLVertexArrayObject* array, vtkShaderProgram* program,
  vtkOpenGLBufferObject* buffer, const std::array<Attribute, N>& fields, int divisor)
{
  const std::size_t stride = Floats(fields) * sizeof(float);
  int offset = 0;
  for (const Attribute& field : fields)
  {
    array->AddAttributeArrayWithDivisor(
      program, buffer, field.Name, offset, stride, VTK_FLOAT, field.Size, false, divisor, false);
    offset += field.Size * static_cast<int>(sizeof(float));
  }
}

// The record's fields as the varyings that the setup program captures, declared before it
// links. One object per thread: the window's shader cache relinks a program readied with
// another one (rasterizers sharing a window share its programs), and linking writes to it
// (windows may render in threads of their own).
vtkTransformFeedback* RecordCapture()
{
  thread_local vtkSmartPointer<vtkTransformFeedback> capture;
  if (!capture)
  {
    capture = vtkSmartPointer<vtkTransformFeedback>::New();
    for (const Attribute& field : RecordFields)
    {
      // (The role only sizes the varying: four floats.)
      capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, field.Name);
    }
  }
  return capture;
}

// A vertex array with the attributes of one program.
struct ProgramArray
{
  vtkNew<vtkOpenGLVertexArrayObject> Array;
  vtkShaderProgram* Program = nullptr; // the program its attributes are bound to
  bool PointIds = false;               // whether they include the point ids

  // Binds the array; true when it was emptied for `program` (current) or the point ids, and
  // needs its attributes added.
  bool Bind(vtkShaderProgram* program, bool pointIds)
  {
    const bool changed = program != this->Program || pointIds != this->PointIds;
    if (changed)
    {
      // (This releases the array: bind it after.)
      this->Array->ShaderProgramChanged();
      this->Program = program;
      this->PointIds = pointIds;
    }
    this->Array->Bind();
    return changed;
  }

  void ReleaseGraphicsResources()
  {
    this->Array->ReleaseGraphicsResources();
    this->Program = nullptr;
  }
};
}

struct vtkOpenGLSurfaceSplatRasterizer::Internals
{
  vtkNew<vtkOpenGLBufferObject> Attributes;
  vtkNew<vtkOpenGLBufferObject> Records; // the setup pass's output, the strip passes' input
  vtkNew<vtkOpenGLBufferObject> PointIds;
  ProgramArray SetupArray; // the surfels, a vertex each
  ProgramArray StripArray; // the records (and point ids), an instance each
  GLsizei RecordCapacity = 0;
  vtkMTimeType Version = 0;
  vtkMTimeType PointIdsVersion = 0;
  glm::dvec3 Shift{ 0.0 };
  GLsizei Count = 0;
  bool Translucent = false;
  bool Differential = false;

  vtkNew<vtkTextureObject> VisibilityDepth[2]; // ping-pong: this layer's and the previous one's
  vtkNew<vtkTextureObject> WeightedColor;
  vtkNew<vtkTextureObject> WeightedNormal;
  vtkNew<vtkTextureObject> WeightedDepth;
  vtkNew<vtkTextureObject> NearestNormal; // the visibility pass's, attached for that pass only
  vtkNew<vtkTextureObject> LayerColor;
  vtkNew<vtkTextureObject> LayerDepth;
  vtkNew<vtkTextureObject> SceneDepth;
  vtkNew<vtkOpenGLFramebufferObject> SplatFramebuffer;
  vtkNew<vtkOpenGLFramebufferObject> ResolveFramebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> Resolve;
  GLuint Query = 0;
  int Width = 0;
  int Height = 0;

  // Runs the setup pass (each splat's record), then makes the strip program current, its
  // vertex array bound and the uniforms of both set. Null when a program did not compile.
  vtkShaderProgram* ReadySplatProgram(vtkOpenGLRenderWindow* window,
    const vtkSurfaceSplatRasterizer::Camera& camera, vtkSurfaceSplatRasterizer* settings,
    bool approximateFilter, bool cullBackFaces, bool withPointIds);
  void Allocate(vtkOpenGLRenderWindow* window, int width, int height);
  void SetViewUniforms(vtkShaderProgram* program, const vtkSurfaceSplatRasterizer::Camera& camera);
  void SetSplatUniforms(vtkShaderProgram* program, const vtkSurfaceSplatRasterizer::Camera& camera,
    vtkSurfaceSplatRasterizer* settings, bool approximateFilter, bool cullBackFaces);
  void ResolveLayer(vtkOpenGLRenderWindow* window, const vtkSurfaceSplatRasterizer::Camera& camera,
    const std::vector<splat::Light>& lights, const splat::Material& material,
    vtkSurfaceSplatRasterizer* settings, int layer, bool translucent);
  void Draw() { glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, this->Count); }
};

//------------------------------------------------------------------------------
vtkShaderProgram* vtkOpenGLSurfaceSplatRasterizer::Internals::ReadySplatProgram(
  vtkOpenGLRenderWindow* window, const vtkSurfaceSplatRasterizer::Camera& camera,
  vtkSurfaceSplatRasterizer* settings, bool approximateFilter, bool cullBackFaces,
  bool withPointIds)
{
  // The setup pass: each splat's record, once for all the passes that draw it.
  vtkOpenGLShaderCache* cache = window->GetShaderCache();
  vtkShaderProgram* setup =
    cache->ReadyShaderProgram(vtkSurfaceSplatSetupVS, SetupFS, "", RecordCapture());
  if (!setup || !setup->GetCompiled())
  {
    return nullptr;
  }
  if (this->SetupArray.Bind(setup, false))
  {
    AddAttributes(this->SetupArray.Array, setup, this->Attributes, SurfelFields, 0);
  }
  this->SetSplatUniforms(setup, camera, settings, approximateFilter, cullBackFaces);
  {
    vtkOpenGLState* state = window->GetState();
    vtkOpenGLState::ScopedglEnableDisable discard(state, GL_RASTERIZER_DISCARD);
    state->vtkglEnable(GL_RASTERIZER_DISCARD);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, this->Records->GetHandle());
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, this->Count);
    glEndTransformFeedback();
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  }
  this->SetupArray.Array->Release();

  // The strips, reading the records.
  vtkShaderProgram* program = cache->ReadyShaderProgram(vtkSurfaceSplatVS, vtkSurfaceSplatFS, "");
  if (!program || !program->GetCompiled())
  {
    return nullptr;
  }
  if (this->StripArray.Bind(program, withPointIds))
  {
    AddAttributes(this->StripArray.Array, program, this->Records, RecordFields, 1);
    if (withPointIds)
    {
      this->StripArray.Array->AddAttributeArrayWithDivisor(
        program, this->PointIds, "pointId", 0, 2 * sizeof(float), VTK_FLOAT, 2, false, 1, false);
    }
  }
  this->SetSplatUniforms(program, camera, settings, approximateFilter, cullBackFaces);
  return program;
}

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::Internals::Allocate(
  vtkOpenGLRenderWindow* window, int width, int height)
{
  if (width == this->Width && height == this->Height && this->LayerColor->GetHandle() != 0)
  {
    return;
  }
  for (auto& depth : this->VisibilityDepth)
  {
    SetNearest(depth, window);
    depth->AllocateDepth(width, height, vtkTextureObject::Float32);
  }
  for (vtkTextureObject* color : { this->WeightedColor.Get(), this->WeightedNormal.Get(),
         this->NearestNormal.Get(), this->LayerColor.Get() })
  {
    SetNearest(color, window);
    color->Allocate2D(width, height, 4, VTK_FLOAT);
  }
  for (vtkTextureObject* scalar : { this->WeightedDepth.Get(), this->LayerDepth.Get() })
  {
    SetNearest(scalar, window);
    scalar->Allocate2D(width, height, 1, VTK_FLOAT);
  }
  // Attachments are made on the bound framebuffer (the caller keeps VTK's bindings).
  this->SplatFramebuffer->SetContext(window);
  this->SplatFramebuffer->Bind();
  this->SplatFramebuffer->AddColorAttachment(0, this->WeightedColor);
  this->SplatFramebuffer->AddColorAttachment(1, this->WeightedNormal);
  this->SplatFramebuffer->AddColorAttachment(2, this->WeightedDepth);
  this->ResolveFramebuffer->SetContext(window);
  this->ResolveFramebuffer->Bind();
  this->ResolveFramebuffer->AddColorAttachment(0, this->LayerColor);
  this->ResolveFramebuffer->AddColorAttachment(1, this->LayerDepth);
  this->Width = width;
  this->Height = height;
}

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::Internals::SetViewUniforms(
  vtkShaderProgram* program, const vtkSurfaceSplatRasterizer::Camera& camera)
{
  // The shift is folded in double precision: the float matrix then only holds the (small)
  // offsets between the data and the camera.
  const glm::dmat4 modelToEye = camera.ModelToEye * glm::translate(glm::dmat4(1.0), this->Shift);
  glm::mat4 modelToEyeF(modelToEye);
  glm::mat3 normalToEye(glm::transpose(glm::inverse(glm::dmat3(camera.ModelToEye))));
  glm::mat4 eyeToClip(camera.EyeToClip);
  const glm::dvec2 viewport(camera.Viewport);
  const splat::PixelRays rays = splat::MakePixelRays(camera.EyeToClip, viewport);
  glm::mat3 rayOrigin(rays.Origin);
  glm::mat3 rayDirection(rays.Direction);
  const glm::dmat4 clipToEye = glm::inverse(camera.EyeToClip);
  auto eyeDepth = [&clipToEye](double zNdc)
  {
    const glm::dvec4 eye = clipToEye * glm::dvec4(0.0, 0.0, zNdc, 1.0);
    return static_cast<float>(-eye.z / eye.w);
  };
  const glm::dmat4& P = camera.EyeToClip;
  const float viewportSize[2] = { static_cast<float>(viewport.x), static_cast<float>(viewport.y) };
  const float depthProjection[2] = { static_cast<float>(P[2][2]), static_cast<float>(P[3][2]) };
  const float depthProjectionW[2] = { static_cast<float>(P[2][3]), static_cast<float>(P[3][3]) };
  program->SetUniformMatrix4x4("modelToEye", glm::value_ptr(modelToEyeF));
  program->SetUniformMatrix3x3("normalToEye", glm::value_ptr(normalToEye));
  program->SetUniformMatrix4x4("eyeToClip", glm::value_ptr(eyeToClip));
  program->SetUniformMatrix3x3("rayOrigin", glm::value_ptr(rayOrigin));
  program->SetUniformMatrix3x3("rayDirection", glm::value_ptr(rayDirection));
  program->SetUniform2f("viewportSize", viewportSize);
  program->SetUniformi("perspective", rays.Perspective ? 1 : 0);
  program->SetUniformf("nearDepth", eyeDepth(-1.0));
  program->SetUniformf("farDepth", eyeDepth(1.0));
  program->SetUniform2f("depthProjection", depthProjection);
  program->SetUniform2f("depthProjectionW", depthProjectionW);
}

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::Internals::SetSplatUniforms(vtkShaderProgram* program,
  const vtkSurfaceSplatRasterizer::Camera& camera, vtkSurfaceSplatRasterizer* settings,
  bool approximateFilter, bool cullBackFaces)
{
  this->SetViewUniforms(program, camera);
  program->SetUniformf("cutoff", static_cast<float>(settings->GetCutoff()));
  program->SetUniformf(
    "antialiasingCutoff", static_cast<float>(settings->GetAntialiasingCutoff()));
  program->SetUniformf(
    "minifiedLowPass", static_cast<float>(settings->GetMinifiedLowPassVariance()));
  program->SetUniformf(
    "magnifiedLowPass", static_cast<float>(settings->GetMagnifiedLowPassVariance()));
  program->SetUniformi("filterMode",
    approximateFilter ? ApproximateFilterMode : static_cast<int>(settings->GetFilter()));
  program->SetUniformi("differential", this->Differential);
  program->SetUniformi("cullBackFaces", cullBackFaces);
  program->SetUniformf("depthThreshold", static_cast<float>(settings->GetDepthThreshold()));
}

//------------------------------------------------------------------------------
vtkOpenGLSurfaceSplatRasterizer::vtkOpenGLSurfaceSplatRasterizer()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkOpenGLSurfaceSplatRasterizer::~vtkOpenGLSurfaceSplatRasterizer() = default;

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::SetSurfels(
  const vtkSurfaceSplatRasterizer::Surfels& surfels, vtkMTimeType version)
{
  Internals& internal = *this->Internal;
  if (version == internal.Version && internal.Attributes->GetHandle() != 0)
  {
    return;
  }
  const std::size_t n = surfels.Count;
  internal.Shift = splat::BoundsCenter(surfels.Positions, n);
  std::vector<float> data(SplatStride * n);
  internal.Translucent = false;
  internal.Differential = surfels.Curvatures != nullptr;
  for (std::size_t i = 0; i < n; ++i)
  {
    float* d = &data[SplatStride * i];
    for (int c = 0; c < 3; ++c)
    {
      d[c] = static_cast<float>(surfels.Positions[3 * i + c] - internal.Shift[c]);
      d[3 + c] = surfels.Axes0[3 * i + c];
      d[6 + c] = surfels.Axes1[3 * i + c];
      d[9 + c] = surfels.Normals[3 * i + c];
      d[12 + c] = surfels.Colors[3 * i + c];
    }
    d[15] = surfels.Opacities ? surfels.Opacities[i] : 1.0f;
    d[16] = surfels.Curvatures ? surfels.Curvatures[2 * i] : 0.0f;
    d[17] = surfels.Curvatures ? surfels.Curvatures[2 * i + 1] : 0.0f;
    internal.Translucent = internal.Translucent || d[15] < 1.0f;
  }
  internal.Attributes->Upload(data, vtkOpenGLBufferObject::ArrayBuffer);
  internal.Count = static_cast<GLsizei>(n);
  internal.Version = version;
  if (internal.Count > internal.RecordCapacity)
  {
    // Storage only: the setup pass fills it every frame (VTK 9.1's buffer object allocates
    // only with an upload).
    internal.Records->GenerateBuffer(vtkOpenGLBufferObject::ArrayBuffer);
    internal.Records->Bind();
    glBufferData(
      GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(n * RecordBytes), nullptr, GL_DYNAMIC_COPY);
    internal.RecordCapacity = internal.Count;
  }
}

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::Render(vtkRenderer* renderer,
  const vtkSurfaceSplatRasterizer::Camera& camera, const std::vector<splat::Light>& lights,
  const splat::Material& material, vtkSurfaceSplatRasterizer* settings,
  const std::vector<float>& sceneDepths)
{
  Internals& internal = *this->Internal;
  this->PeeledLayers = 0;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  const int width = camera.Viewport.x;
  const int height = camera.Viewport.y;
  if (!window || width <= 0 || height <= 0)
  {
    return;
  }
  vtkOpenGLState* state = window->GetState();
  state->PushFramebufferBindings();
  internal.Allocate(window, width, height);
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  vtkOpenGLState::ScopedglColorMask colorMask(state);
  vtkOpenGLState::ScopedglClearColor clearColor(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  state->vtkglViewport(0, 0, width, height);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);

  // The resolved image starts empty: no color, the far plane.
  internal.ResolveFramebuffer->Bind();
  internal.ResolveFramebuffer->ActivateDrawBuffers(1);
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
  internal.ResolveFramebuffer->ActivateDrawBuffer(1);
  state->vtkglClearColor(1.0f, 1.0f, 1.0f, 1.0f);
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
  state->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);

  // GPU times of the passes, for vtkRenderWindow::GetRenderTimer() (when its logging is on).
  vtkRenderTimerLog* timer = window->GetRenderTimer();
  VTK_SCOPED_RENDER_EVENT2("vtkOpenGLSurfaceSplatRasterizer setup", timer, setupEvent);
  const bool translucent = internal.Translucent;
  vtkShaderProgram* program = internal.ReadySplatProgram(window, camera, settings,
    this->ApproximateFilter, settings->GetBackfaceCulling() && !translucent, false);
  setupEvent.Stop();
  if (!program)
  {
    vtkErrorMacro("The splatting shaders did not compile.");
    state->PopFramebufferBindings();
    return;
  }
  program->SetUniform2f("viewportOrigin", std::array<float, 2>{ 0.0f, 0.0f }.data());
  const bool sceneTest =
    translucent && sceneDepths.size() == static_cast<std::size_t>(width) * height;
  program->SetUniformi("sceneTest", sceneTest);
  if (sceneTest)
  {
    SetNearest(internal.SceneDepth, window);
    internal.SceneDepth->Create2DFromRaw(
      width, height, 1, VTK_FLOAT, const_cast<float*>(sceneDepths.data()));
    internal.SceneDepth->Activate();
    program->SetUniformi("sceneDepth", internal.SceneDepth->GetTextureUnit());
  }

  if (!internal.Query)
  {
    glGenQueries(1, &internal.Query);
  }
  // Automatic layers: the paper's, since each layer is a pass over every splat.
  const int requested = settings->GetNumberOfLayers();
  const int layers = translucent || settings->GetEdgeAntialiasing()
    ? (requested > 0 ? requested : vtkSurfaceSplatRasterizer::PaperLayers)
    : 1;
  this->LastNumberOfLayers = layers;
  for (int layer = 0; layer < layers; ++layer)
  {
    vtkTextureObject* depth = internal.VisibilityDepth[layer % 2];
    vtkTextureObject* previous = internal.VisibilityDepth[(layer + 1) % 2];
    window->GetShaderCache()->ReadyShaderProgram(program);
    internal.StripArray.Array->Bind();
    internal.SplatFramebuffer->Bind();
    internal.SplatFramebuffer->AddDepthAttachment(depth);
    if (layer > 0)
    {
      previous->Activate();
      program->SetUniformi("previousDepth", previous->GetTextureUnit());
      internal.LayerColor->Activate();
      program->SetUniformi("layersInFront", internal.LayerColor->GetTextureUnit());
    }
    program->SetUniformi("peel", layer > 0);

    // Pass 1: visibility, and the nearest splat's normal (the one pass 2 turns normals to).
    internal.SplatFramebuffer->AddColorAttachment(3, internal.NearestNormal);
    internal.SplatFramebuffer->ActivateDrawBuffer(3);
    state->vtkglDisable(GL_BLEND);
    state->vtkglEnable(GL_DEPTH_TEST);
    state->vtkglDepthFunc(GL_LESS);
    state->vtkglDepthMask(GL_TRUE);
    state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    state->vtkglClear(GL_DEPTH_BUFFER_BIT);
    program->SetUniformi("splatPass", VisibilityPass);
    VTK_SCOPED_RENDER_EVENT2("visibility, layer " << layer, timer, visibilityEvent);
    glBeginQuery(GL_ANY_SAMPLES_PASSED, internal.Query);
    internal.Draw();
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    GLuint anySamples = 0;
    glGetQueryObjectuiv(internal.Query, GL_QUERY_RESULT, &anySamples);
    visibilityEvent.Stop();
    // Read, not drawn, from here: detached so that it is no feedback loop.
    internal.SplatFramebuffer->RemoveColorAttachment(3);
    internal.SplatFramebuffer->ActivateDrawBuffers(3);
    if (!anySamples)
    {
      if (layer > 0)
      {
        previous->Deactivate();
        internal.LayerColor->Deactivate();
      }
      break; // nothing shows behind the layers peeled so far
    }

    // Pass 2: attributes, added up within the visibility depth.
    internal.NearestNormal->Activate();
    program->SetUniformi("nearestNormal", internal.NearestNormal->GetTextureUnit());
    state->vtkglClear(GL_COLOR_BUFFER_BIT);
    state->vtkglDepthFunc(GL_LEQUAL);
    state->vtkglDepthMask(GL_FALSE);
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    program->SetUniformi("splatPass", AttributePass);
    VTK_SCOPED_RENDER_EVENT2("attributes, layer " << layer, timer, attributeEvent);
    internal.Draw();
    attributeEvent.Stop();
    internal.NearestNormal->Deactivate();
    internal.StripArray.Array->Release();
    if (layer > 0)
    {
      previous->Deactivate();
      internal.LayerColor->Deactivate();
    }

    // Pass 3: normalize, shade, and blend under the layers in front (the first one also
    // writes its depth).
    VTK_SCOPED_RENDER_EVENT2("resolve, layer " << layer, timer, resolveEvent);
    internal.ResolveLayer(window, camera, lights, material, settings, layer, translucent);
    resolveEvent.Stop();
    this->PeeledLayers = layer + 1;
  }
  if (sceneTest)
  {
    internal.SceneDepth->Deactivate();
  }
  state->PopFramebufferBindings();
}

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::Internals::ResolveLayer(vtkOpenGLRenderWindow* window,
  const vtkSurfaceSplatRasterizer::Camera& camera, const std::vector<splat::Light>& lights,
  const splat::Material& material, vtkSurfaceSplatRasterizer* settings, int layer,
  bool translucent)
{
  static const std::string resolveSource = splat::WithLighting(vtkSurfaceSplatResolveFS);
  vtkShaderProgram* program = splat::ReadyQuad(this->Resolve, window, resolveSource.c_str());
  if (!program)
  {
    return;
  }
  vtkOpenGLState* state = window->GetState();
  this->ResolveFramebuffer->Bind();
  state->vtkglDisable(GL_DEPTH_TEST);
  if (layer == 0)
  {
    this->ResolveFramebuffer->ActivateDrawBuffers(2);
    state->vtkglDisable(GL_BLEND);
  }
  else
  {
    // Front to back: what this layer shows is what the layers in front let through.
    this->ResolveFramebuffer->ActivateDrawBuffers(1);
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE_MINUS_DST_ALPHA, GL_ONE, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  }

  this->SetViewUniforms(program, camera);
  program->SetUniformi("edgeAntialiasing", settings->GetEdgeAntialiasing());
  program->SetUniformf("fullCoverage", settings->FullCoverageWeight());
  program->SetUniformi("closeDips", layer == 0 && !translucent);
  program->SetUniformf("opaqueAlpha", splat::OpaqueAlpha);
  program->SetUniformf("edgeOnCosine", splat::EdgeOnCosine);
  program->SetUniformf("dipCoverage", splat::DipCoverage);
  program->SetUniformf(
    "dipTolerance", splat::DipDepthTolerance(camera.EyeToClip[1][1], camera.Viewport.y));
  splat::SetLightingUniforms(program, lights, material, camera.EyeToClip);

  vtkTextureObject* inputs[3] = { this->WeightedColor, this->WeightedNormal, this->WeightedDepth };
  const char* names[3] = { "weightedColor", "weightedNormal", "weightedDepth" };
  for (int i = 0; i < 3; ++i)
  {
    inputs[i]->Activate();
    program->SetUniformi(names[i], inputs[i]->GetTextureUnit());
  }
  this->Resolve->Render();
  for (vtkTextureObject* input : inputs)
  {
    input->Deactivate();
  }
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkOpenGLSurfaceSplatRasterizer::GetColorTexture()
{
  return this->Internal->LayerColor;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkOpenGLSurfaceSplatRasterizer::GetDepthTexture()
{
  return this->Internal->LayerDepth;
}

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::RenderSelection(vtkRenderer* renderer,
  vtkHardwareSelector* selector, const vtkSurfaceSplatRasterizer::Camera& camera,
  vtkSurfaceSplatRasterizer* settings, const std::vector<vtkIdType>& pointIds)
{
  Internals& internal = *this->Internal;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window || internal.Count == 0 || pointIds.size() != static_cast<std::size_t>(internal.Count))
  {
    return;
  }
  if (internal.PointIdsVersion != internal.Version)
  {
    // The ids in two exact 24-bit halves (the actor pass tells hits from the background).
    std::vector<float> ids(2 * pointIds.size());
    for (std::size_t i = 0; i < pointIds.size(); ++i)
    {
      const long long id = static_cast<long long>(pointIds[i]);
      ids[2 * i] = static_cast<float>(id & 0xffffff);
      ids[2 * i + 1] = static_cast<float>((id >> 24) & 0xffffff);
    }
    internal.PointIds->Upload(ids, vtkOpenGLBufferObject::ArrayBuffer);
    internal.PointIdsVersion = internal.Version;
  }
  vtkShaderProgram* program = internal.ReadySplatProgram(
    window, camera, settings, this->ApproximateFilter, settings->GetBackfaceCulling(), true);
  if (!program)
  {
    vtkErrorMacro("The splatting shaders did not compile.");
    return;
  }
  int width, height, originX, originY;
  renderer->GetTiledSizeAndOrigin(&width, &height, &originX, &originY);
  const float origin[2] = { static_cast<float>(originX), static_cast<float>(originY) };
  program->SetUniform2f("viewportOrigin", origin);
  program->SetUniformi("peel", 0);
  program->SetUniformi("sceneTest", 0);
  program->SetUniformi("splatPass", SelectionPass);
  int idPass = 0;
  switch (selector->GetCurrentPass())
  {
    case vtkHardwareSelector::POINT_ID_LOW24:
    case vtkHardwareSelector::CELL_ID_LOW24:
      idPass = 1;
      break;
    case vtkHardwareSelector::POINT_ID_HIGH24:
    case vtkHardwareSelector::CELL_ID_HIGH24:
      idPass = 2;
      break;
    default:
      break;
  }
  program->SetUniformi("selectionIdPass", idPass);
  program->SetUniform3f("selectionColor", selector->GetPropColorValue());

  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDepthMask(GL_TRUE);
  state->vtkglDepthFunc(GL_LEQUAL);
  internal.Draw();
  internal.StripArray.Array->Release();
}

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& internal = *this->Internal;
  internal.Attributes->ReleaseGraphicsResources();
  internal.Records->ReleaseGraphicsResources();
  internal.PointIds->ReleaseGraphicsResources();
  // The programs are the window's (its shader cache releases them).
  internal.SetupArray.ReleaseGraphicsResources();
  internal.StripArray.ReleaseGraphicsResources();
  internal.RecordCapacity = 0;
  internal.Version = internal.PointIdsVersion = 0;
  for (vtkTextureObject* texture :
    { internal.VisibilityDepth[0].Get(), internal.VisibilityDepth[1].Get(),
      internal.WeightedColor.Get(), internal.WeightedNormal.Get(), internal.WeightedDepth.Get(),
      internal.NearestNormal.Get(), internal.LayerColor.Get(), internal.LayerDepth.Get(), internal.SceneDepth.Get() })
  {
    texture->ReleaseGraphicsResources(window);
  }
  internal.SplatFramebuffer->ReleaseGraphicsResources(window);
  internal.ResolveFramebuffer->ReleaseGraphicsResources(window);
  internal.Width = internal.Height = 0;
  if (internal.Resolve)
  {
    internal.Resolve->ReleaseGraphicsResources(window);
    internal.Resolve.reset();
  }
  if (internal.Query)
  {
    glDeleteQueries(1, &internal.Query);
    internal.Query = 0;
  }
}

//------------------------------------------------------------------------------
void vtkOpenGLSurfaceSplatRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ApproximateFilter: " << this->ApproximateFilter << "\n";
  os << indent << "LastNumberOfLayers: " << this->LastNumberOfLayers << "\n";
  os << indent << "PeeledLayers: " << this->PeeledLayers << "\n";
}
