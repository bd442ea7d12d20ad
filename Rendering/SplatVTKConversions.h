// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatVTKConversions.h
 * @brief VTK types to the GLM types of the splatting core, shared by the mappers.
 */
#ifndef SplatVTKConversions_h
#define SplatVTKConversions_h

#include "vtkMatrix4x4.h"

#include <glm/glm.hpp>

namespace splat
{
/// A vtkMatrix4x4 (row-major, element (row, column)) as a column-major GLM matrix.
inline glm::dmat4 ToGlm(vtkMatrix4x4* m)
{
  glm::dmat4 result;
  for (int row = 0; row < 4; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      result[column][row] = m->GetElement(row, column);
    }
  }
  return result;
}
} // namespace splat

#endif
