// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkCaptureAwarePLYReader
 * @brief   vtkPLYReader that leaves 3D Gaussian Splatting captures to vtkGaussianSplatReader
 *
 * ParaView offers a file to every reader whose CanReadFile accepts it, and asks the user to
 * choose (Open Data With...) when more than one does. VTK's PLY reader accepts every PLY file,
 * captures included, and ParaView 5.11 to 5.13 have no reader priority. The plugin therefore
 * makes this class the core of ParaView's own PLY Reader proxy (internal_sources/PLYReaderCore
 * in SplatReaders.xml): meshes and point clouds open with PLY Reader as before, captures with
 * Gaussian Splat Reader, neither with a question. Reading is vtkPLYReader's, unchanged.
 *
 * @sa vtkGaussianSplatReader
 */
#ifndef vtkCaptureAwarePLYReader_h
#define vtkCaptureAwarePLYReader_h

#include "SplatRepresentationsModule.h" // For export macro
#include "vtkPLYReader.h"

class SPLATREPRESENTATIONS_EXPORT vtkCaptureAwarePLYReader : public vtkPLYReader
{
public:
  static vtkCaptureAwarePLYReader* New();
  vtkTypeMacro(vtkCaptureAwarePLYReader, vtkPLYReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * 1 for the PLY files vtkPLYReader reads that are not captures
   * (vtkGaussianSplatReader::IsGaussianSplatFile), else 0.
   */
  static int CanReadFile(VTK_FILEPATH const char* filename);

protected:
  vtkCaptureAwarePLYReader() = default;
  ~vtkCaptureAwarePLYReader() override = default;

private:
  vtkCaptureAwarePLYReader(const vtkCaptureAwarePLYReader&) = delete;
  void operator=(const vtkCaptureAwarePLYReader&) = delete;
};

#endif
