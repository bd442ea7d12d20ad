// SPDX-License-Identifier: BSD-3-Clause
// The stiff and extreme cases of issue 16, shared by TestSplatStability (one CTest test per
// group, mapper and backend) and the stability section of splat_report: each case builds a scene
// (input, volume property, window, camera) and says what it must give (Expectation).
// SplatStabilityRun.h renders a case and checks the result.
#ifndef SplatStabilityCases_h
#define SplatStabilityCases_h

#include "SplatVolumeTestUtilities.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkMatrix3x3.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace splatstability
{
enum MapperKind
{
  Surface = 0,
  Volume = 1
};

inline const char* MapperName(int kind)
{
  return kind == Surface ? "surface" : "volume";
}

/// What a case renders.
struct Scene
{
  vtkSmartPointer<vtkDataSet> Input;
  vtkSmartPointer<vtkVolumeProperty> Property; // volume cases; null: the volume's default
  int Width = 96;
  int Height = 96;
  double Position[3] = { 0.0, 0.0, 5.0 };
  double FocalPoint[3] = { 0.0, 0.0, 0.0 };
  double ViewAngle = 30.0;
  bool Parallel = false;
  double ParallelScale = 1.5;
  bool ResetCamera = false;     // renderer->ResetCamera() along the direction above
  double ClippingRange[2] = { -1.0, -1.0 }; // negative: ResetCameraClippingRange
  bool ScalarVisibility = false; // surface cases coloring by their point scalars
};

/// What a case must give.
struct Expectation
{
  bool Error = false;     // an error event from the mapper (bad input refused)
  vtkIdType Skipped = 0;  // skipped as invalid, with a warning when > 0; -1: not checked
  bool Visible = true;    // some pixel drawn
};

struct Case
{
  std::string Name;
  std::string Group;
  int Kind;
  std::function<Scene()> Make;
  Expectation Expected;
  std::string Reference = {}; // the case whose image this one must match (report only), or ""
  std::string Note = {};
};

struct Result
{
  bool Rendered = false;
  int Backend = 0;
  vtkIdType NonFinite = 0;
  vtkIdType Covered = 0;
  vtkIdType Skipped = 0;
  std::string Why;
  bool Error = false;
  bool Warning = false;
  std::string Message;
  double Milliseconds = 0.0;
  std::vector<double> RGB;
};

// ---- Scenes --------------------------------------------------------------------------------

/// Points of `data` moved by `offset` and scaled by `scale` about the origin, in doubles.
inline void Transform(vtkPointSet* data, double scale, const double offset[3])
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(data->GetNumberOfPoints());
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double p[3];
    data->GetPoint(i, p);
    points->SetPoint(i, scale * p[0] + offset[0], scale * p[1] + offset[1],
      scale * p[2] + offset[2]);
  }
  data->SetPoints(points);
}

/// The surface cases' base: 600 surfels on the unit sphere.
inline vtkSmartPointer<vtkPolyData> Sphere(vtkIdType n = 600)
{
  return splattest::SurfelSphere(n, 1.0);
}

/// One 3D Gaussian of a kernel set: position, standard deviations and quaternion (w, x, y, z).
struct Gaussian
{
  double P[3];
  double S[3];
  double Q[4];
};

/// A kernel set (3D Gaussian Splatting convention: Scale, Rotation, Opacity, Color arrays).
inline vtkSmartPointer<vtkPolyData> Gaussians(const std::vector<Gaussian>& kernels)
{
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  splattest::KernelSetArrays<vtkDoubleArray> arrays;
  for (const Gaussian& g : kernels)
  {
    points->InsertNextPoint(g.P);
    arrays.Scale->InsertNextTuple(g.S);
    arrays.Rotation->InsertNextTuple(g.Q);
    arrays.Opacity->InsertNextValue(0.8);
    arrays.Color->InsertNextTuple3(0.9, 0.6, 0.3);
  }
  data->SetPoints(points);
  arrays.AddTo(data);
  return data;
}

/// The kernel cases' base: three Gaussians around the origin.
inline std::vector<Gaussian> BaseGaussians()
{
  return { { { -0.6, 0.0, 0.0 }, { 0.2, 0.1, 0.1 }, { 1, 0, 0, 0 } },
    { { 0.6, 0.2, 0.0 }, { 0.1, 0.25, 0.1 }, { 0.9, 0.3, 0.1, 0 } },
    { { 0.0, -0.5, 0.2 }, { 0.15, 0.15, 0.15 }, { 1, 0, 0, 0 } } };
}

/// The base kernels and one more.
inline vtkSmartPointer<vtkPolyData> GaussiansWith(const Gaussian& extra)
{
  std::vector<Gaussian> kernels = BaseGaussians();
  kernels.push_back(extra);
  return Gaussians(kernels);
}

/// The image cases' base: a 12^3 Gaussian blob of extinction (SplatVolumeTestUtilities.h).
inline vtkSmartPointer<vtkImageData> Blob()
{
  return splattest::GaussianBlob(12, 0.2, 0.4, 4.0);
}

inline vtkSmartPointer<vtkVolumeProperty> BlobProperty(double maximum = 4.0)
{
  const double rgb[3] = { 0.9, 0.6, 0.3 };
  return splattest::ExtinctionProperty(maximum, 1.0 / maximum, rgb);
}

inline Scene BlobScene()
{
  Scene s;
  s.Input = Blob();
  s.Property = BlobProperty();
  return s;
}

inline Scene SurfaceScene(vtkPolyData* data)
{
  Scene s;
  s.Input = data;
  return s;
}

inline Scene KernelScene(vtkPolyData* data)
{
  Scene s;
  s.Input = data;
  return s;
}

/// The blob's scalar array.
inline vtkDataArray* Scalars(vtkDataSet* data)
{
  return data->GetPointData()->GetScalars();
}

/// The unit sphere's surfels with a float scalar array of values v(i) to color by.
inline Scene ColoredSphere(const std::function<double(vtkIdType)>& v)
{
  vtkSmartPointer<vtkPolyData> sphere = Sphere();
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("Value");
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    scalars->InsertNextValue(static_cast<float>(v(i)));
  }
  sphere->GetPointData()->SetScalars(scalars);
  Scene s = SurfaceScene(sphere);
  s.ScalarVisibility = true;
  return s;
}

/// The blob with scalars v(i, original value).
inline Scene BlobWith(const std::function<double(vtkIdType, double)>& v, double maximum = 4.0)
{
  Scene s = BlobScene();
  vtkDataArray* scalars = Scalars(s.Input);
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
  {
    scalars->SetTuple1(i, v(i, scalars->GetTuple1(i)));
  }
  s.Property = BlobProperty(maximum);
  return s;
}

/// Number of coincident points of the "coincident" cases (SPLAT_STABILITY_COINCIDENT, else 1e6).
inline vtkIdType CoincidentPoints()
{
  const char* value = std::getenv("SPLAT_STABILITY_COINCIDENT");
  return value ? std::max<vtkIdType>(1, std::atoll(value)) : 1000000;
}

// ---- The cases -----------------------------------------------------------------------------

inline std::vector<Case> Cases()
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Case> cases;
  auto add = [&](const std::string& group, int kind, const std::string& name,
               std::function<Scene()> make, Expectation expected = {},
               const std::string& reference = {})
  { cases.push_back(Case{ name, group, kind, std::move(make), expected, reference }); };

  // Baselines: the scenes the extremes are measured against.
  add("baseline", Surface, "sphere", [] { return SurfaceScene(Sphere()); });
  add("baseline", Volume, "gaussians", [] { return KernelScene(Gaussians(BaseGaussians())); });
  add("baseline", Volume, "blob", [] { return BlobScene(); });

  // Kernels: covariances with eigenvalue ratios up to 1e12, zero scales, negative and
  // non-symmetric covariances, quaternions of zero and huge norm.
  for (int exponent : { 3, 6, 9, 12 })
  {
    add("kernels", Volume, "eigenvalue-ratio-1e" + std::to_string(exponent),
      [exponent]
      {
        const double thin = 0.3 / std::sqrt(std::pow(10.0, exponent));
        return KernelScene(GaussiansWith({ { 0, 0, 0 }, { 0.3, thin, 0.2 }, { 0.9, 0.3, 0.2, 0.1 } }));
      });
  }
  add("kernels", Volume, "zero-scale-one-axis",
    [] { return KernelScene(GaussiansWith({ { 0, 0, 0 }, { 0.3, 0.0, 0.2 }, { 0.9, 0.3, 0.2, 0.1 } })); });
  add("kernels", Volume, "zero-scale-two-axes",
    [] { return KernelScene(GaussiansWith({ { 0, 0, 0 }, { 0.3, 0.0, 0.0 }, { 0.9, 0.3, 0.2, 0.1 } })); });
  add("kernels", Volume, "zero-scale-three-axes",
    [] { return KernelScene(GaussiansWith({ { 0, 0, 0 }, { 0.0, 0.0, 0.0 }, { 1, 0, 0, 0 } })); });
  add("kernels", Volume, "negative-covariance",
    []
    {
      vtkSmartPointer<vtkPolyData> data = Gaussians(BaseGaussians());
      vtkNew<vtkDoubleArray> covariance;
      covariance->SetName("Covariance");
      covariance->SetNumberOfComponents(6);
      covariance->InsertNextTuple6(0.01, 0, 0, 0.01, 0, 0.01);
      covariance->InsertNextTuple6(0.01, 0, 0, -0.01, 0, 0.01); // indefinite
      covariance->InsertNextTuple6(-0.01, 0, 0, -0.01, 0, -0.01); // negative definite
      data->GetPointData()->AddArray(covariance);
      return KernelScene(data);
    },
    { false, 2, true });
  // A 3x3 (9-component) covariance cannot be taken as symmetric: refused with an error.
  add("kernels", Volume, "non-symmetric-covariance",
    []
    {
      vtkSmartPointer<vtkPolyData> data = Gaussians(BaseGaussians());
      data->GetPointData()->RemoveArray("Scale");
      vtkNew<vtkDoubleArray> covariance;
      covariance->SetName("Covariance");
      covariance->SetNumberOfComponents(9);
      for (int i = 0; i < 3; ++i)
      {
        const double c[9] = { 0.01, 0.005, 0, 0, 0.01, 0, 0, 0, 0.01 };
        covariance->InsertNextTuple(c);
      }
      data->GetPointData()->AddArray(covariance);
      return KernelScene(data);
    },
    { true, 0, false });
  add("kernels", Volume, "quaternion-zero",
    [] { return KernelScene(GaussiansWith({ { 0, 0, 0 }, { 0.2, 0.1, 0.1 }, { 0, 0, 0, 0 } })); },
    { false, 1, true });
  add("kernels", Volume, "scale-1e200",
    [] { return KernelScene(GaussiansWith({ { 0, 0, 0 }, { 1e200, 0.1, 0.1 }, { 1, 0, 0, 0 } })); },
    { false, 1, true });
  for (double norm : { 1e-200, 1e-150, 1e30, 1e200 })
  {
    std::ostringstream name;
    name << "quaternion-norm-" << norm;
    add("kernels", Volume, name.str(),
      [norm]
      {
        return KernelScene(GaussiansWith(
          { { 0, 0, 0 }, { 0.2, 0.1, 0.1 }, { 0.9 * norm, 0.3 * norm, 0.2 * norm, 0.1 * norm } }));
      });
  }

  // Surfels: edge-on, tiny and huge radii, zero and NaN normals, parallel and zero axes.
  add("surfels", Surface, "edge-on-1e-9-rad",
    []
    {
      const double center[3] = { 0, 0, 0 };
      // Steps a and b span a plane whose normal a x b = (cos, 0, -sin) / 100 is 1e-9 rad off
      // the image plane: seen from +z, edge-on.
      const double angle = 1e-9;
      const double a[3] = { 0.0, 0.1, 0.0 };
      const double b[3] = { 0.1 * std::sin(angle), 0.0, 0.1 * std::cos(angle) };
      return SurfaceScene(splattest::SurfelPlane(center, a, b, 20, 20));
    },
    { false, 0, false });
  for (double factor : { 1e-12, 1e-6, 1e3, 1e6 })
  {
    std::ostringstream name;
    name << "radius-" << factor << "x";
    add("surfels", Surface, name.str(),
      [factor]
      {
        vtkSmartPointer<vtkPolyData> sphere = Sphere();
        vtkDataArray* radius = sphere->GetPointData()->GetArray("Radius");
        for (vtkIdType i = 0; i < radius->GetNumberOfTuples(); ++i)
        {
          radius->SetTuple1(i, 2.0 * factor); // the scene's size is the diameter, 2
        }
        return SurfaceScene(sphere);
      },
      // Tiny splats cover no pixel (coverage below the threshold); splats of 1e6 times the
      // scene, centered in front of the near plane, are drawn where they reach past it.
      { false, 0, factor > 1e-6 });
  }
  add("surfels", Surface, "zero-and-nan-normals",
    [nan]
    {
      vtkSmartPointer<vtkPolyData> sphere = Sphere();
      vtkDataArray* normals = sphere->GetPointData()->GetNormals();
      normals->SetTuple3(0, 0, 0, 0);
      normals->SetTuple3(1, nan, 0, 1);
      normals->SetTuple3(2, nan, nan, nan);
      return SurfaceScene(sphere);
    },
    { false, 3, true });
  auto axes = [](vtkPolyData* data, const std::function<void(vtkIdType, double*, double*)>& f)
  {
    vtkNew<vtkFloatArray> a0, a1;
    a0->SetName("TangentAxis0");
    a1->SetName("TangentAxis1");
    a0->SetNumberOfComponents(3);
    a1->SetNumberOfComponents(3);
    vtkDataArray* normals = data->GetPointData()->GetNormals();
    for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
    {
      double n[3], t0[3], t1[3];
      normals->GetTuple(i, n);
      vtkMath::Perpendiculars(n, t0, t1, 0.0);
      vtkMath::MultiplyScalar(t0, 0.12);
      vtkMath::MultiplyScalar(t1, 0.06);
      f(i, t0, t1);
      a0->InsertNextTuple(t0);
      a1->InsertNextTuple(t1);
    }
    data->GetPointData()->AddArray(a0);
    data->GetPointData()->AddArray(a1);
  };
  add("surfels", Surface, "parallel-and-zero-axes",
    [axes]
    {
      vtkSmartPointer<vtkPolyData> sphere = Sphere();
      axes(sphere,
        [](vtkIdType i, double* t0, double* t1)
        {
          if (i == 0)
          {
            std::copy_n(t0, 3, t1); // parallel
          }
          else if (i == 1)
          {
            std::fill_n(t0, 3, 0.0); // zero
          }
          else if (i == 2)
          {
            std::fill_n(t0, 3, 0.0);
            std::fill_n(t1, 3, 0.0);
          }
          else if (i == 3)
          {
            t1[0] = t0[0] * (1.0 + 1e-7); // nearly parallel: still valid
            t1[1] = t0[1];
            t1[2] = t0[2] * (1.0 - 1e-7);
          }
        });
      return SurfaceScene(sphere);
    },
    { false, 3, true });

  // Placement: unit-size data far from the origin; tiny and huge data.
  for (double distance : { 1e6, 1e7, 1e9 })
  {
    std::ostringstream name;
    name << "offset-" << distance;
    const double offset[3] = { distance, -0.5 * distance, 0.25 * distance };
    add("placement", Surface, name.str(),
      [offset]
      {
        vtkSmartPointer<vtkPolyData> sphere = Sphere();
        Transform(sphere, 1.0, offset);
        Scene s = SurfaceScene(sphere);
        s.ResetCamera = true;
        return s;
      },
      {}, "sphere");
    add("placement", Volume, name.str() + "-kernels",
      [offset]
      {
        vtkSmartPointer<vtkPolyData> data = Gaussians(BaseGaussians());
        Transform(data, 1.0, offset);
        Scene s = KernelScene(data);
        s.ResetCamera = true;
        return s;
      },
      {}, "gaussians");
    add("placement", Volume, name.str() + "-image",
      [offset]
      {
        Scene s = BlobScene();
        auto* image = vtkImageData::SafeDownCast(s.Input);
        double origin[3];
        image->GetOrigin(origin);
        image->SetOrigin(origin[0] + offset[0], origin[1] + offset[1], origin[2] + offset[2]);
        s.ResetCamera = true;
        return s;
      },
      {}, "blob");
  }
  for (double size : { 1e-6, 1e6 })
  {
    std::ostringstream name;
    name << "size-" << size;
    const double zero[3] = { 0, 0, 0 };
    add("placement", Surface, name.str(),
      [size, zero]
      {
        vtkSmartPointer<vtkPolyData> sphere = Sphere();
        Transform(sphere, size, zero);
        vtkDataArray* radius = sphere->GetPointData()->GetArray("Radius");
        for (vtkIdType i = 0; i < radius->GetNumberOfTuples(); ++i)
        {
          radius->SetTuple1(i, size * radius->GetTuple1(i));
        }
        Scene s = SurfaceScene(sphere);
        s.ResetCamera = true;
        return s;
      },
      {}, "sphere");
    add("placement", Volume, name.str() + "-image",
      [size]
      {
        Scene s = BlobScene();
        auto* image = vtkImageData::SafeDownCast(s.Input);
        double spacing[3], origin[3];
        image->GetSpacing(spacing);
        image->GetOrigin(origin);
        image->SetSpacing(size * spacing[0], size * spacing[1], size * spacing[2]);
        image->SetOrigin(size * origin[0], size * origin[1], size * origin[2]);
        // The same optical depths: extinction per unit length scaled by 1/size.
        s.Property = BlobProperty(4.0);
        s.Property->SetScalarOpacityUnitDistance(size / 4.0);
        s.ResetCamera = true;
        return s;
      },
      {}, "blob");
  }

  // Camera: kernels at, behind and across the near plane; the eye inside; extreme projections.
  add("camera", Surface, "eye-at-sphere-center",
    []
    {
      Scene s = SurfaceScene(Sphere());
      s.Position[2] = 0.0;
      s.FocalPoint[2] = -1.0;
      s.ViewAngle = 90.0;
      return s;
    });
  add("camera", Surface, "eye-on-a-surfel",
    []
    {
      vtkSmartPointer<vtkPolyData> sphere = Sphere();
      double p[3];
      sphere->GetPoint(0, p);
      Scene s = SurfaceScene(sphere);
      std::copy_n(p, 3, s.Position);
      s.ViewAngle = 90.0;
      return s;
    },
    { false, 0, true });
  add("camera", Surface, "near-plane-through-sphere",
    []
    {
      Scene s = SurfaceScene(Sphere());
      s.ClippingRange[0] = 4.5; // cuts the front of the sphere (z = 0.5)
      s.ClippingRange[1] = 10.0;
      return s;
    });
  add("camera", Surface, "behind-the-eye",
    []
    {
      Scene s = SurfaceScene(Sphere());
      s.Position[2] = -3.0;
      s.FocalPoint[2] = -10.0;
      s.ClippingRange[0] = 0.1;
      s.ClippingRange[1] = 10.0;
      return s;
    },
    { false, 0, false });
  add("camera", Volume, "eye-inside-blob",
    []
    {
      Scene s = BlobScene();
      s.Position[2] = 0.3;
      s.ViewAngle = 90.0;
      s.ClippingRange[0] = 0.01;
      s.ClippingRange[1] = 10.0;
      return s;
    });
  add("camera", Volume, "kernel-at-eye",
    []
    {
      Scene s = KernelScene(GaussiansWith({ { 0, 0, 5 }, { 0.2, 0.2, 0.2 }, { 1, 0, 0, 0 } }));
      s.ClippingRange[0] = 0.1;
      s.ClippingRange[1] = 20.0;
      return s;
    });
  add("camera", Volume, "kernels-behind-and-across-near",
    []
    {
      Scene s = KernelScene(Gaussians({ { { 0, 0, 0 }, { 0.2, 0.1, 0.1 }, { 1, 0, 0, 0 } },
        { { 0, 0, 8 }, { 0.3, 0.3, 0.3 }, { 1, 0, 0, 0 } },
        { { 0.2, 0, 4.5 }, { 0.3, 0.3, 0.3 }, { 1, 0, 0, 0 } } }));
      s.ClippingRange[0] = 0.4;
      s.ClippingRange[1] = 20.0;
      return s;
    });
  for (int kind : { Surface, Volume })
  {
    for (double angle : { 1.0, 170.0 })
    {
      std::ostringstream name;
      name << "view-angle-" << angle;
      add("camera", kind, name.str(),
        [kind, angle]
        {
          Scene s = kind == Surface ? SurfaceScene(Sphere()) : BlobScene();
          s.ViewAngle = angle;
          // At 170 degrees the scene is moved closer, to cover more than a pixel.
          s.Position[2] = angle > 90.0 ? 1.5 : 5.0;
          return s;
        });
    }
    for (double scale : { 1e-4, 1e4 })
    {
      std::ostringstream name;
      name << "parallel-scale-" << scale;
      add("camera", kind, name.str(),
        [kind, scale]
        {
          Scene s = kind == Surface ? SurfaceScene(Sphere()) : BlobScene();
          s.Parallel = true;
          s.ParallelScale = scale;
          return s;
        },
        { false, 0, scale < 1.0 });
    }
  }

  // Windows and input sizes.
  for (int kind : { Surface, Volume })
  {
    auto base = [kind] { return kind == Surface ? SurfaceScene(Sphere()) : BlobScene(); };
    // Known: the surface mapper's CPU backend leaves a 1x1 window empty although the sphere
    // covers its pixel: the whole visible half falls into that pixel, the depth threshold (a
    // splat radius) keeps only the cap nearest the eye as its surface, and that cap's summed
    // weight, 2e-4 of full coverage, rounds to 0. Only the volume mapper's pixel is required.
    add("window", kind, "1x1",
      [base]
      {
        Scene s = base();
        s.Width = s.Height = 1;
        return s;
      },
      { false, 0, kind == Volume });
    add("window", kind, "1x4096",
      [base]
      {
        Scene s = base();
        s.Width = 1;
        s.Height = 4096;
        return s;
      });
    // 8192x8192 (gigabytes of buffers): only with SPLAT_STABILITY_LARGE=1 (the report's figures).
    if (std::getenv("SPLAT_STABILITY_LARGE"))
    {
      add("window", kind, "8192x8192",
        [base]
        {
          Scene s = base();
          s.Width = s.Height = 8192;
          return s;
        });
    }
    add("input", kind, "empty",
      [kind]
      {
        Scene s;
        if (kind == Surface)
        {
          auto data = vtkSmartPointer<vtkPolyData>::New();
          vtkNew<vtkPoints> points;
          data->SetPoints(points);
          vtkNew<vtkFloatArray> normals;
          normals->SetNumberOfComponents(3);
          data->GetPointData()->SetNormals(normals);
          s.Input = data;
        }
        else
        {
          s.Input = Gaussians({});
        }
        return s;
      },
      { false, 0, false });
    add("input", kind, "single-point",
      [kind]
      {
        if (kind == Surface)
        {
          const double center[3] = { 0, 0, 0 }, u[3] = { 0.3, 0, 0 }, v[3] = { 0, 0.3, 0 };
          return SurfaceScene(splattest::SurfelPlane(center, u, v, 1, 1));
        }
        return KernelScene(Gaussians({ { { 0, 0, 0 }, { 0.3, 0.2, 0.1 }, { 1, 0, 0, 0 } } }));
      });
    add("input", kind, "coincident-points",
      [kind]
      {
        const vtkIdType n = CoincidentPoints();
        auto data = vtkSmartPointer<vtkPolyData>::New();
        vtkNew<vtkPoints> points;
        points->SetNumberOfPoints(n);
        for (vtkIdType i = 0; i < n; ++i)
        {
          points->SetPoint(i, 0.1, 0.2, 0.3);
        }
        data->SetPoints(points);
        if (kind == Surface)
        {
          vtkNew<vtkFloatArray> normals, radius;
          normals->SetNumberOfComponents(3);
          normals->SetNumberOfTuples(n);
          normals->FillComponent(0, 0.0);
          normals->FillComponent(1, 0.0);
          normals->FillComponent(2, 1.0);
          radius->SetName("Radius");
          radius->SetNumberOfTuples(n);
          radius->FillComponent(0, 0.05);
          data->GetPointData()->SetNormals(normals);
          data->GetPointData()->AddArray(radius);
          return SurfaceScene(data);
        }
        splattest::KernelSetArrays<vtkFloatArray> arrays;
        arrays.Scale->SetNumberOfTuples(n);
        arrays.Rotation->SetNumberOfTuples(n);
        arrays.Opacity->SetNumberOfTuples(n);
        arrays.Color->SetNumberOfTuples(n);
        for (int c = 0; c < 4; ++c)
        {
          arrays.Rotation->FillComponent(c, c == 0 ? 1.0 : 0.0);
          if (c < 3)
          {
            arrays.Scale->FillComponent(c, 0.05);
            arrays.Color->FillComponent(c, 0.5);
          }
        }
        arrays.Opacity->FillComponent(0, 0.01);
        arrays.AddTo(data);
        return KernelScene(data);
      });
  }

  // Transfer functions and scalars.
  add("transfer", Volume, "single-point",
    []
    {
      Scene s = BlobScene();
      vtkNew<vtkPiecewiseFunction> opacity;
      opacity->AddPoint(2.0, 0.3);
      vtkNew<vtkColorTransferFunction> color;
      color->AddRGBPoint(2.0, 0.2, 0.8, 0.4);
      s.Property->SetScalarOpacity(opacity);
      s.Property->SetColor(color);
      return s;
    });
  for (double value : { 0.0, 1.0 })
  {
    add("transfer", Volume, value == 0.0 ? "opacity-zero" : "opacity-one",
      [value]
      {
        Scene s = BlobScene();
        vtkNew<vtkPiecewiseFunction> opacity;
        opacity->AddPoint(0.0, value);
        opacity->AddPoint(4.0, value);
        s.Property->SetScalarOpacity(opacity);
        return s;
      },
      { false, 0, value > 0.0 });
  }
  add("transfer", Volume, "scalars-nan",
    [nan] { return BlobWith([nan](vtkIdType i, double v) { return i % 97 == 5 ? nan : v; }); },
    { false, 18, true });
  add("transfer", Volume, "scalars-inf",
    [inf]
    {
      return BlobWith(
        [inf](vtkIdType i, double v) { return i % 101 == 7 ? (i % 2 ? inf : -inf) : v; });
    },
    { false, 18, true });
  add("transfer", Volume, "scalars-constant", [] { return BlobWith([](vtkIdType, double) { return 2.0; }); });
  add("transfer", Volume, "scalars-1e38",
    [] { return BlobWith([](vtkIdType, double v) { return v * 0.25e38; }, 1e38); });
  add("transfer", Surface, "scalars-nan",
    [nan] { return ColoredSphere([nan](vtkIdType i) { return i % 7 == 0 ? nan : double(i); }); });
  add("transfer", Surface, "scalars-inf",
    [inf] { return ColoredSphere([inf](vtkIdType i) { return i % 7 == 0 ? inf : double(i); }); });
  add("transfer", Surface, "scalars-constant", [] { return ColoredSphere([](vtkIdType) { return 3.0; }); });
  add("transfer", Surface, "scalars-1e38",
    [] { return ColoredSphere([](vtkIdType i) { return (i % 2 ? 1e38 : -1e38); }); });

  // Image geometry: zero, negative and non-finite spacing, a non-orthogonal direction matrix.
  add("image", Volume, "zero-spacing",
    []
    {
      Scene s = BlobScene();
      vtkImageData::SafeDownCast(s.Input)->SetSpacing(0.2, 0.2, 0.0);
      return s;
    },
    { true, 0, false });
  add("image", Volume, "negative-spacing",
    []
    {
      Scene s = BlobScene();
      auto* image = vtkImageData::SafeDownCast(s.Input);
      double origin[3];
      image->GetOrigin(origin);
      image->SetSpacing(-0.2, 0.2, -0.2);
      image->SetOrigin(-origin[0], origin[1], -origin[2]);
      return s;
    },
    {}, "blob");
  add("image", Volume, "non-orthogonal-direction",
    []
    {
      Scene s = BlobScene();
      const double shear[9] = { 1, 0.5, 0, 0, 1, 0.3, 0, 0, 1 };
      vtkImageData::SafeDownCast(s.Input)->SetDirectionMatrix(shear);
      return s;
    });
  add("image", Volume, "singular-direction",
    []
    {
      Scene s = BlobScene();
      const double flat[9] = { 1, 0, 1, 0, 1, 0, 0, 0, 0 };
      vtkImageData::SafeDownCast(s.Input)->SetDirectionMatrix(flat);
      return s;
    },
    { true, 0, false });
  return cases;
}

}

#endif
