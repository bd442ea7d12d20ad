// SPDX-License-Identifier: BSD-3-Clause
// splat_report's reference images of the volume scenes: the Gaussian mixture that
// vtkVolumeSplatMapper draws (SplatVolumeScenes.h), integrated by fine ray marching instead of
// splatting. Per pixel one ray through the pixel's center from the camera's eye (perspective);
// samples every `step` along it (1/8 of the smallest kernel standard deviation); at each sample
// the extinction tau(x) = sum_k tau_k(x) and the emission E(x) = sum_k color_k tau_k(x) of all
// kernels within reach; emission-absorption front to back: a sample adds
// T E (1 - exp(-tau step)) / tau to the color and multiplies the transmittance T by
// exp(-tau step); the ray stops once T < 1e-6. Over a black background. No screen filter and no
// cutoff: the exact mixture, which the splats approximate.
//
// - Image data (identity direction matrix): one kernel per voxel of standard deviation
//   splat::VoxelKernelSigma (0.6) times the spacing, carrying tau(scalar) times the voxel
//   volume, axis-aligned, so that a kernel's value is separable: a sample takes 3x5 1-D
//   Gaussians (the 5 nearest voxels along each axis, 3.3 sigma) and 125 4-wide multiply-adds
//   (tau and emission). Bricks of 4^3 voxels with no extinction within reach are skipped.
// - Point sets: per ray the kernels whose bounding sphere (5 largest standard deviations) the
//   ray crosses, ordered by entry; a sample evaluates the kernels whose span it lies in, and
//   spans without any are skipped.
// Rows of pixels run in parallel (vtkSMPTools).
#ifndef SplatVolumeReference_h
#define SplatVolumeReference_h

#include "SplatVolumeScenes.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkSMPTools.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace splatexample
{
/// The eye and the unit direction of each pixel's ray through its center (rows from the bottom)
/// for the camera at width x height pixels.
struct PixelRays
{
  std::array<double, 3> Eye;
  int Width = 0;
  int Height = 0;
  std::vector<std::array<double, 3>> Directions;
};

inline PixelRays CameraRays(vtkCamera* camera, int width, int height)
{
  if (camera->GetParallelProjection())
  {
    throw std::runtime_error("the ray-marched reference needs a perspective camera");
  }
  PixelRays rays;
  rays.Width = width;
  rays.Height = height;
  camera->GetPosition(rays.Eye.data());
  vtkNew<vtkMatrix4x4> clipToWorld;
  clipToWorld->DeepCopy(camera->GetCompositeProjectionTransformMatrix(
    static_cast<double>(width) / height, -1.0, 1.0));
  clipToWorld->Invert();
  rays.Directions.resize(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      // A point on the far plane seen through the pixel's center.
      const double clip[4] = { 2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0, 1.0,
        1.0 };
      double world[4];
      clipToWorld->MultiplyPoint(clip, world);
      std::array<double, 3>& d = rays.Directions[static_cast<std::size_t>(y) * width + x];
      for (int c = 0; c < 3; ++c)
      {
        d[c] = world[c] / world[3] - rays.Eye[c];
      }
      vtkMath::Normalize(d.data());
    }
  }
  return rays;
}

/// A reference image: RGB floats in [0, 1], rows from the bottom, and what it took.
struct VolumeReference
{
  std::vector<float> RGB;
  double Step = 0.0;
  long long Samples = 0; // samples that evaluated kernels
};

/// Front-to-back emission-absorption along every ray, with samples at t0 + (i + 1/2) step.
/// `Field::Ray` is a per-thread cursor: Start(eye, direction, t0, t1) gives the span of the ray
/// to integrate (false: nothing on it), Skip(t) the first position at or after t where the
/// field may not vanish, Sample(x, t, tau, emission) the field at x = eye + t direction.
template <typename Field>
VolumeReference RayMarch(const PixelRays& rays, const Field& field, double step)
{
  VolumeReference reference;
  reference.Step = step;
  reference.RGB.assign(3 * rays.Directions.size(), 0.0f);
  std::atomic<long long> samples(0);
  vtkSMPTools::For(0, rays.Height,
    [&](vtkIdType begin, vtkIdType end)
    {
      typename Field::Ray ray(field);
      long long count = 0;
      for (vtkIdType y = begin; y < end; ++y)
      {
        for (int x = 0; x < rays.Width; ++x)
        {
          const std::size_t pixel = static_cast<std::size_t>(y) * rays.Width + x;
          const double* d = rays.Directions[pixel].data();
          double t0, t1;
          if (!ray.Start(rays.Eye.data(), d, t0, t1))
          {
            continue;
          }
          double transmittance = 1.0;
          double color[3] = { 0.0, 0.0, 0.0 };
          for (double i = 0.0; transmittance >= 1e-6; ++i)
          {
            double t = t0 + (i + 0.5) * step;
            const double next = ray.Skip(t);
            if (next > t)
            {
              i = std::ceil((next - t0) / step - 0.5);
              t = t0 + (i + 0.5) * step;
            }
            if (t >= t1)
            {
              break;
            }
            const double position[3] = { rays.Eye[0] + t * d[0], rays.Eye[1] + t * d[1],
              rays.Eye[2] + t * d[2] };
            double tau = 0.0;
            double emission[3] = { 0.0, 0.0, 0.0 };
            if (!ray.Sample(position, t, tau, emission))
            {
              continue;
            }
            ++count;
            // (1 - exp(-tau step)) / tau, which tends to step as tau vanishes.
            const double absorbed = -std::expm1(-tau * step);
            const double weight = tau > 1e-12 ? absorbed / tau : step;
            for (int c = 0; c < 3; ++c)
            {
              color[c] += transmittance * weight * emission[c];
            }
            transmittance *= 1.0 - absorbed;
          }
          for (int c = 0; c < 3; ++c)
          {
            reference.RGB[3 * pixel + c] = static_cast<float>(std::min(color[c], 1.0));
          }
        }
      }
      samples += count;
    });
  reference.Samples = samples;
  return reference;
}

/// The voxel kernels of image data as vtkVolumeSplatMapper builds them (see the file comment).
class GridField
{
public:
  GridField(vtkImageData* image, vtkVolumeProperty* property)
  {
    vtkMatrix3x3* direction = image->GetDirectionMatrix();
    if (!direction->IsIdentity())
    {
      throw std::runtime_error("the grid reference needs an identity direction matrix");
    }
    image->GetDimensions(this->Dims.data());
    for (int a = 0; a < 3; ++a)
    {
      this->Origin[a] = image->GetOrigin()[a];
      this->Spacing[a] = image->GetSpacing()[a];
    }
    vtkDataArray* scalars = image->GetPointData()->GetScalars();
    if (!scalars)
    {
      throw std::runtime_error("the grid reference needs point scalars");
    }
    // A kernel's extinction at index offset u: tau V / ((2 pi)^(3/2) prod sigma_a) exp(-|u|^2 /
    // (2 0.6^2)), V = prod h_a and sigma_a = 0.6 h_a: the spacing cancels.
    const double sigma = splat::VoxelKernelSigma;
    const double normalization = 1.0 / (splat::TwoPiToThreeHalves * sigma * sigma * sigma);
    const vtkIdType n = image->GetNumberOfPoints();
    this->Weights.resize(4 * static_cast<std::size_t>(n));
    // In one thread: the transfer functions are not meant to be read concurrently.
    for (vtkIdType id = 0; id < n; ++id)
    {
      const double s = scalars->GetComponent(id, 0);
      const double tau = std::isfinite(s) ? Extinction(property, s) * normalization : 0.0;
      double rgb[3] = { 0.0, 0.0, 0.0 };
      if (tau > 0.0)
      {
        property->GetRGBTransferFunction(0)->GetColor(s, rgb);
      }
      float* w = this->Weights.data() + 4 * id;
      w[0] = static_cast<float>(tau);
      for (int c = 0; c < 3; ++c)
      {
        w[1 + c] = static_cast<float>(tau * rgb[c]);
      }
    }
    // Bricks of 4^3 voxels: occupied when a voxel within 3 of the brick has extinction (a
    // sample whose nearest voxel lies in the brick reaches 2 voxels further).
    for (int a = 0; a < 3; ++a)
    {
      this->Bricks[a] = (this->Dims[a] + 3) / 4;
    }
    this->Occupied.assign(
      static_cast<std::size_t>(this->Bricks[0]) * this->Bricks[1] * this->Bricks[2], 0);
    for (int z = 0; z < this->Dims[2]; ++z)
    {
      for (int y = 0; y < this->Dims[1]; ++y)
      {
        for (int x = 0; x < this->Dims[0]; ++x)
        {
          if (this->Weights[4 * this->Index(x, y, z)] <= 0.0f)
          {
            continue;
          }
          const int at[3] = { x, y, z };
          int low[3], high[3];
          for (int a = 0; a < 3; ++a)
          {
            low[a] = std::max(0, (at[a] - 3) / 4);
            high[a] = std::min(this->Bricks[a] - 1, (at[a] + 3) / 4);
          }
          for (int k = low[2]; k <= high[2]; ++k)
            for (int j = low[1]; j <= high[1]; ++j)
              for (int i = low[0]; i <= high[0]; ++i)
              {
                this->Occupied[i + this->Bricks[0] * (j + this->Bricks[1] * k)] = 1;
              }
        }
      }
    }
  }

  /// 1/8 of the kernels' standard deviation along the finest axis.
  double Step() const
  {
    return splat::VoxelKernelSigma *
      std::min({ std::abs(this->Spacing[0]), std::abs(this->Spacing[1]),
        std::abs(this->Spacing[2]) }) /
      8.0;
  }

  class Ray
  {
  public:
    explicit Ray(const GridField& field)
      : Field(field)
    {
    }

    // The span inside the grid's box grown by 3 voxels (the kernels' reach).
    bool Start(const double eye[3], const double d[3], double& t0, double& t1) const
    {
      t0 = 0.0;
      t1 = std::numeric_limits<double>::max();
      for (int a = 0; a < 3; ++a)
      {
        const double h = this->Field.Spacing[a];
        double low = this->Field.Origin[a] - 3.0 * h;
        double high = this->Field.Origin[a] + (this->Field.Dims[a] - 1 + 3.0) * h;
        if (std::abs(d[a]) < 1e-300)
        {
          if (eye[a] < low || eye[a] > high)
          {
            return false;
          }
          continue;
        }
        double ta = (low - eye[a]) / d[a];
        double tb = (high - eye[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      }
      return t0 < t1;
    }

    double Skip(double t) const { return t; }

    bool Sample(const double x[3], double, double& tau, double emission[3]) const
    {
      const GridField& f = this->Field;
      double u[3];
      int center[3];
      for (int a = 0; a < 3; ++a)
      {
        u[a] = (x[a] - f.Origin[a]) / f.Spacing[a];
        center[a] = static_cast<int>(std::lround(u[a]));
      }
      const int brick[3] = { std::min(std::max(center[0], 0), f.Dims[0] - 1) / 4,
        std::min(std::max(center[1], 0), f.Dims[1] - 1) / 4,
        std::min(std::max(center[2], 0), f.Dims[2] - 1) / 4 };
      if (!f.Occupied[brick[0] + f.Bricks[0] * (brick[1] + f.Bricks[1] * brick[2])])
      {
        return false;
      }
      // The five nearest voxels per axis inside the grid, and their 1-D Gaussians.
      constexpr double inverseVariance = 1.0 / (splat::VoxelKernelSigma * splat::VoxelKernelSigma);
      int low[3], high[3];
      float g[3][5];
      for (int a = 0; a < 3; ++a)
      {
        low[a] = std::max(center[a] - 2, 0);
        high[a] = std::min(center[a] + 2, f.Dims[a] - 1);
        for (int i = low[a]; i <= high[a]; ++i)
        {
          const double o = u[a] - i;
          g[a][i - low[a]] = static_cast<float>(std::exp(-0.5 * inverseVariance * o * o));
        }
      }
      float sum[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
      for (int k = low[2]; k <= high[2]; ++k)
      {
        for (int j = low[1]; j <= high[1]; ++j)
        {
          const float gjk = g[2][k - low[2]] * g[1][j - low[1]];
          const float* w = f.Weights.data() + 4 * f.Index(low[0], j, k);
          float row[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
          for (int i = 0; i <= high[0] - low[0]; ++i, w += 4)
          {
            for (int c = 0; c < 4; ++c)
            {
              row[c] += g[0][i] * w[c];
            }
          }
          for (int c = 0; c < 4; ++c)
          {
            sum[c] += gjk * row[c];
          }
        }
      }
      tau = sum[0];
      for (int c = 0; c < 3; ++c)
      {
        emission[c] = sum[1 + c];
      }
      return true;
    }

  private:
    const GridField& Field;
  };

private:
  std::size_t Index(int x, int y, int z) const
  {
    return static_cast<std::size_t>(x) +
      static_cast<std::size_t>(this->Dims[0]) * (y + static_cast<std::size_t>(this->Dims[1]) * z);
  }

  std::array<int, 3> Dims;
  std::array<double, 3> Origin;
  std::array<double, 3> Spacing;
  std::vector<float> Weights; // per voxel: tau', tau' r, tau' g, tau' b
  std::array<int, 3> Bricks;
  std::vector<unsigned char> Occupied;
};

/// The kernels of a point set (GaussianMixture), each within 5 of its largest standard
/// deviations.
class MixtureField
{
public:
  explicit MixtureField(const GaussianMixture& mixture)
    : Mixture(mixture)
  {
  }

  double Step() const { return this->Mixture.SmallestSigma / 8.0; }

  class Ray
  {
  public:
    explicit Ray(const MixtureField& field)
      : Field(field)
    {
    }

    bool Start(const double eye[3], const double d[3], double& t0, double& t1)
    {
      this->Candidates.clear();
      this->Active.clear();
      this->Next = 0;
      t0 = std::numeric_limits<double>::max();
      t1 = 0.0;
      const auto& kernels = this->Field.Mixture.Kernels;
      for (std::size_t i = 0; i < kernels.size(); ++i)
      {
        const auto& k = kernels[i];
        const double e[3] = { k.Center[0] - eye[0], k.Center[1] - eye[1], k.Center[2] - eye[2] };
        const double along = vtkMath::Dot(e, d);
        const double r = Reach * k.LargestSigma;
        const double miss = vtkMath::Dot(e, e) - along * along;
        if (miss >= r * r)
        {
          continue;
        }
        const double half = std::sqrt(r * r - miss);
        if (along + half <= 0.0)
        {
          continue;
        }
        this->Candidates.push_back({ std::max(along - half, 0.0), along + half, i });
        t0 = std::min(t0, this->Candidates.back().Enter);
        t1 = std::max(t1, this->Candidates.back().Exit);
      }
      std::sort(this->Candidates.begin(), this->Candidates.end(),
        [](const Span& a, const Span& b) { return a.Enter < b.Enter; });
      return !this->Candidates.empty();
    }

    // Past the spans that ended; where none is open, on to the next one's entry.
    double Skip(double t)
    {
      this->Active.erase(std::remove_if(this->Active.begin(), this->Active.end(),
                           [t](const Span& s) { return s.Exit < t; }),
        this->Active.end());
      if (this->Active.empty() && this->Next < this->Candidates.size())
      {
        return std::max(t, this->Candidates[this->Next].Enter);
      }
      return t;
    }

    bool Sample(const double x[3], double t, double& tau, double emission[3])
    {
      while (this->Next < this->Candidates.size() && this->Candidates[this->Next].Enter <= t)
      {
        this->Active.push_back(this->Candidates[this->Next++]);
      }
      tau = 0.0;
      for (const Span& s : this->Active)
      {
        if (s.Exit < t)
        {
          continue;
        }
        const auto& k = this->Field.Mixture.Kernels[s.Kernel];
        const double value = GaussianMixture::Evaluate(k, x);
        tau += value;
        for (int c = 0; c < 3; ++c)
        {
          emission[c] += value * k.Color[c];
        }
      }
      return !this->Active.empty();
    }

  private:
    struct Span
    {
      double Enter;
      double Exit;
      std::size_t Kernel;
    };
    static constexpr double Reach = 5.0;
    const MixtureField& Field;
    std::vector<Span> Candidates;
    std::vector<Span> Active;
    std::size_t Next = 0;
  };

private:
  const GaussianMixture& Mixture;
};
}

#endif
