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
  , OpenPixels((width + Lanes - 1) / Lanes, 0)
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
  for (int y = this->RowBegin; y <= this->RowEnd; ++y)
  {
    const std::size_t pixelRow = static_cast<std::size_t>(y) * this->Width;
    for (int x = 0; x < this->Width; ++x)
    {
      const std::size_t p = pixelRow + x;
      this->OpenPixels[x / Lanes] += IsOpen(weights, ascending, buffer, p);
    }
  }
}

//------------------------------------------------------------------------------
SPLAT_VECTOR_CLONES void VolumeLayerCompositor::Add(const ScreenKernel& s)
{
  if (!this->Reaches(s))
  {
    return;
  }
  const int y0 = std::max(s.Y0, this->RowBegin);
  const int y1 = std::min(s.Y1, this->RowEnd);
  const float xx = s.ConicXX;
  const float amplitude = s.Amplitude;
  const float red = s.Color[0], green = s.Color[1], blue = s.Color[2];
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
    const std::size_t row = this->Row(y, s);
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
      this->Accumulate(row + i, t, red, green, blue);
    }
  }
}

//------------------------------------------------------------------------------
void VolumeLayerCompositor::Flush(const float* weights, bool ascending, glm::vec4* buffer)
{
  for (int y = this->RowBegin; y <= this->RowEnd; ++y)
  {
    glm::ivec2& span = this->Spans[y - this->RowBegin];
    const std::size_t row = static_cast<std::size_t>(y - this->RowBegin) * this->Stride;
    const std::size_t pixelRow = static_cast<std::size_t>(y) * this->Width;
    for (int x = span.x; x <= span.y; ++x)
    {
      const std::size_t q = row + x;
      const float depth = this->Sums[3][q];
      const glm::vec3 color(this->Sums[0][q], this->Sums[1][q], this->Sums[2][q]);
      for (auto& sum : this->Sums)
      {
        sum[q] = 0.0f;
      }
      const std::size_t p = pixelRow + x;
      if (!(depth > 0.0f) || !IsOpen(weights, ascending, buffer, p))
      {
        continue;
      }
      glm::vec4& c = buffer[p];
      // 1 - exp(-t) loses digits only where the layer's opacity is far below an 8-bit step.
      const float alpha = this->PeakOpacity ? std::min(depth, MaximumPeakOpacity)
                                            : 1.0f - splat::NegativeExponential(depth);
      const float coverage = (1.0f - c.a) * alpha;
      c += glm::vec4((coverage / depth) * color, coverage);
      this->OpenPixels[x / Lanes] -= c.a >= TerminationAlpha;
    }
    span = glm::ivec2(std::numeric_limits<int>::max(), -1);
  }
}
}
