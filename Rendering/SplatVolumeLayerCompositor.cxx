// SPDX-License-Identifier: BSD-3-Clause
#include "SplatVolumeLayerCompositor.h"

#include "SplatExponential.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
// The most a kernel of the 3D Gaussian Splatting convention covers a pixel, as in its viewers.
constexpr float MaximumPeakOpacity = 0.99f;

// The largest optical depth whose opacity 1 - exp(-t) is taken from its series to t^5: the
// remainder, below t^6 / 720, is 6e-9 there.
constexpr float SeriesOpticalDepth = 0.125f;
}

namespace splat
{
//------------------------------------------------------------------------------
VolumeLayerCompositor::VolumeLayerCompositor(int width, int rowBegin, int rowEnd, float cutoff,
  bool peakOpacity, const float* sceneDepths)
  : Width(width)
  , RowBegin(rowBegin)
  , RowEnd(rowEnd)
  , Cutoff(cutoff)
  , PeakOpacity(peakOpacity)
  , Stride(width + Lanes)
  , Spans(rowEnd - rowBegin + 1, glm::ivec2(std::numeric_limits<int>::max(), -1))
  , LayerRows(std::numeric_limits<int>::max(), -1)
  , Tiles((width + Lanes - 1) / Lanes)
  , OpenPixels(static_cast<std::size_t>(rowEnd - rowBegin + 1) * Tiles, 0)
  , OpenTotal(0)
  , SelectedRows(Tiles, 0)
{
  const std::size_t size = static_cast<std::size_t>(rowEnd - rowBegin + 1) * this->Stride;
  for (auto& sum : this->Sums)
  {
    sum.assign(size, 0.0f);
  }
  this->SceneDepths.assign(size, std::numeric_limits<float>::infinity());
  for (int y = rowBegin; sceneDepths && y <= rowEnd; ++y)
  {
    std::copy_n(sceneDepths + static_cast<std::size_t>(y) * width, width,
      this->SceneDepths.begin() + static_cast<std::size_t>(y - rowBegin) * this->Stride);
  }
}

//------------------------------------------------------------------------------
void VolumeLayerCompositor::Begin(const float* weights, bool ascending, const glm::vec4* buffer)
{
  std::fill(this->OpenPixels.begin(), this->OpenPixels.end(), 0);
  this->OpenTotal = 0;
  for (int y = this->RowBegin; y <= this->RowEnd; ++y)
  {
    const std::size_t pixelRow = static_cast<std::size_t>(y) * this->Width;
    int* openTiles =
      this->OpenPixels.data() + static_cast<std::size_t>(y - this->RowBegin) * this->Tiles;
    for (int x = 0; x < this->Width; ++x)
    {
      const bool open = IsOpen(weights, ascending, buffer, pixelRow + x);
      openTiles[x / Lanes] += open;
      this->OpenTotal += open;
    }
  }
}

//------------------------------------------------------------------------------
template <typename Visit>
SPLAT_ALWAYS_INLINE void VolumeLayerCompositor::ForEachGroup(const ScreenKernel& s, Visit&& visit)
{
  const int y0 = std::max(s.Y0, this->RowBegin);
  const int y1 = std::min(s.Y1, this->RowEnd);
  const float xx = s.ConicXX;
  const float amplitude = s.Amplitude;
  const float kernelDepth = s.Depth;
  const float cutoff = this->Cutoff;
  const int columns = s.X1 - s.X0 + 1;
  // Whole groups of lanes over the box's columns, the cutoff ellipse as a mask: no per-row
  // span and no scalar remainder.
  const int groups = (columns + Lanes - 1) / Lanes;
  const Float8 lane = Float8::Iota();
  const float dx0 = s.X0 + 0.5f - s.CenterX;
  for (int y = y0; y <= y1; ++y)
  {
    const float dy = y + 0.5f - s.CenterY;
    const float bq = s.ConicXY * dy;
    const float yTerm = s.ConicYY * dy * dy;
    const std::size_t row = static_cast<std::size_t>(y - this->RowBegin) * this->Stride + s.X0;
    for (int group = 0; group < groups; ++group)
    {
      const int i = group * Lanes;
      const Float8 column = lane + static_cast<float>(i);
      const Float8 dx = column + dx0;
      const Float8 beta = (xx * dx + bq) * dx + yTerm;
      Float8 t = amplitude * Float8::NegativeExponential(beta);
      t = Float8::SelectLess(beta, cutoff, t, 0.0f);
      t = Float8::SelectLess(column, static_cast<float>(columns), t, 0.0f);
      // Behind the opaque scene the kernel adds nothing.
      const Float8 sceneDepth = Float8::Load(this->SceneDepths.data() + row + i);
      t = Float8::SelectLess(sceneDepth, kernelDepth, 0.0f, t);
      visit(y, s.X0 + i, row + i, t);
    }
  }
}

//------------------------------------------------------------------------------
SPLAT_ALWAYS_INLINE void VolumeLayerCompositor::UnderGroup(const float* weights, bool ascending,
  glm::vec4* buffer, std::size_t p, int x, int y, int lanes, const Float8& alpha,
  const Float8& red, const Float8& green, const Float8& blue)
{
  int* openTiles =
    this->OpenPixels.data() + static_cast<std::size_t>(y - this->RowBegin) * this->Tiles;
  if (x + Lanes > this->Width)
  {
    alignas(32) float values[4][Lanes];
    alpha.Store(values[3]);
    red.Store(values[0]);
    green.Store(values[1]);
    blue.Store(values[2]);
    for (int i = 0; i < lanes; ++i)
    {
      this->Under(weights, ascending, buffer, p + i, x + i, openTiles, values[3][i],
        glm::vec3(values[0][i], values[1][i], values[2][i]));
    }
    return;
  }
  Float8 c[4];
  Float8::LoadChannels(&buffer[p].x, c);
  const Float8 zero(0.0f), one(1.0f), termination(TerminationAlpha);
  // Under's transmittance: 1 - alpha where the pixel is open, zero elsewhere.
  Float8 transmittance = Float8::SelectLess(c[3], termination, one - c[3], zero);
  transmittance = Float8::SelectLess(zero, alpha, transmittance, zero);
  if (weights)
  {
    const Float8 w = Float8::Load(weights + p);
    transmittance = ascending ? Float8::SelectLess(zero, w, transmittance, zero)
                              : Float8::SelectLess(w, zero, transmittance, zero);
  }
  c[0] = c[0] + transmittance * red;
  c[1] = c[1] + transmittance * green;
  c[2] = c[2] + transmittance * blue;
  c[3] = c[3] + transmittance * alpha;
  Float8::StoreChannels(&buffer[p].x, c);
  // The pixels this closed: open before, at the termination opacity now.
  alignas(32) float closed[Lanes];
  Float8::SelectLess(zero, transmittance, Float8::SelectLess(c[3], termination, zero, one), zero)
    .Store(closed);
  for (int i = 0; i < Lanes; ++i)
  {
    openTiles[(x + i) / Lanes] -= static_cast<int>(closed[i]);
    this->OpenTotal -= static_cast<int>(closed[i]);
  }
}

//------------------------------------------------------------------------------
SPLAT_ALWAYS_INLINE Float8 VolumeLayerCompositor::Opacity(const Float8& t, float largest) const
{
  if (this->PeakOpacity)
  {
    return Float8::SelectLess(t, MaximumPeakOpacity, t, MaximumPeakOpacity);
  }
  // Small optical depths (those of most point kernels) need no exponential.
  if (largest <= SeriesOpticalDepth)
  {
    const Float8 one(1.0f);
    return t *
      (one - t * (0.5f - t * (1.0f / 6.0f - t * (1.0f / 24.0f - t * (1.0f / 120.0f)))));
  }
  // 1 - exp(-t) loses digits only where the opacity is far below an 8-bit step.
  return Float8(1.0f) - Float8::NegativeExponential(t);
}

//------------------------------------------------------------------------------
SPLAT_VECTOR_CLONES void VolumeLayerCompositor::Add(const ScreenKernel& s)
{
  if (!this->Reaches(s))
  {
    return;
  }
  this->Touch(s.X0, s.X1, s.Y0, s.Y1);
  const Float8 red(s.Color[0]), green(s.Color[1]), blue(s.Color[2]);
  const std::array<float*, 4> sums = this->SumsAt(0);
  this->ForEachGroup(
    s, [&](int, int, std::size_t q, const Float8& t) SPLAT_INLINE_LAMBDA
    { Accumulate(sums, q, t, red, green, blue); });
}

//------------------------------------------------------------------------------
SPLAT_VECTOR_CLONES void VolumeLayerCompositor::Composite(
  const ScreenKernel& s, const float* weights, bool ascending, glm::vec4* buffer)
{
  if (!this->Reaches(s))
  {
    return;
  }
  const Float8 red(s.Color[0]), green(s.Color[1]), blue(s.Color[2]);
  this->ForEachGroup(s,
    [&](int y, int x, std::size_t, const Float8& t) SPLAT_INLINE_LAMBDA
    {
      const Float8 alpha = this->Opacity(t, s.Amplitude);
      this->UnderGroup(weights, ascending, buffer, static_cast<std::size_t>(y) * this->Width + x,
        x, y, std::min(Lanes, s.X1 - x + 1), alpha, alpha * red, alpha * green, alpha * blue);
    });
}

//------------------------------------------------------------------------------
SPLAT_VECTOR_CLONES void VolumeLayerCompositor::Flush(
  const float* weights, bool ascending, glm::vec4* buffer)
{
  const Float8 zero(0.0f);
  for (int y = this->LayerRows.x; y <= this->LayerRows.y; ++y)
  {
    glm::ivec2& span = this->Spans[y - this->RowBegin];
    const std::size_t row = static_cast<std::size_t>(y - this->RowBegin) * this->Stride;
    const std::size_t pixelRow = static_cast<std::size_t>(y) * this->Width;
    // Eight pixels at a time (the rows' padding takes the last group's excess lanes, whose sums
    // are zero): the layer's opacity and colors, then under the pixels.
    for (int x = span.x; x <= span.y; x += Lanes)
    {
      const std::size_t q = row + x;
      const Float8 depth = Float8::Load(this->Sums[3].data() + q);
      const Float8 alpha = this->Opacity(depth);
      const Float8 scale = Float8::SelectLess(zero, depth, alpha / depth, zero);
      const Float8 red = scale * Float8::Load(this->Sums[0].data() + q);
      const Float8 green = scale * Float8::Load(this->Sums[1].data() + q);
      const Float8 blue = scale * Float8::Load(this->Sums[2].data() + q);
      for (auto& sum : this->Sums)
      {
        zero.Store(sum.data() + q);
      }
      this->UnderGroup(weights, ascending, buffer, pixelRow + x, x, y,
        std::min(Lanes, span.y - x + 1), alpha, red, green, blue);
    }
    span = glm::ivec2(std::numeric_limits<int>::max(), -1);
  }
  this->LayerRows = glm::ivec2(std::numeric_limits<int>::max(), -1);
}
}
