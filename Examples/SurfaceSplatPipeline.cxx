// SPDX-License-Identifier: BSD-3-Clause
// The shortest Splat pipeline: a PLY mesh or point cloud rendered as EWA surface splats to a PNG.
//   surface_splat_pipeline input.ply output.png
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkWindowToImageFilter.h"

#include <cstdlib>
#include <iostream>

int main(int argc, char* argv[])
{
  if (argc != 3 || !vtkPLYReader::CanReadFile(argv[1]))
  {
    std::cerr << "Usage: " << argv[0] << " input.ply output.png (input.ply must be readable)\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(argv[1]);

  // Each vertex becomes a surfel: a normal and a radius that covers the gaps to its neighbors.
  vtkNew<vtkSurfelGenerator> surfels;
  surfels->SetInputConnection(reader->GetOutputPort());

  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputConnection(surfels->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(800, 800);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  window->Render();

  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(window);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(argv[2]);
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
  return EXIT_SUCCESS;
}
