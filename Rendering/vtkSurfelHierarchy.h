// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSurfelHierarchy
 * @brief   levels of detail of opaque surfels, for splats far below a pixel
 *
 * Where a surface is sampled much more densely than the screen's pixels, each pixel sums many
 * minified splats (see vtkSurfaceSplatRasterizer::SetMinifiedVariance) whose setup costs more
 * than what they add. vtkSurfelHierarchy merges them ahead of time, once per surfel set, into
 * coarser levels, and picks per frame the coarsest level that still draws minified splats.
 *
 * Level 0 is the surfels themselves, kept as a copy in the order below, so that a frame reads
 * them, as it reads the merged nodes, block by block from consecutive memory. A node of level
 * l > 0 merges the surfels whose positions
 * lie in one cell of side h 2^l of a grid, h the surfels' mean spacing (the square root of their
 * mean area), and whose normals share their dominant axis and its sign, so that the two sides of
 * a thin part never merge. A node is one elliptical Gaussian: the merged surfels' mass (the sum
 * of their areas; an EWA splat's resampling kernel integrates to its area in pixels), their
 * mass-weighted mean position, normal and color, and their Gaussians' second moments about that
 * mean, projected on its tangent plane, as the variance of its axes (0.5 |a|^2 each, as for a
 * surfel). Matching the moments, not the area, keeps the merged splat as sharp as the surfels it
 * replaces; its mass scale, the ratio of its mass to the area its axes span, restores its weight.
 *
 * One sort of the surfels by normal class and by the Morton code of their cells makes every
 * node a run of consecutive sorted surfels and every level's nodes sorted the same way. The
 * nodes of the top level are blocks: each holds its nodes of every level contiguously. Per
 * frame, Select() picks for each block the coarsest level whose splats are all minified at the
 * block's nearest depth, and lists the splats to draw, block by block, in that order; a block
 * that may hold a silhouette lists its splats front to back, so that the front sheet's splats
 * form the rim's fragments before the back sheet's come.
 *
 * @sa vtkSurfaceSplatRasterizer vtkSurfaceSplatMapper
 */
#ifndef vtkSurfelHierarchy_h
#define vtkSurfelHierarchy_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkObject.h"
#include "vtkSurfaceSplatRasterizer.h" // For Surfels, Camera

#include <glm/glm.hpp> // For the regions' spheres

#include <cstdint> // For std::uint32_t
#include <vector>  // For the levels

class SPLATRENDERING_EXPORT vtkSurfelHierarchy : public vtkObject
{
public:
  static vtkSurfelHierarchy* New();
  vtkTypeMacro(vtkSurfelHierarchy, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Builds the levels of opaque plain surfels (neither opacities nor curvatures are read). A
   * set without a finite positive mean area, or too large to number in 32 bits, gets level 0
   * only.
   */
  void Build(const vtkSurfaceSplatRasterizer::Surfels& surfels);

  /// The number of surfels it was built from (level 0).
  vtkIdType GetNumberOfSurfels() const { return this->SurfelCount; }

  /// Levels, level 0 included, and the nodes of each.
  int GetNumberOfLevels() const { return static_cast<int>(this->LevelNodes.size()) + 1; }
  vtkIdType GetNumberOfNodes(int level) const;

  /**
   * Every node as a surfel (opaque, no curvatures): the surfels of level 0 in sorted order,
   * then the merged nodes of every level above 0, level by level; and the mass scale of each
   * (1 for the surfels).
   */
  vtkSurfaceSplatRasterizer::Surfels GetNodes() const;
  const float* GetMassScales() const { return this->MassScales.data(); }

  /**
   * The splats to draw for a camera: for each block the nodes of the coarsest level whose
   * splats' warped basis variance (see vtkSurfaceSplatRasterizer::SetMinifiedVariance) is at
   * most `variance` pixels^2 at the block's nearest depth, or its surfels: item i is node i of
   * GetNodes(), and each surfel is drawn once, by itself or by a node that stands for it.
   * Returns the number of surfels the merged nodes among them stand for. Degenerate input
   * (level 0 only) selects nothing.
   */
  vtkIdType Select(const vtkSurfaceSplatRasterizer::Camera& camera, double variance,
    std::vector<std::uint32_t>& items) const;

  /**
   * A region whose splats all face away from the eye (with two-sided lighting they are drawn,
   * and hidden wherever a nearer surface covers them): items [Begin, End) of a selection, the
   * box in model coordinates that holds their splats' centers, and the largest axis of its
   * splats.
   */
  struct BackRegion
  {
    std::size_t Begin = 0;
    std::size_t End = 0;
    glm::dvec3 Low{ 0.0 };
    glm::dvec3 High{ 0.0 };
    double Reach = 0.0;
  };

  /**
   * Select() that also lists the regions whose splats all face away from the eye: their items
   * come last, region by region, after those of the regions that may face it.
   */
  vtkIdType Select(const vtkSurfaceSplatRasterizer::Camera& camera, double variance,
    std::vector<std::uint32_t>& items, std::vector<BackRegion>& backRegions) const;

protected:
  vtkSurfelHierarchy() = default;
  ~vtkSurfelHierarchy() override = default;

private:
  vtkSurfelHierarchy(const vtkSurfelHierarchy&) = delete;
  void operator=(const vtkSurfelHierarchy&) = delete;

  vtkIdType SelectBlocks(const vtkSurfaceSplatRasterizer::Camera& camera, double variance,
    std::vector<std::uint32_t>& items, std::vector<BackRegion>* backRegions) const;

  vtkIdType SurfelCount = 0;
  double Spacing = 0.0;
  // Per level above 0: where each of its nodes starts among the sorted surfels (one past the
  // end last), and where its nodes start among all nodes.
  std::vector<std::vector<std::uint32_t>> LevelNodes;
  std::vector<std::uint32_t> LevelOffsets;
  // The nodes: the sorted surfels, then the merged nodes level by level.
  std::vector<double> Positions;
  std::vector<float> Normals;
  std::vector<float> Axes0;
  std::vector<float> Axes1;
  std::vector<float> Colors;
  std::vector<float> MassScales;
  // A node of the top level: its surfels' bounding box and sphere (of their centers) and the
  // cone of its surfels' normals.
  struct Block
  {
    glm::dvec3 Low{ 0.0 };
    glm::dvec3 High{ 0.0 };
    glm::dvec3 Center{ 0.0 };
    double Radius = 0.0;
    glm::dvec3 ConeAxis{ 0.0 };
    double ConeAngle = 0.0; // radians
  };
  std::vector<Block> Blocks;
  // Per block, per level (0 first): the root mean square of its nodes' larger axis or
  // spacing, which decides the level a frame draws; and the largest axis of the splats that
  // level draws, its nodes' or their surfels', which bounds how far they reach.
  std::vector<float> BlockAxes;
  std::vector<float> BlockReaches;
  // Per level above 0, per block and one past the last: the index of the block's first node
  // among the level's nodes.
  std::vector<std::uint32_t> BlockNodes;
};

#endif
