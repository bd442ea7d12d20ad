// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCaptureAwarePLYReader.h"

#include "vtkGaussianSplatReader.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkCaptureAwarePLYReader);

//------------------------------------------------------------------------------
int vtkCaptureAwarePLYReader::CanReadFile(const char* filename)
{
  return vtkPLYReader::CanReadFile(filename) &&
      !vtkGaussianSplatReader::IsGaussianSplatFile(filename)
    ? 1
    : 0;
}

//------------------------------------------------------------------------------
void vtkCaptureAwarePLYReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
