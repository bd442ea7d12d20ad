// SPDX-License-Identifier: BSD-3-Clause
// Hardware picking of splats by point: vtkHardwareSelector over a splatted grid returns, at the
// pixel where a point projects, that point's id in the input, with either backend: for an input
// starting with invalid points (skipped by the mapper), where surfel indices and point ids
// differ, and for one without.
#include "SplatTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"

#include <cstdio>
#include <limits>

int main(int, char*[])
{
  const double center[3] = { 0.0, 0.0, 0.0 };
  const double u[3] = { 0.1, 0.0, 0.0 };
  const double v[3] = { 0.0, 0.1, 0.0 };
  vtkSmartPointer<vtkPolyData> grid = splattest::SurfelPlane(center, u, v, 15, 15);
  // Three invalid points first: a NaN position, a zero normal, a negative radius.
  auto input = vtkSmartPointer<vtkPolyData>::New();
  input->DeepCopy(grid);
  vtkPoints* points = input->GetPoints();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vtkDataArray* normals = input->GetPointData()->GetNormals();
  vtkDataArray* radii = input->GetPointData()->GetArray("Radius");
  const vtkIdType invalid = 3;
  points->SetPoint(0, nan, 0.0, 0.0);
  normals->SetTuple3(1, 0.0, 0.0, 0.0);
  radii->SetTuple1(2, -1.0);

  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(input);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  auto window = splattest::MakeRenderWindow(300, 300);
  window->AddRenderer(renderer);
  renderer->GetActiveCamera()->SetPosition(0.2, -0.3, 3.0);
  renderer->GetActiveCamera()->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->ResetCameraClippingRange();

  int failures = 0;
  // With the invalid points, then the grid alone (no point skipped: surfel i is point i).
  for (vtkPolyData* data : { input.Get(), grid.Get() })
  {
    for (int backend : { vtkSplatBackend::CPU, vtkSplatBackend::OPENGL })
    {
      mapper->SetInputData(data);
      mapper->SetBackend(backend);
      window->Render();
      for (vtkIdType id : { invalid, vtkIdType(100), vtkIdType(112), vtkIdType(224) })
      {
        double p[3];
        data->GetPoint(id, p);
        renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
        renderer->WorldToDisplay();
        const double* display = renderer->GetDisplayPoint();
        const auto x = static_cast<unsigned int>(display[0]);
        const auto y = static_cast<unsigned int>(display[1]);
        vtkNew<vtkHardwareSelector> selector;
        selector->SetRenderer(renderer);
        selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_POINTS);
        selector->SetArea(x, y, x, y);
        vtkSmartPointer<vtkSelection> selection;
        selection.TakeReference(selector->Select());
        vtkIdType picked = -1;
        if (selection && selection->GetNumberOfNodes() == 1)
        {
          vtkSelectionNode* node = selection->GetNode(0);
          auto* ids = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
          if (node->GetProperties()->Get(vtkSelectionNode::PROP()) == actor.Get() && ids &&
            ids->GetNumberOfTuples() == 1)
          {
            picked = ids->GetValue(0);
          }
        }
        std::printf("%s: point %lld at pixel (%u, %u) picked as %lld\n",
          vtkSplatBackend::GetBackendAsString(backend), static_cast<long long>(id), x, y,
          static_cast<long long>(picked));
        if (picked != id)
        {
          ++failures;
        }
      }
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
