// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfelSphereSource.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <cmath>

vtkStandardNewMacro(vtkSurfelSphereSource);

//------------------------------------------------------------------------------
vtkSurfelSphereSource::vtkSurfelSphereSource()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
int vtkSurfelSphereSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  const vtkIdType n = this->NumberOfPoints;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  radii->SetNumberOfTuples(n);
  radii->Fill(std::sqrt(4.0 * vtkMath::Pi() * this->Radius * this->Radius / n));
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfTuples(n);
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfTuples(n + 1);
  offsets->SetValue(n, n);

  // Point i at height z_i = 1 - (2 i + 1) / n and longitude i times the golden angle.
  const double golden = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  auto* xyz = static_cast<double*>(points->GetVoidPointer(0));
  float* nxyz = normals->GetPointer(0);
  vtkIdType* ids = connectivity->GetPointer(0);
  vtkIdType* starts = offsets->GetPointer(0);
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const double z = 1.0 - (2.0 * i + 1.0) / n;
        const double r = std::sqrt(1.0 - z * z);
        const double phi = golden * i;
        const double normal[3] = { r * std::cos(phi), r * std::sin(phi), z };
        for (int c = 0; c < 3; ++c)
        {
          xyz[3 * i + c] = this->Center[c] + this->Radius * normal[c];
          nxyz[3 * i + c] = static_cast<float>(normal[c]);
        }
        ids[i] = starts[i] = i;
      }
    });
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);

  output->SetPoints(points);
  output->SetVerts(vertices);
  output->GetPointData()->SetNormals(normals);
  output->GetPointData()->AddArray(radii);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSurfelSphereSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfPoints: " << this->NumberOfPoints << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "Center: (" << this->Center[0] << ", " << this->Center[1] << ", "
     << this->Center[2] << ")\n";
}
