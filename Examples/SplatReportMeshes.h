// SPDX-License-Identifier: BSD-3-Clause
// splat_report's mesh scenes: real scans and a finely tessellated sphere, drawn by the surfels of
// their vertices (vtkSurfelGenerator) against the mesh itself drawn by vtkPolyDataMapper at 4x4
// supersampling. Each scan is seen whole and magnified, the armadillo also from a point cloud
// scattered over its triangles (a scan without its mesh), and the sphere's million vertices are
// seen whole, many to a pixel: the surface mapper's defaults are measured where splats are
// smaller than a pixel, where they are several pixels wide, and in between.
#ifndef SplatReportMeshes_h
#define SplatReportMeshes_h

#include "SplatExampleUtilities.h"
#include "SplatFileReaders.h"
#include "SplatReportCases.h"
#include "vtkSplatPLYReader.h"
#include "vtkSurfelGenerator.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkPolyDataPointSampler.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace splatreport
{
/// A mesh seen from one camera.
struct MeshScene
{
  std::string Name;                  ///< the --scenes name and the images' prefix
  std::string What;                  ///< what the mesh is, for the Markdown text
  std::string View;                  ///< how it is seen, for the Markdown text
  vtkSmartPointer<vtkPolyData> Mesh; ///< triangles with point normals
  double Azimuth = 0.0;              ///< degrees around the view up, from the +z view
  double Elevation = 0.0;            ///< degrees
  double Dolly = 1.0;                ///< after ResetCamera: above 1 magnifies
  double Color[3] = { 0.85, 0.75, 0.6 };
  /// Above 0: the surfels come from points scattered at random over the triangles about this
  /// far apart, with the normals and radii vtkSurfelGenerator estimates for a point cloud (a
  /// scan's points, irregular, without the mesh), instead of from the mesh's vertices.
  double SampleDistance = 0.0;

  /// Places the camera: the mesh's bounds reset into a 30-degree view from +z, then turned and
  /// moved closer.
  void PlaceCamera(vtkRenderer* renderer) const
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0, 0, 1);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(30.0);
    renderer->ResetCamera(this->Mesh->GetBounds());
    camera->Azimuth(this->Azimuth);
    camera->Elevation(this->Elevation);
    camera->OrthogonalizeViewUp();
    camera->Dolly(this->Dolly);
    renderer->ResetCameraClippingRange(this->Mesh->GetBounds());
  }
};

/// The mean length of a mesh's polygon edges (each interior edge counted from both sides).
inline double MeanEdgeLength(vtkPolyData* mesh)
{
  double sum = 0.0;
  vtkIdType edges = 0;
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(ids);)
  {
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
    {
      double a[3], b[3];
      mesh->GetPoint(ids->GetId(i), a);
      mesh->GetPoint(ids->GetId((i + 1) % ids->GetNumberOfIds()), b);
      sum += std::sqrt(vtkMath::Distance2BetweenPoints(a, b));
      ++edges;
    }
  }
  return edges > 0 ? sum / edges : 0.0;
}

/// What a scene's surfels are (`count` of them), for the Markdown text.
inline std::string SurfelsText(const MeshScene& scene, vtkIdType count)
{
  vtkNew<vtkSurfelGenerator> generator;
  return scene.SampleDistance > 0.0
    ? "vtkSurfelGenerator on a point cloud scattered at random over the triangles "
      "(vtkPolyDataPointSampler, about " + Fixed(scene.SampleDistance, 3) + " apart, three times "
      "the vertices' density; " + std::to_string(count) + " points), with the normals it fits "
      "and the radius from the mean distance to the " +
      std::to_string(generator->GetNumberOfNeighbors()) + " nearest points"
    : "vtkSurfelGenerator on the mesh's vertices (" + std::to_string(count) +
      " points, radius from the longest edge at each vertex)";
}

/// The surfels of a scene: its mesh's vertices, or a point cloud sampled from its triangles.
inline vtkSmartPointer<vtkPolyData> SceneSurfels(const MeshScene& scene)
{
  vtkNew<vtkSurfelGenerator> generator;
  if (scene.SampleDistance > 0.0)
  {
    vtkNew<vtkPolyDataPointSampler> sampler;
    sampler->SetInputData(scene.Mesh);
    sampler->SetPointGenerationModeToRandom();
    sampler->SetDistance(scene.SampleDistance);
    sampler->GenerateVertexPointsOff();
    sampler->GenerateEdgePointsOff();
    sampler->GenerateVerticesOn();
    sampler->Update();
    // Points only: the cloud's normals are estimated, not the mesh's.
    vtkNew<vtkPolyData> cloud;
    cloud->SetPoints(sampler->GetOutput()->GetPoints());
    cloud->SetVerts(sampler->GetOutput()->GetVerts());
    generator->SetInputData(cloud);
  }
  else
  {
    generator->SetInputData(scene.Mesh);
  }
  generator->Update();
  return generator->GetOutput();
}

/// The mesh with smooth, consistently oriented point normals, the same for its triangles and its
/// surfels. Vertices that no triangle uses are dropped (vtkSurfelGenerator gives them no
/// radius), so that triangles and surfels cover the same surface.
inline vtkSmartPointer<vtkPolyData> SmoothMesh(vtkPolyData* mesh)
{
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(mesh);
  clean->PointMergingOff();
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(clean->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOn();
  normals->Update();
  return normals->GetOutput();
}

/// The Stanford bunny of the shared data, or nullptr (with a note) when it is absent.
inline vtkSmartPointer<vtkPolyData> BunnyMesh(std::vector<std::string>& notes)
{
  const std::string file = splatexample::BunnyFile();
  if (!vtkSplatPLYReader::CanReadFile(file.c_str()))
  {
    notes.push_back("bunny scenes skipped: " + file + " is absent (set SPLAT_DATA_DIR)");
    return nullptr;
  }
  vtkNew<vtkSplatPLYReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  return SmoothMesh(reader->GetOutput());
}

/// CGAL's armadillo (Debian's libcgal-demo), or nullptr (with a note) when it is absent.
inline vtkSmartPointer<vtkPolyData> ArmadilloMesh(std::vector<std::string>& notes)
{
  if (!vtksys::SystemTools::FileExists(splatexample::CgalData, true))
  {
    notes.push_back(std::string("armadillo scenes skipped: ") + splatexample::CgalData +
      " is absent (Debian package libcgal-demo)");
    return nullptr;
  }
  return SmoothMesh(splatexample::ReadCgalArmadillo());
}

/// A unit sphere of about `vertices` vertices (a latitude-longitude tessellation).
inline vtkSmartPointer<vtkPolyData> SphereMesh(long long vertices)
{
  vtkNew<vtkSphereSource> sphere;
  const int resolution = std::max(8, static_cast<int>(std::sqrt(static_cast<double>(vertices))));
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution);
  sphere->SetRadius(1.0);
  sphere->Update();
  return sphere->GetOutput();
}

/// The mesh scenes among `wanted` (scene names), in the report's order; scenes whose data are
/// absent are left out with a note.
inline std::vector<MeshScene> MeshScenes(
  const std::vector<std::string>& wanted, long long sphereVertices, std::vector<std::string>& notes)
{
  const auto wants = [&](const std::string& name)
  { return std::find(wanted.begin(), wanted.end(), name) != wanted.end(); };
  std::vector<MeshScene> scenes;
  // A scan seen whole (dolly 1.3), then its `part` magnified (dolly `closeup`); `read` only when
  // either view is wanted.
  const auto addScan = [&](const std::string& name, const std::string& what, double azimuth,
                         const char* part, double closeup,
                         const std::function<vtkSmartPointer<vtkPolyData>()>& read)
  {
    const std::string magnified = name + "-closeup";
    const std::string points = name + "-points";
    if (!wants(name) && !wants(magnified) && !wants(points))
    {
      return;
    }
    if (vtkSmartPointer<vtkPolyData> mesh = read())
    {
      if (wants(name))
      {
        scenes.push_back({ name, what, "seen whole", mesh, azimuth, 10.0, 1.3 });
      }
      if (wants(magnified))
      {
        scenes.push_back(
          { magnified, what, part + std::string(" seen magnified"), mesh, azimuth, 10.0, closeup });
      }
      if (wants(points))
      {
        // Three times the vertices' density, so that the splats are about as large on screen.
        const double spacing = MeanEdgeLength(mesh) / std::sqrt(3.0);
        scenes.push_back({ points, what, part + std::string(" seen magnified"), mesh, azimuth,
          10.0, closeup, { 0.85, 0.75, 0.6 }, spacing });
      }
    }
  };
  addScan("bunny",
    "The Stanford bunny (range scans merged by zippering, `bunny.ply` of the shared data)", 25.0,
    "its flank", 4.0, [&] { return BunnyMesh(notes); });
  addScan("armadillo",
    "The Stanford armadillo as CGAL ships it (a scan, decimated; `armadillo.off` of Debian's "
    "libcgal-demo)",
    160.0, "its torso", 3.5, [&] { return ArmadilloMesh(notes); });
  if (wants("sphere"))
  {
    scenes.push_back({ "sphere",
      "A unit sphere tessellated by latitude and longitude (vtkSphereSource)",
      "seen whole: its surfels crowd several to a pixel",
      SphereMesh(sphereVertices), 25.0, 10.0, 1.0 });
  }
  return scenes;
}
}

#endif
