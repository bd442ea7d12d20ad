// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfelHierarchy.h"

#include "SplatMortonCode.h"
#include "SplatSortKey.h"

#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

vtkStandardNewMacro(vtkSurfelHierarchy);

namespace
{
// Cells per axis of the level-1 grid: 20 bits each, so that three Morton-interleaved
// coordinates and a normal class fit in 63 bits.
constexpr int CellBits = 20;

// Blocks hold about this many surfels: enough that a frame's choice per block costs nothing,
// few enough that a block's nearest depth is close to each of its surfels' depths.
constexpr vtkIdType BlockSurfels = 128;

// A level whose node count falls by less than this factor merges too little to pay for itself:
// the hierarchy stops there (scattered points far apart for their size).
constexpr double MinimumMerge = 0.8;

// Nodes seen at a grazing angle, |cos| below this, draw their surfels instead: a silhouette
// drawn by few merged nodes of uneven mass is ragged.
constexpr double GrazingCosine = 0.1;

// The minor axis variance of a merged node is at least this share of the major one: a cell cut
// by the surface in a sliver must not become a needle.
constexpr double MinimumAspect = 1.0 / 64.0;

// The dominant axis of a normal and its sign, 0 to 5: the sides of a thin part differ.
std::uint64_t NormalClass(const float* n)
{
  int axis = 0;
  for (int c = 1; c < 3; ++c)
  {
    if (std::abs(n[c]) > std::abs(n[axis]))
    {
      axis = c;
    }
  }
  return static_cast<std::uint64_t>(2 * axis + (n[axis] < 0.0f ? 1 : 0));
}

// What merging needs of a node: its mass (area), mass-weighted mean position and color, the
// second moments of its Gaussians about its position, and its mass-weighted normal sum.
struct Moments
{
  double Mass = 0.0;
  glm::dvec3 Position{ 0.0 };
  glm::dmat3 Covariance{ 0.0 };
  glm::dvec3 Normal{ 0.0 };
  glm::dvec3 Color{ 0.0 };
};

glm::dvec3 Axis(const float* axes, std::size_t i)
{
  return glm::dvec3(axes[3 * i], axes[3 * i + 1], axes[3 * i + 2]);
}

// A surfel's mass: the area its axes span.
double SurfelArea(const vtkSurfaceSplatRasterizer::Surfels& s, std::size_t i)
{
  return glm::length(glm::cross(Axis(s.Axes0, i), Axis(s.Axes1, i)));
}

Moments SurfelMoments(const vtkSurfaceSplatRasterizer::Surfels& s, std::size_t i)
{
  const glm::dvec3 a0 = Axis(s.Axes0, i);
  const glm::dvec3 a1 = Axis(s.Axes1, i);
  Moments m;
  m.Mass = SurfelArea(s, i);
  m.Position = glm::dvec3(s.Positions[3 * i], s.Positions[3 * i + 1], s.Positions[3 * i + 2]);
  m.Covariance = 0.5 * (glm::outerProduct(a0, a0) + glm::outerProduct(a1, a1));
  m.Normal = m.Mass * glm::dvec3(s.Normals[3 * i], s.Normals[3 * i + 1], s.Normals[3 * i + 2]);
  m.Color = glm::dvec3(s.Colors[3 * i], s.Colors[3 * i + 1], s.Colors[3 * i + 2]);
  return m;
}

// The moments of the union of nodes [first, last): masses add, means are mass-weighted, and the
// second moments about the new mean add each part's offset (parallel axis theorem). Massless
// parts (degenerate surfels) count equally when all are massless.
template <typename Part>
Moments Merge(std::size_t first, std::size_t last, const Part& part)
{
  double mass = 0.0;
  for (std::size_t j = first; j < last; ++j)
  {
    mass += part(j).Mass;
  }
  const bool uniform = !(mass > 0.0);
  const double total = uniform ? static_cast<double>(last - first) : mass;
  Moments m;
  m.Mass = mass;
  for (std::size_t j = first; j < last; ++j)
  {
    const Moments& p = part(j);
    const double w = (uniform ? 1.0 : p.Mass) / total;
    m.Position += w * p.Position;
    m.Color += w * p.Color;
    m.Normal += p.Normal;
  }
  for (std::size_t j = first; j < last; ++j)
  {
    const Moments& p = part(j);
    const glm::dvec3 d = p.Position - m.Position;
    m.Covariance += ((uniform ? 1.0 : p.Mass) / total) * (p.Covariance + glm::outerProduct(d, d));
  }
  return m;
}
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfelHierarchy::GetNumberOfNodes(int level) const
{
  if (level == 0)
  {
    return this->SurfelCount;
  }
  return level > 0 && level < this->GetNumberOfLevels()
    ? static_cast<vtkIdType>(this->LevelNodes[level - 1].size()) - 1
    : 0;
}

//------------------------------------------------------------------------------
vtkSurfaceSplatRasterizer::Surfels vtkSurfelHierarchy::GetNodes() const
{
  return vtkSurfaceSplatRasterizer::Surfels::Of(
    this->Positions, this->Normals, this->Axes0, this->Axes1, this->Colors);
}

//------------------------------------------------------------------------------
void vtkSurfelHierarchy::Build(const vtkSurfaceSplatRasterizer::Surfels& surfels)
{
  const std::size_t n = surfels.Count;
  this->SurfelCount = static_cast<vtkIdType>(n);
  this->Spacing = 0.0;
  this->LevelNodes.clear();
  this->LevelOffsets.clear();
  for (std::vector<float>* v : { &this->Normals, &this->Axes0, &this->Axes1, &this->Colors,
         &this->MassScales, &this->BlockAxes, &this->BlockReaches })
  {
    v->clear();
  }
  this->Positions.clear();
  this->Blocks.clear();
  this->BlockNodes.clear();
  this->Modified();
  if (n == 0 || n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
  {
    return;
  }

  // The level-1 cell is twice the mean spacing, or coarser where the bounds need more bits.
  glm::dvec3 lo(std::numeric_limits<double>::infinity());
  glm::dvec3 hi(-std::numeric_limits<double>::infinity());
  double area = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const glm::dvec3 p(
      surfels.Positions[3 * i], surfels.Positions[3 * i + 1], surfels.Positions[3 * i + 2]);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    area += SurfelArea(surfels, i);
  }
  const double spacing = std::sqrt(area / static_cast<double>(n));
  const glm::dvec3 extent = hi - lo;
  const double largest = std::max({ extent.x, extent.y, extent.z });
  if (!(spacing > 0.0) || !std::isfinite(spacing) || !std::isfinite(largest))
  {
    return;
  }
  this->Spacing = spacing;
  const double cell = std::max(2.0 * spacing, largest / ((1 << CellBits) - 1));

  // One sort by normal class, then Morton code of the level-1 cell, then index.
  struct Entry
  {
    std::uint64_t Key;
    std::uint32_t Index;
    bool operator<(const Entry& o) const
    {
      return this->Key < o.Key || (this->Key == o.Key && this->Index < o.Index);
    }
  };
  std::vector<Entry> entries(n);
  vtkSMPTools::For(0, static_cast<vtkIdType>(n),
    [&](vtkIdType begin, vtkIdType end)
    {
      const std::uint64_t top = (1 << CellBits) - 1;
      for (vtkIdType i = begin; i < end; ++i)
      {
        std::uint64_t morton = 0;
        for (int c = 0; c < 3; ++c)
        {
          const double q = std::floor((surfels.Positions[3 * i + c] - lo[c]) / cell);
          const std::uint64_t index = std::min(static_cast<std::uint64_t>(std::max(q, 0.0)), top);
          morton |= splat::SpreadBits(index) << c;
        }
        entries[i] = { NormalClass(surfels.Normals + 3 * i) << (3 * CellBits) | morton,
          static_cast<std::uint32_t>(i) };
      }
    });
  vtkSMPTools::Sort(entries.begin(), entries.end());
  std::vector<std::uint32_t> order(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    order[k] = entries[k].Index;
  }

  // Level l's nodes are the runs of equal keys with the last 3 (l - 1) bits dropped: nested
  // runs, level by level, until blocks hold about BlockSurfels surfels.
  const vtkIdType targetBlocks = std::max<vtkIdType>(1, static_cast<vtkIdType>(n) / BlockSurfels);
  std::size_t previous = n;
  for (int level = 1; level <= CellBits + 1; ++level)
  {
    const int shift = 3 * (level - 1);
    std::vector<std::uint32_t> starts;
    for (std::size_t k = 0; k < n; ++k)
    {
      if (k == 0 || (entries[k].Key >> shift) != (entries[k - 1].Key >> shift))
      {
        starts.push_back(static_cast<std::uint32_t>(k));
      }
    }
    const std::size_t count = starts.size();
    starts.push_back(static_cast<std::uint32_t>(n));
    this->LevelNodes.push_back(std::move(starts));
    if (static_cast<vtkIdType>(count) <= targetBlocks || count > MinimumMerge * previous)
    {
      break;
    }
    previous = count;
  }
  entries = std::vector<Entry>();

  // The nodes: the surfels in sorted order, then the merged nodes level by level, each from the
  // nodes of the level below.
  const int levels = static_cast<int>(this->LevelNodes.size());
  std::size_t nodeCount = n;
  for (const std::vector<std::uint32_t>& starts : this->LevelNodes)
  {
    this->LevelOffsets.push_back(static_cast<std::uint32_t>(nodeCount));
    nodeCount += starts.size() - 1;
  }
  this->Positions.resize(3 * nodeCount);
  for (std::vector<float>* v : { &this->Normals, &this->Axes0, &this->Axes1, &this->Colors })
  {
    v->resize(3 * nodeCount);
  }
  this->MassScales.assign(nodeCount, 1.0f);
  vtkSMPTools::For(0, static_cast<vtkIdType>(n),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType k = begin; k < end; ++k)
      {
        const std::size_t i = order[k];
        std::copy_n(surfels.Positions + 3 * i, 3, &this->Positions[3 * k]);
        std::copy_n(surfels.Normals + 3 * i, 3, &this->Normals[3 * k]);
        std::copy_n(surfels.Axes0 + 3 * i, 3, &this->Axes0[3 * k]);
        std::copy_n(surfels.Axes1 + 3 * i, 3, &this->Axes1[3 * k]);
        std::copy_n(surfels.Colors + 3 * i, 3, &this->Colors[3 * k]);
      }
    });
  order = std::vector<std::uint32_t>();
  const vtkSurfaceSplatRasterizer::Surfels sorted = this->GetNodes();
  std::vector<Moments> below;
  for (int level = 1; level <= levels; ++level)
  {
    const std::vector<std::uint32_t>& starts = this->LevelNodes[level - 1];
    const std::size_t count = starts.size() - 1;
    std::vector<Moments> moments(count);
    // The children of node j: the nodes of the level below that start within its run.
    const std::vector<std::uint32_t>* childStarts =
      level > 1 ? &this->LevelNodes[level - 2] : nullptr;
    const std::uint32_t offset = this->LevelOffsets[level - 1];
    vtkSMPTools::For(0, static_cast<vtkIdType>(count),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType j = begin; j < end; ++j)
        {
          Moments& m = moments[j];
          if (!childStarts)
          {
            m = Merge(starts[j], starts[j + 1],
              [&](std::size_t k) { return SurfelMoments(sorted, k); });
          }
          else
          {
            const auto first =
              std::lower_bound(childStarts->begin(), childStarts->end() - 1, starts[j]) -
              childStarts->begin();
            const auto last =
              std::lower_bound(childStarts->begin(), childStarts->end() - 1, starts[j + 1]) -
              childStarts->begin();
            m = Merge(static_cast<std::size_t>(first), static_cast<std::size_t>(last),
              [&](std::size_t k) -> const Moments& { return below[k]; });
          }
          // The node's splat: its moments on its tangent plane as the variance of its axes.
          const glm::dvec3 normal = glm::normalize(m.Normal);
          const glm::dvec3 t0 = glm::normalize(glm::cross(normal,
            std::abs(normal.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0)));
          const glm::dvec3 t1 = glm::cross(normal, t0);
          const double c00 = glm::dot(t0, m.Covariance * t0);
          const double c01 = glm::dot(t0, m.Covariance * t1);
          const double c11 = glm::dot(t1, m.Covariance * t1);
          const double mean = 0.5 * (c00 + c11);
          const double half = std::sqrt(0.25 * (c00 - c11) * (c00 - c11) + c01 * c01);
          const double major = std::max(mean + half, std::numeric_limits<double>::min());
          const double minor = std::max(mean - half, MinimumAspect * major);
          const double angle = 0.5 * std::atan2(2.0 * c01, c00 - c11);
          const glm::dvec3 e0 = std::cos(angle) * t0 + std::sin(angle) * t1;
          const glm::dvec3 e1 = glm::cross(normal, e0);
          const glm::dvec3 a0 = std::sqrt(2.0 * major) * e0;
          const glm::dvec3 a1 = std::sqrt(2.0 * minor) * e1;
          const std::size_t out = offset + static_cast<std::size_t>(j);
          for (int c = 0; c < 3; ++c)
          {
            this->Positions[3 * out + c] = m.Position[c];
            this->Normals[3 * out + c] = static_cast<float>(normal[c]);
            this->Axes0[3 * out + c] = static_cast<float>(a0[c]);
            this->Axes1[3 * out + c] = static_cast<float>(a1[c]);
            this->Colors[3 * out + c] = static_cast<float>(m.Color[c]);
          }
          this->MassScales[out] = static_cast<float>(m.Mass / (2.0 * std::sqrt(major * minor)));
        }
      });
    below = std::move(moments);
  }

  // Blocks: the top level's nodes, with their bounding spheres, normal cones and largest axes.
  const std::vector<std::uint32_t>& blocks = this->LevelNodes.back();
  const std::size_t blockCount = blocks.size() - 1;
  this->Blocks.resize(blockCount);
  this->BlockAxes.assign(blockCount * (levels + 1), 0.0f);
  this->BlockReaches.assign(blockCount * (levels + 1), 0.0f);
  this->BlockNodes.resize(levels * (blockCount + 1));
  for (int level = 1; level <= levels; ++level)
  {
    this->BlockNodes[level * (blockCount + 1) - 1] =
      static_cast<std::uint32_t>(this->LevelNodes[level - 1].size() - 1);
  }
  auto axisLength = [](const float* axis)
  { return std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]); };
  vtkSMPTools::For(0, static_cast<vtkIdType>(blockCount),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType b = begin; b < end; ++b)
      {
        Block& block = this->Blocks[b];
        glm::dvec3 low(std::numeric_limits<double>::infinity());
        glm::dvec3 high(-std::numeric_limits<double>::infinity());
        glm::dvec3 normals(0.0);
        float* axes = &this->BlockAxes[b * (levels + 1)];
        float* reaches = &this->BlockReaches[b * (levels + 1)];
        for (std::uint32_t k = blocks[b]; k < blocks[b + 1]; ++k)
        {
          const double* p = sorted.Positions + 3 * k;
          low = glm::min(low, glm::dvec3(p[0], p[1], p[2]));
          high = glm::max(high, glm::dvec3(p[0], p[1], p[2]));
          const float* n = sorted.Normals + 3 * k;
          normals += glm::dvec3(n[0], n[1], n[2]);
          axes[0] = std::max(
            { axes[0], axisLength(sorted.Axes0 + 3 * k), axisLength(sorted.Axes1 + 3 * k) });
        }
        reaches[0] = axes[0];
        block.ConeAxis = glm::length(normals) > 0.0 ? glm::normalize(normals) : glm::dvec3(0.0);
        double cosine = 1.0;
        for (std::uint32_t k = blocks[b]; k < blocks[b + 1]; ++k)
        {
          const float* n = sorted.Normals + 3 * k;
          cosine = std::min(cosine, glm::dot(block.ConeAxis, glm::dvec3(n[0], n[1], n[2])));
        }
        block.ConeAngle = std::acos(std::max(-1.0, cosine));
        for (int level = 1; level <= levels; ++level)
        {
          const std::vector<std::uint32_t>& starts = this->LevelNodes[level - 1];
          const auto first = std::lower_bound(starts.begin(), starts.end() - 1, blocks[b]);
          const auto last = std::lower_bound(starts.begin(), starts.end() - 1, blocks[b + 1]);
          this->BlockNodes[(level - 1) * (blockCount + 1) + b] =
            static_cast<std::uint32_t>(first - starts.begin());
          double squares = 0.0;
          reaches[level] = reaches[0]; // nodes seen at a grazing angle draw their surfels
          for (auto node = first; node != last; ++node)
          {
            const std::size_t out = this->LevelOffsets[level - 1] + (node - starts.begin());
            const double major = axisLength(&this->Axes0[3 * out]);
            const double spacing =
              this->MassScales[out] * major * axisLength(&this->Axes1[3 * out]);
            squares += std::max(major * major, spacing);
            reaches[level] = std::max(reaches[level], static_cast<float>(major));
          }
          axes[level] = static_cast<float>(std::sqrt(squares / (last - first)));
        }
        block.Low = low;
        block.High = high;
        block.Center = 0.5 * (low + high);
        block.Radius = 0.5 * glm::length(high - low);
      }
    });
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfelHierarchy::Select(const vtkSurfaceSplatRasterizer::Camera& camera,
  double variance, std::vector<std::uint32_t>& items) const
{
  return this->SelectBlocks(camera, variance, items, nullptr);
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfelHierarchy::Select(const vtkSurfaceSplatRasterizer::Camera& camera,
  double variance, std::vector<std::uint32_t>& items, std::vector<BackRegion>& backRegions) const
{
  return this->SelectBlocks(camera, variance, items, &backRegions);
}

//------------------------------------------------------------------------------
vtkIdType vtkSurfelHierarchy::SelectBlocks(const vtkSurfaceSplatRasterizer::Camera& camera,
  double variance, std::vector<std::uint32_t>& items, std::vector<BackRegion>* backRegions) const
{
  items.clear();
  if (backRegions)
  {
    backRegions->clear();
  }
  const int levels = this->GetNumberOfLevels();
  if (levels == 1)
  {
    return 0;
  }
  // A model-space length l at eye depth z spans at most l * scale * pixelsPerUnit / z pixels
  // (without the division for a parallel projection): scale is the model-to-eye matrix's
  // largest column norm.
  const glm::dmat4& modelToEye = camera.ModelToEye;
  const glm::dvec3 columns(glm::length(glm::dvec3(modelToEye[0])),
    glm::length(glm::dvec3(modelToEye[1])), glm::length(glm::dvec3(modelToEye[2])));
  const double scale = std::max({ columns.x, columns.y, columns.z });
  // Normal cones keep their angles only without a non-uniform scale. Angles between normals
  // and view vectors are then the same in model space, where the grazing test needs no
  // transform: the view vector to a point is its offset from the eye, or the view direction.
  const bool uniform =
    std::max({ columns.x, columns.y, columns.z }) - std::min({ columns.x, columns.y, columns.z }) <=
    1e-9 * scale;
  const glm::dmat4 eyeToModel = glm::inverse(modelToEye);
  const glm::dvec3 eyeInModel(eyeToModel[3]);
  const glm::dvec3 viewInModel(eyeToModel * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  const glm::dmat4& P = camera.EyeToClip;
  const bool perspective = P[2][3] != 0.0;
  const double pixelsPerUnit =
    0.5 * std::max(std::abs(P[0][0]) * camera.Viewport.x, std::abs(P[1][1]) * camera.Viewport.y);

  const glm::dmat3 normalToEye = glm::transpose(glm::inverse(glm::dmat3(modelToEye)));
  const std::vector<std::uint32_t>& blocks = this->LevelNodes.back();
  const vtkIdType blockCount = static_cast<vtkIdType>(blocks.size()) - 1;
  // The nodes of block b at level `level` (level > 0), as indices into LevelNodes[level - 1].
  auto nodesOf = [&](vtkIdType b, int level)
  {
    const std::uint32_t* first = &this->BlockNodes[(level - 1) * (blockCount + 1) + b];
    return std::make_pair(first[0], first[1]);
  };
  // The splats of block b at level `level`, in order, to emit(item, surfels it stands for):
  // its nodes, but for those seen at a grazing angle, whose surfels are drawn instead. Blocks
  // whose normal cones keep clear of grazing angles skip the test node by node.
  auto visit = [&](vtkIdType b, int level, bool grazing, auto&& emit)
  {
    if (level == 0)
    {
      for (std::uint32_t k = blocks[b]; k < blocks[b + 1]; ++k)
      {
        emit(k, 0);
      }
      return;
    }
    const std::vector<std::uint32_t>& starts = this->LevelNodes[level - 1];
    const auto range = nodesOf(b, level);
    const std::uint32_t offset = this->LevelOffsets[level - 1];
    for (auto j = range.first; j < range.second; ++j)
    {
      const std::size_t node = offset + j;
      bool edgeOn = false;
      if (grazing)
      {
        const glm::dvec3 n(
          this->Normals[3 * node], this->Normals[3 * node + 1], this->Normals[3 * node + 2]);
        const glm::dvec3 p(this->Positions[3 * node], this->Positions[3 * node + 1],
          this->Positions[3 * node + 2]);
        const glm::dvec3 normal = uniform ? n : normalToEye * n;
        const glm::dvec3 view = uniform ? (perspective ? p - eyeInModel : viewInModel)
          : (perspective ? glm::dvec3(modelToEye * glm::dvec4(p, 1.0))
                         : glm::dvec3(0.0, 0.0, -1.0));
        const double cosine = glm::dot(normal, view);
        edgeOn = cosine * cosine <
          GrazingCosine * GrazingCosine * glm::dot(normal, normal) * glm::dot(view, view);
      }
      if (edgeOn)
      {
        for (std::uint32_t k = starts[j]; k < starts[j + 1]; ++k)
        {
          emit(k, 0);
        }
      }
      else
      {
        emit(static_cast<std::uint32_t>(node), starts[j + 1] - starts[j]);
      }
    }
  };
  // The range of angles between the block's normals and the view directions to the points of
  // its sphere: the angle between its cone's axis and the view direction to its center, widened
  // by the cone's half angle and the angle the sphere subtends; all angles without a cone.
  auto viewAngles = [&](const Block& block, const glm::dvec3& center)
  {
    const std::pair<double, double> all(0.0, vtkMath::Pi());
    if (!uniform || glm::dot(block.ConeAxis, block.ConeAxis) == 0.0)
    {
      return all;
    }
    double subtended = 0.0;
    glm::dvec3 view(0.0, 0.0, -1.0);
    if (perspective)
    {
      const double distance = glm::length(center);
      const double radius = scale * block.Radius;
      if (!(distance > radius))
      {
        return all;
      }
      subtended = std::asin(radius / distance);
      view = center / distance;
    }
    const double axis = std::acos(
      std::min(1.0, std::max(-1.0, glm::dot(glm::normalize(normalToEye * block.ConeAxis), view))));
    const double spread = block.ConeAngle + subtended + 1e-3;
    return std::make_pair(axis - spread, axis + spread);
  };
  const double grazingAngle = std::acos(GrazingCosine);

  // Per block: the level it draws, whether all its normals face away, whether some node may be
  // seen at a grazing angle, whether it may hold a silhouette, and how many items it emits.
  std::vector<int> chosen(blockCount);
  std::vector<char> away(blockCount);
  std::vector<char> grazing(blockCount);
  std::vector<char> silhouette(blockCount);
  std::vector<std::size_t> counts(blockCount);
  vtkSMPTools::For(0, blockCount,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType b = begin; b < end; ++b)
      {
        const Block& block = this->Blocks[b];
        const glm::dvec3 center = glm::dvec3(modelToEye * glm::dvec4(block.Center, 1.0));
        const double nearest = -center.z - scale * block.Radius;
        const double pixels = perspective
          ? (nearest > 0.0 ? scale * pixelsPerUnit / nearest
                           : std::numeric_limits<double>::infinity())
          : scale * pixelsPerUnit;
        int level = levels - 1;
        for (; level > 0; --level)
        {
          const double axis = pixels * this->BlockAxes[b * levels + level];
          if (0.5 * axis * axis <= variance)
          {
            break;
          }
        }
        chosen[b] = level;
        const std::pair<double, double> angles = viewAngles(block, center);
        away[b] = backRegions && angles.second < 0.5 * vtkMath::Pi();
        grazing[b] = angles.second > grazingAngle && angles.first < vtkMath::Pi() - grazingAngle;
        silhouette[b] = angles.first < 0.5 * vtkMath::Pi() && angles.second > 0.5 * vtkMath::Pi();
        std::size_t count = 0;
        if (level > 0 && !grazing[b])
        {
          const auto range = nodesOf(b, level);
          count = static_cast<std::size_t>(range.second - range.first);
        }
        else
        {
          visit(b, level, grazing[b], [&](std::uint32_t, std::uint32_t) { ++count; });
        }
        counts[b] = count;
      }
    });
  // The blocks that may face the eye first, then those facing away, each in block order.
  std::vector<std::size_t> offsets(blockCount);
  std::size_t total = 0;
  for (int facingAway = 0; facingAway < 2; ++facingAway)
  {
    for (vtkIdType b = 0; b < blockCount; ++b)
    {
      if (away[b] == facingAway)
      {
        offsets[b] = total;
        total += counts[b];
        if (facingAway)
        {
          const Block& block = this->Blocks[b];
          backRegions->push_back({ offsets[b], total, block.Low, block.High,
            this->BlockReaches[b * levels + chosen[b]] });
        }
      }
    }
  }
  items.resize(total);
  // A block whose normals may be seen both facing the eye and facing away may hold splats on
  // both sides of a silhouette, at depths closer than their z threshold. A pixel's fragments
  // take contributions in the order they come, so such a block's splats are drawn front to
  // back: the front sheet's form the fragment, and the back sheet's join it or fall behind it
  // as behind any opaque surface. (In Morton order, back splats that came first took the
  // fragment, whose filtered normal then turned edge-on and was shaded dark.)
  const glm::dvec4 depthRow(-modelToEye[0][2], -modelToEye[1][2], -modelToEye[2][2],
    -modelToEye[3][2]);
  std::vector<vtkIdType> merged(blockCount, 0);
  vtkSMPTools::For(0, blockCount,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<std::uint64_t> byDepth;
      for (vtkIdType b = begin; b < end; ++b)
      {
        std::uint32_t* const first = items.data() + offsets[b];
        std::uint32_t* out = first;
        vtkIdType represented = 0;
        visit(b, chosen[b], grazing[b],
          [&](std::uint32_t item, std::uint32_t surfels)
          {
            *out++ = item;
            represented += surfels;
          });
        merged[b] = represented;
        if (silhouette[b])
        {
          byDepth.clear();
          for (const std::uint32_t* item = first; item != out; ++item)
          {
            const double* p = &this->Positions[3 * *item];
            const double depth = glm::dot(depthRow, glm::dvec4(p[0], p[1], p[2], 1.0));
            byDepth.push_back(splat::DepthOrderKey(static_cast<float>(depth), *item));
          }
          std::sort(byDepth.begin(), byDepth.end());
          std::transform(byDepth.begin(), byDepth.end(), first, splat::IndexOfKey);
        }
      }
    });
  return std::accumulate(merged.begin(), merged.end(), vtkIdType(0));
}

//------------------------------------------------------------------------------
void vtkSurfelHierarchy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSurfels: " << this->SurfelCount << "\n";
  os << indent << "Spacing: " << this->Spacing << "\n";
  for (int level = 0; level < this->GetNumberOfLevels(); ++level)
  {
    os << indent << "Level " << level << ": " << this->GetNumberOfNodes(level) << " nodes\n";
  }
}
