// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkGaussianSplatWriter
 * @brief   writes a 3D Gaussian Splatting kernel set as a .ply of the INRIA layout
 *
 * vtkGaussianSplatWriter writes the points of a vtkPointSet with the arrays
 * vtkGaussianSplatReader produces ("Scale", "Rotation", "Opacity", and "SphericalHarmonics" or
 * "Color") as a binary little-endian PLY file of the INRIA 3D Gaussian Splatting layout: vertex
 * properties x, y, z, nx, ny, nz (zero), f_dc_0..2, f_rest_0..(3m - 1) (channel-major), opacity
 * (the logit), scale_0..2 (the logarithms) and rot_0..3 (w first), all float. A capture
 * clipped, thresholded or transformed in a pipeline is thus saved in the format every 3DGS tool
 * reads, and vtkGaussianSplatReader reads it back with its values to float precision (the
 * logarithms and logits round once). Without "SphericalHarmonics" the DC coefficients come from
 * "Color" ((color - 0.5) / C0); peak opacities are clamped to [1e-7, 1 - 1e-7] so that their
 * logits stay finite.
 *
 * A missing or mis-sized array gives a vtkErrorMacro naming it and writes nothing.
 *
 * @sa vtkGaussianSplatReader
 */
#ifndef vtkGaussianSplatWriter_h
#define vtkGaussianSplatWriter_h

#include "SplatFiltersModule.h" // For export macro
#include "vtkWriter.h"

class vtkPointSet;

class SPLATFILTERS_EXPORT vtkGaussianSplatWriter : public vtkWriter
{
public:
  static vtkGaussianSplatWriter* New();
  vtkTypeMacro(vtkGaussianSplatWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The .ply file to write.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

protected:
  vtkGaussianSplatWriter();
  ~vtkGaussianSplatWriter() override;

  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  char* FileName = nullptr;

private:
  vtkGaussianSplatWriter(const vtkGaussianSplatWriter&) = delete;
  void operator=(const vtkGaussianSplatWriter&) = delete;
};

#endif
