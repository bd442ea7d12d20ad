// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfelTextureAcquisition.h"

#include "vtkAlgorithmOutput.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkImplicitFunction.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkScalarsToColors.h"
#include "vtkStaticPointLocator.h"
#include "vtkUnsignedCharArray.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkSurfelTextureAcquisition);

struct vtkSurfelTextureAcquisition::Callback
{
  TextureFunction Function;
  bool HasAlpha = false;
};

namespace
{
using Vec2 = std::array<double, 2>;
using Vec3 = std::array<double, 3>;
using Color = std::array<double, 4>;

// A symmetric 2x2 matrix (xx, xy, yy).
struct Sym2
{
  double XX = 0, XY = 0, YY = 0;
};

// Square root factor L (L L^T = s) of a positive semi-definite 2x2 matrix, from its
// eigen-decomposition (robust for singular matrices). Column-major: L = [l0 l1].
void SqrtFactor(const Sym2& s, double l[4])
{
  const double mean = 0.5 * (s.XX + s.YY);
  const double half = 0.5 * (s.XX - s.YY);
  const double root = std::sqrt(half * half + s.XY * s.XY);
  const double e0 = std::max(0.0, mean + root);
  const double e1 = std::max(0.0, mean - root);
  double vx = 1.0, vy = 0.0;
  if (root > 0.0)
  {
    const double angle = 0.5 * std::atan2(s.XY, half);
    vx = std::cos(angle);
    vy = std::sin(angle);
  }
  const double r0 = std::sqrt(e0), r1 = std::sqrt(e1);
  l[0] = vx * r0;
  l[1] = vy * r0;
  l[2] = -vy * r1;
  l[3] = vx * r1;
}

//------------------------------------------------------------------------------------------------
// Textures: Sample (unfiltered) and Filter (convolved with a Gaussian of covariance Sigma, given
// in texture coordinates), both in [0, 1] RGBA.
class Texture
{
public:
  virtual ~Texture() = default;
  virtual void Sample(const Vec2& s, Color& rgba) const = 0;
  // samples: for procedural textures, the samples per axis (0: the texture's own setting).
  virtual void Filter(const Vec2& s, const Sym2& sigma, Color& rgba, int samples = 0) const = 0;
  bool HasAlpha = false;
  bool Repeat = true;

  // Texture coordinates reduced to [0, 1) (repeat) or clamped to [0, 1].
  Vec2 Wrap(const Vec2& s) const
  {
    Vec2 w;
    for (int i = 0; i < 2; ++i)
    {
      w[i] = this->Repeat ? s[i] - std::floor(s[i]) : std::min(1.0, std::max(0.0, s[i]));
    }
    return w;
  }
};

class ImageTexture : public Texture
{
public:
  int Size[2] = { 1, 1 };
  std::vector<float> Texels; // RGBA, row by row

  // The EWA filter over at most about this many texels per lookup (larger footprints are
  // strided: a mipmap would be exact).
  static constexpr double MaximumTexels = 4096.0;

  int WrapIndex(long long i, int n) const
  {
    if (this->Repeat)
    {
      const long long m = i % n;
      return static_cast<int>(m < 0 ? m + n : m);
    }
    return static_cast<int>(std::min<long long>(n - 1, std::max<long long>(0, i)));
  }

  const float* Texel(long long i, long long j) const
  {
    return &this->Texels[4 *
      (static_cast<std::size_t>(this->WrapIndex(j, this->Size[1])) * this->Size[0] +
        this->WrapIndex(i, this->Size[0]))];
  }

  void Sample(const Vec2& s, Color& rgba) const override
  {
    const Vec2 w = this->Wrap(s);
    const double x = w[0] * this->Size[0] - 0.5, y = w[1] * this->Size[1] - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double ax = x - fx, ay = y - fy;
    const auto i = static_cast<long long>(fx), j = static_cast<long long>(fy);
    const float* t00 = this->Texel(i, j);
    const float* t10 = this->Texel(i + 1, j);
    const float* t01 = this->Texel(i, j + 1);
    const float* t11 = this->Texel(i + 1, j + 1);
    for (int c = 0; c < 4; ++c)
    {
      rgba[c] =
        (1 - ay) * ((1 - ax) * t00[c] + ax * t10[c]) + ay * ((1 - ax) * t01[c] + ax * t11[c]);
    }
  }

  void Filter(const Vec2& s, const Sym2& sigma, Color& rgba, int = 0) const override
  {
    const Vec2 w = this->Wrap(s);
    const double nx = this->Size[0], ny = this->Size[1];
    // In texel units, plus the texel reconstruction Gaussian of variance 1/2.
    Sym2 t{ sigma.XX * nx * nx + 0.5, sigma.XY * nx * ny, sigma.YY * ny * ny + 0.5 };
    const double det = t.XX * t.YY - t.XY * t.XY;
    if (!(det > 0.0) || !std::isfinite(det))
    {
      this->Sample(s, rgba);
      return;
    }
    const double cxx = t.YY / det, cxy = -t.XY / det, cyy = t.XX / det;
    const double x = w[0] * nx - 0.5, y = w[1] * ny - 0.5;
    // 3 sigma; clamped to the texture's size plus a little when repeating (a footprint larger
    // than the texture averages the whole of it).
    const double hx = std::min(3.0 * std::sqrt(t.XX), 2.0 * nx + 3.0);
    const double hy = std::min(3.0 * std::sqrt(t.YY), 2.0 * ny + 3.0);
    const auto i0 = static_cast<long long>(std::ceil(x - hx));
    const auto i1 = static_cast<long long>(std::floor(x + hx));
    const auto j0 = static_cast<long long>(std::ceil(y - hy));
    const auto j1 = static_cast<long long>(std::floor(y + hy));
    const double count = static_cast<double>(i1 - i0 + 1) * static_cast<double>(j1 - j0 + 1);
    const long long stride = count > MaximumTexels
      ? static_cast<long long>(std::ceil(std::sqrt(count / MaximumTexels)))
      : 1;
    double sum[4] = { 0, 0, 0, 0 };
    double weights = 0.0;
    for (long long j = j0; j <= j1; j += stride)
    {
      const double dy = j - y;
      for (long long i = i0; i <= i1; i += stride)
      {
        const double dx = i - x;
        const double e = 0.5 * (cxx * dx * dx + 2.0 * cxy * dx * dy + cyy * dy * dy);
        if (e > 4.5)
        {
          continue;
        }
        const double g = std::exp(-e);
        const float* texel = this->Texel(i, j);
        for (int c = 0; c < 4; ++c)
        {
          sum[c] += g * texel[c];
        }
        weights += g;
      }
    }
    if (!(weights > 0.0))
    {
      this->Sample(s, rgba);
      return;
    }
    for (int c = 0; c < 4; ++c)
    {
      rgba[c] = sum[c] / weights;
    }
  }
};

// Procedural textures: Filter samples the function on a grid over +-2.5 sigma of the Gaussian.
class FunctionTexture : public Texture
{
public:
  int Samples = 16;

  virtual void Evaluate(double s, double t, Color& rgba) const = 0;

  // Procedural textures are defined everywhere: evaluated where the coordinates are.
  void Sample(const Vec2& s, Color& rgba) const override
  {
    this->Evaluate(s[0], s[1], rgba);
    for (double& v : rgba)
    {
      v = std::isfinite(v) ? std::min(1.0, std::max(0.0, v)) : 0.0;
    }
  }

  void Filter(const Vec2& s, const Sym2& sigma, Color& rgba, int samples = 0) const override
  {
    double l[4];
    SqrtFactor(sigma, l);
    const int n = samples > 0 ? samples : this->Samples;
    if (n == 1 || !(std::abs(l[0]) + std::abs(l[1]) + std::abs(l[2]) + std::abs(l[3]) > 0.0))
    {
      this->Sample(s, rgba);
      return;
    }
    // The grid's positions and separable Gaussian weights along one axis (n <= 256).
    double z[256], g1[256];
    for (int i = 0; i < n; ++i)
    {
      z[i] = -2.5 + 5.0 * (i + 0.5) / n;
      g1[i] = std::exp(-0.5 * z[i] * z[i]);
    }
    double sum[4] = { 0, 0, 0, 0 };
    double weights = 0.0;
    Color value;
    for (int j = 0; j < n; ++j)
    {
      const double zy = z[j];
      for (int i = 0; i < n; ++i)
      {
        const double zx = z[i];
        const double g = g1[i] * g1[j];
        this->Sample({ s[0] + l[0] * zx + l[2] * zy, s[1] + l[1] * zx + l[3] * zy }, value);
        for (int c = 0; c < 4; ++c)
        {
          sum[c] += g * value[c];
        }
        weights += g;
      }
    }
    for (int c = 0; c < 4; ++c)
    {
      rgba[c] = sum[c] / weights;
    }
  }
};

class CallbackTexture : public FunctionTexture
{
public:
  vtkSurfelTextureAcquisition::TextureFunction Function;
  void Evaluate(double s, double t, Color& rgba) const override
  {
    rgba = { 0, 0, 0, 1 };
    this->Function(s, t, rgba.data());
  }
};

class ImplicitTexture : public FunctionTexture
{
public:
  vtkImplicitFunction* Function = nullptr;
  vtkScalarsToColors* Colors = nullptr;
  void Evaluate(double s, double t, Color& rgba) const override
  {
    double x[3] = { s, t, 0.0 };
    const double value = this->Function->FunctionValue(x);
    if (this->Colors)
    {
      double rgb[3];
      this->Colors->GetColor(value, rgb);
      rgba = { rgb[0], rgb[1], rgb[2], this->Colors->GetOpacity(value) };
    }
    else
    {
      const double grey = std::isfinite(value) ? std::min(1.0, std::max(0.0, value)) : 0.0;
      rgba = { grey, grey, grey, 1.0 };
    }
  }
};

std::unique_ptr<ImageTexture> MakeImageTexture(vtkImageData* image, std::string& error)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars || dims[0] < 1 || dims[1] < 1)
  {
    error = "the texture image has no point scalars or no texels";
    return nullptr;
  }
  const int components = scalars->GetNumberOfComponents();
  if (components < 1 || components > 4)
  {
    error = "the texture image has " + std::to_string(components) +
      " components; 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA) are supported";
    return nullptr;
  }
  auto texture = std::make_unique<ImageTexture>();
  texture->Size[0] = dims[0];
  texture->Size[1] = dims[1];
  texture->HasAlpha = components == 2 || components == 4;
  const double scale = scalars->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
  const vtkIdType count = static_cast<vtkIdType>(dims[0]) * dims[1]; // slice z = 0
  texture->Texels.resize(4 * static_cast<std::size_t>(count));
  vtkSMPTools::For(0, count, [&](vtkIdType first, vtkIdType last) {
    double tuple[4];
    for (vtkIdType i = first; i < last; ++i)
    {
      scalars->GetTuple(i, tuple);
      double rgba[4];
      if (components <= 2)
      {
        rgba[0] = rgba[1] = rgba[2] = tuple[0];
        rgba[3] = components == 2 ? tuple[1] : 1.0 / scale;
      }
      else
      {
        rgba[0] = tuple[0];
        rgba[1] = tuple[1];
        rgba[2] = tuple[2];
        rgba[3] = components == 4 ? tuple[3] : 1.0 / scale;
      }
      for (int c = 0; c < 4; ++c)
      {
        const double v = rgba[c] * scale;
        texture->Texels[4 * i + c] =
          static_cast<float>(std::isfinite(v) ? std::min(1.0, std::max(0.0, v)) : 0.0);
      }
    }
  });
  return texture;
}

// One surfel: center, tangent axes (their lengths the semi-axes), unit normal, texture
// coordinates, and the affine map M from axis units to texture coordinates (columns dS/du0,
// dS/du1).
struct Surfel
{
  Vec3 P, A0, A1, N;
  Vec2 S;
  double M[4] = { 0, 0, 0, 0 }; // column-major
  double Area = 0.0;            // |a0 x a1|
  bool Valid = false;
  bool MapValid = false;
};

double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Axis-unit coordinates of the tangent-plane projection of x - P (least squares on the axes).
bool AxisCoordinates(const Surfel& s, const Vec3& d, Vec2& u)
{
  const double g00 = Dot(s.A0, s.A0), g01 = Dot(s.A0, s.A1), g11 = Dot(s.A1, s.A1);
  const double det = g00 * g11 - g01 * g01;
  if (!(det > 0.0))
  {
    return false;
  }
  const double b0 = Dot(s.A0, d), b1 = Dot(s.A1, d);
  u[0] = (g11 * b0 - g01 * b1) / det;
  u[1] = (g00 * b1 - g01 * b0) / det;
  return true;
}

// The texture-space covariance of the axis-unit covariance v I mapped by M.
Sym2 MapCovariance(const double m[4], double v)
{
  return { v * (m[0] * m[0] + m[2] * m[2]), v * (m[0] * m[1] + m[2] * m[3]),
    v * (m[1] * m[1] + m[3] * m[3]) };
}

//------------------------------------------------------------------------------------------------
// The optimal fit (eq. 10 and 11) with the normalized basis rhat_k = r_k / S, S = sum_j r_j.
struct OptimalSettings
{
  double Cutoff;
  int Resolution;
  double Lambda;
  int MaximumIterations;
  double Tolerance;
  int Components;
  int Samples;
};

struct OptimalStatistics
{
  vtkIdType Unknowns = 0;
  vtkIdType NonZeros = 0;
  int Iterations = 0;
  double Error = 0.0;
};

// Contributions of the nodes of one surfel: R's upper-triangle entries and b's rows.
struct Assembly
{
  std::vector<Eigen::Triplet<double>> Entries;
  std::vector<std::pair<vtkIdType, Color>> Rhs;
  vtkIdList* Ids = nullptr;
};

void SolveOptimal(const std::vector<Surfel>& surfels, const std::vector<vtkIdType>& validIds,
  vtkStaticPointLocator* locator, double maxRadius, const Texture& texture,
  const OptimalSettings& settings, std::vector<Color>& w, OptimalStatistics& statistics,
  const std::function<bool(double)>& progress)
{
  const auto valid = static_cast<vtkIdType>(validIds.size());
  auto radiusOf = [](const Surfel& s)
  { return std::sqrt(std::max(Dot(s.A0, s.A0), Dot(s.A1, s.A1))); };

  // Coincident surfels (centers within 1e-6 of the radius) have the same basis function: they
  // share one unknown, whose basis is the representative's (the lowest index) times their count.
  std::vector<vtkIdType> representative(valid);
  vtkSMPThreadLocalObject<vtkIdList> nearIds;
  vtkSMPTools::For(0, valid, [&](vtkIdType first, vtkIdType last) {
    vtkIdList* ids = nearIds.Local();
    for (vtkIdType v = first; v < last; ++v)
    {
      const Surfel& s = surfels[validIds[v]];
      locator->FindPointsWithinRadius(1e-6 * radiusOf(s), s.P.data(), ids);
      vtkIdType lowest = v;
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        lowest = std::min(lowest, ids->GetId(i));
      }
      representative[v] = lowest;
    }
  });
  std::vector<double> multiplicity(valid, 0.0);
  std::vector<vtkIdType> unknown(valid, -1);
  vtkIdType unknowns = 0;
  for (vtkIdType v = 0; v < valid; ++v)
  {
    representative[v] = representative[representative[v]]; // chains end at a lower index
    multiplicity[representative[v]] += 1.0;
    if (representative[v] == v)
    {
      unknown[v] = unknowns++;
    }
  }
  statistics.Unknowns = unknowns;
  const double rho = std::sqrt(settings.Cutoff);
  const int q = settings.Resolution;
  const double cell = 2.0 * rho / q; // node cell side in axis units
  // Procedural textures at the nodes: the samples per axis scaled down from the surfel's filter
  // (standard deviation sqrt(1/2)) to the node's (cell / 2).
  const int nodeSamples =
    std::max(2, static_cast<int>(std::ceil(settings.Samples * cell * std::sqrt(0.5))));

  vtkSMPThreadLocal<Assembly> local;
  vtkSMPThreadLocalObject<vtkIdList> localIds;
  vtkSMPTools::For(0, valid, [&](vtkIdType first, vtkIdType last) {
    Assembly& assembly = local.Local();
    vtkIdList* ids = localIds.Local();
    std::vector<vtkIdType> candidates;
    std::vector<double> gram;
    std::vector<Color> rhs;
    std::vector<std::pair<int, double>> active;
    for (vtkIdType v = first; v < last; ++v)
    {
      if (representative[v] != v)
      {
        continue;
      }
      const Surfel& s = surfels[validIds[v]];
      const double radius = radiusOf(s);
      // Every surfel whose support can hold a node of this one: in-plane distance below
      // rho (R_v + R_c) and normal offset below rho R_c.
      locator->FindPointsWithinRadius(
        rho * (radius + std::sqrt(2.0) * maxRadius) * (1.0 + 1e-9), s.P.data(), ids);
      candidates.clear();
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        const vtkIdType c = ids->GetId(i);
        if (representative[c] == c && Dot(surfels[validIds[c]].N, s.N) > 0.0)
        {
          candidates.push_back(c);
        }
      }
      const std::size_t m = candidates.size();
      gram.assign(m * m, 0.0);
      rhs.assign(m, Color{ 0, 0, 0, 0 });
      for (int j = 0; j < q; ++j)
      {
        const double u1 = -rho + (j + 0.5) * cell;
        for (int i = 0; i < q; ++i)
        {
          const double u0 = -rho + (i + 0.5) * cell;
          const double own = u0 * u0 + u1 * u1;
          if (!(own < settings.Cutoff))
          {
            continue;
          }
          const Vec3 x = { s.P[0] + u0 * s.A0[0] + u1 * s.A1[0],
            s.P[1] + u0 * s.A0[1] + u1 * s.A1[1], s.P[2] + u0 * s.A0[2] + u1 * s.A1[2] };
          active.clear();
          double sum = 0.0;
          for (std::size_t a = 0; a < m; ++a)
          {
            const Surfel& o = surfels[validIds[candidates[a]]];
            const Vec3 d = { x[0] - o.P[0], x[1] - o.P[1], x[2] - o.P[2] };
            const double oRadius = radiusOf(o);
            Vec2 u;
            if (std::abs(Dot(d, o.N)) > rho * oRadius || !AxisCoordinates(o, d, u))
            {
              continue;
            }
            const double e = u[0] * u[0] + u[1] * u[1];
            if (e < settings.Cutoff)
            {
              const double r = multiplicity[candidates[a]] * std::exp(-e);
              active.emplace_back(static_cast<int>(a), r);
              sum += r;
            }
          }
          if (!(sum > 0.0))
          {
            continue; // cannot happen: the node lies in its own surfel's support
          }
          // The node's weight: cell area times this surfel's share r_v / S of the partition.
          const double weight =
            cell * cell * s.Area * multiplicity[v] * std::exp(-own) / sum;
          const double inverse = 1.0 / sum; // rhat_a = r_a / S
          Color f;
          const Vec2 st = { s.S[0] + s.M[0] * u0 + s.M[2] * u1,
            s.S[1] + s.M[1] * u0 + s.M[3] * u1 };
          texture.Filter(st, MapCovariance(s.M, 0.25 * cell * cell), f, nodeSamples);
          for (std::size_t a = 0; a < active.size(); ++a)
          {
            const int ia = active[a].first;
            const double wa = weight * active[a].second * inverse;
            for (int c = 0; c < settings.Components; ++c)
            {
              rhs[ia][c] += wa * f[c];
            }
            for (std::size_t b = a; b < active.size(); ++b)
            {
              gram[ia * m + active[b].first] += wa * active[b].second * inverse;
            }
          }
        }
      }
      for (std::size_t a = 0; a < m; ++a)
      {
        for (std::size_t b = 0; b < m; ++b)
        {
          const double value = gram[a * m + b];
          if (value != 0.0)
          {
            const vtkIdType ga = unknown[candidates[a]], gb = unknown[candidates[b]];
            assembly.Entries.emplace_back(std::min(ga, gb), std::max(ga, gb), value);
          }
        }
        if (rhs[a][0] != 0.0 || rhs[a][1] != 0.0 || rhs[a][2] != 0.0 || rhs[a][3] != 0.0)
        {
          assembly.Rhs.emplace_back(unknown[candidates[a]], rhs[a]);
        }
      }
    }
  });
  if (!progress(0.5))
  {
    return;
  }

  // R (upper triangle) and b.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(unknowns, settings.Components);
  for (Assembly& assembly : local)
  {
    entries.insert(entries.end(), assembly.Entries.begin(), assembly.Entries.end());
    assembly.Entries = {};
    for (const auto& row : assembly.Rhs)
    {
      for (int c = 0; c < settings.Components; ++c)
      {
        b(row.first, c) += row.second[c];
      }
    }
  }
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, std::ptrdiff_t>;
  Matrix a(unknowns, unknowns);
  a.setFromTriplets(entries.begin(), entries.end());
  entries = {};
  a.makeCompressed();
  statistics.NonZeros = static_cast<vtkIdType>(a.nonZeros());

  // Tikhonov towards the view-independent result: (R + lambda D) w = b + lambda D w_VI.
  Eigen::VectorXd diagonal = a.diagonal();
  for (vtkIdType k = 0; k < unknowns; ++k)
  {
    a.coeffRef(k, k) += settings.Lambda * diagonal[k];
  }
  Eigen::ConjugateGradient<Matrix, Eigen::Upper> cg;
  cg.setTolerance(settings.Tolerance);
  cg.compute(a);
  constexpr int Chunk = 25; // iterations between progress reports
  for (int c = 0; c < settings.Components; ++c)
  {
    Eigen::VectorXd start(unknowns), rhs(unknowns);
    for (vtkIdType v = 0; v < valid; ++v)
    {
      if (const vtkIdType k = unknown[v]; k >= 0)
      {
        start[k] = w[v][c];
        rhs[k] = b(k, c) + settings.Lambda * diagonal[k] * w[v][c];
      }
    }
    Eigen::VectorXd x = start;
    int iterations = 0;
    double error = 0.0;
    while (iterations < settings.MaximumIterations)
    {
      cg.setMaxIterations(std::min(Chunk, settings.MaximumIterations - iterations));
      x = cg.solveWithGuess(rhs, x);
      iterations += static_cast<int>(cg.iterations());
      error = cg.error();
      if (cg.info() == Eigen::Success || cg.iterations() == 0 ||
        !progress(0.5 + 0.5 * (c + static_cast<double>(iterations) / settings.MaximumIterations) /
            settings.Components))
      {
        break;
      }
    }
    statistics.Iterations = std::max(statistics.Iterations, iterations);
    statistics.Error = std::max(statistics.Error, error);
    if (!x.allFinite())
    {
      continue; // keep the view-independent result
    }
    for (vtkIdType v = 0; v < valid; ++v)
    {
      w[v][c] = x[unknown[representative[v]]];
    }
  }
}
}

//------------------------------------------------------------------------------
vtkSurfelTextureAcquisition::vtkSurfelTextureAcquisition()
  : Function(new Callback)
{
  this->SetNumberOfInputPorts(2);
  this->SetRadiusArrayName("Radius");
  this->SetTangentAxis0ArrayName("TangentAxis0");
  this->SetTangentAxis1ArrayName("TangentAxis1");
  this->SetOutputArrayName("TextureColors");
}

//------------------------------------------------------------------------------
vtkSurfelTextureAcquisition::~vtkSurfelTextureAcquisition()
{
  this->SetRadiusArrayName(nullptr);
  this->SetTangentAxis0ArrayName(nullptr);
  this->SetTangentAxis1ArrayName(nullptr);
  this->SetTextureCoordinatesArrayName(nullptr);
  this->SetOutputArrayName(nullptr);
  delete this->Function;
}

//------------------------------------------------------------------------------
const char* vtkSurfelTextureAcquisition::GetModeAsString(int mode)
{
  switch (mode)
  {
    case POINT_SAMPLING:
      return "point-sampling";
    case VIEW_INDEPENDENT_EWA:
      return "view-independent-ewa";
    case OPTIMAL:
      return "optimal";
    default:
      return "unknown";
  }
}

//------------------------------------------------------------------------------
void vtkSurfelTextureAcquisition::SetTextureData(vtkImageData* image)
{
  this->SetInputData(1, image);
}

//------------------------------------------------------------------------------
void vtkSurfelTextureAcquisition::SetTextureConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
void vtkSurfelTextureAcquisition::SetImplicitTexture(vtkImplicitFunction* function)
{
  if (this->ImplicitTexture != function)
  {
    this->ImplicitTexture = function;
    this->Modified();
  }
}

vtkImplicitFunction* vtkSurfelTextureAcquisition::GetImplicitTexture()
{
  return this->ImplicitTexture;
}

void vtkSurfelTextureAcquisition::SetImplicitTextureColors(vtkScalarsToColors* colors)
{
  if (this->ImplicitTextureColors != colors)
  {
    this->ImplicitTextureColors = colors;
    this->Modified();
  }
}

vtkScalarsToColors* vtkSurfelTextureAcquisition::GetImplicitTextureColors()
{
  return this->ImplicitTextureColors;
}

void vtkSurfelTextureAcquisition::SetTextureFunction(TextureFunction function, bool hasAlpha)
{
  this->Function->Function = std::move(function);
  this->Function->HasAlpha = hasAlpha;
  this->Modified();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkSurfelTextureAcquisition::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->ImplicitTexture)
  {
    time = std::max(time, this->ImplicitTexture->GetMTime());
  }
  if (this->ImplicitTextureColors)
  {
    time = std::max(time, this->ImplicitTextureColors->GetMTime());
  }
  return time;
}

//------------------------------------------------------------------------------
int vtkSurfelTextureAcquisition::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkSurfelTextureAcquisition::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkImageData* image = vtkImageData::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->NumberOfSkippedPoints = 0;
  this->NumberOfDegenerateMaps = 0;
  this->NumberOfClampedValues = 0;
  this->NumberOfUnknowns = 0;
  this->NumberOfNonZeros = 0;
  this->NumberOfIterations = 0;
  this->SolverError = 0.0;
  if (!input || !output)
  {
    return 0;
  }
  output->ShallowCopy(input);
  if (!this->OutputArrayName || !*this->OutputArrayName)
  {
    vtkErrorMacro("OutputArrayName must be a non-empty name.");
    return 0;
  }
  if (this->OutputScalarType != VTK_UNSIGNED_CHAR && this->OutputScalarType != VTK_FLOAT)
  {
    vtkErrorMacro("OutputScalarType must be VTK_UNSIGNED_CHAR or VTK_FLOAT.");
    return 0;
  }

  // The texture.
  std::unique_ptr<Texture> texture;
  if (image)
  {
    std::string error;
    texture = MakeImageTexture(image, error);
    if (!texture)
    {
      vtkErrorMacro("Cannot use the texture image: " << error << ".");
      return 0;
    }
  }
  else if (this->ImplicitTexture)
  {
    auto implicit = std::make_unique<::ImplicitTexture>();
    implicit->Function = this->ImplicitTexture;
    implicit->Colors = this->ImplicitTextureColors;
    implicit->Samples = this->ProceduralSamples;
    implicit->HasAlpha = this->ImplicitTextureColors != nullptr;
    texture = std::move(implicit);
  }
  else if (this->Function->Function)
  {
    auto callback = std::make_unique<CallbackTexture>();
    callback->Function = this->Function->Function;
    callback->Samples = this->ProceduralSamples;
    callback->HasAlpha = this->Function->HasAlpha;
    texture = std::move(callback);
  }
  else
  {
    vtkErrorMacro("No texture: give an image on input port 1 (SetTextureData), an implicit "
                  "function (SetImplicitTexture) or a callback (SetTextureFunction).");
    return 0;
  }
  texture->Repeat = this->Repeat;

  // The surfels.
  const vtkIdType n = input->GetNumberOfPoints();
  if (n == 0)
  {
    return 1; // nothing to color
  }
  vtkPointData* pd = input->GetPointData();
  vtkDataArray* tcoords = (this->TextureCoordinatesArrayName && *this->TextureCoordinatesArrayName)
    ? pd->GetArray(this->TextureCoordinatesArrayName)
    : pd->GetTCoords();
  if (!tcoords || tcoords->GetNumberOfComponents() < 2)
  {
    vtkErrorMacro("The input has no texture coordinates with at least 2 components ("
      << (this->TextureCoordinatesArrayName ? this->TextureCoordinatesArrayName : "active TCoords")
      << ").");
    return 0;
  }
  vtkDataArray* axis0 =
    this->TangentAxis0ArrayName ? pd->GetArray(this->TangentAxis0ArrayName) : nullptr;
  vtkDataArray* axis1 =
    this->TangentAxis1ArrayName ? pd->GetArray(this->TangentAxis1ArrayName) : nullptr;
  if (!axis0 || !axis1 || axis0->GetNumberOfComponents() != 3 ||
    axis1->GetNumberOfComponents() != 3)
  {
    axis0 = axis1 = nullptr;
  }
  vtkDataArray* normals = pd->GetNormals();
  if (!axis0 && (!normals || normals->GetNumberOfComponents() != 3))
  {
    vtkErrorMacro("The input has neither point normals nor tangent-axis arrays ("
      << (this->TangentAxis0ArrayName ? this->TangentAxis0ArrayName : "") << ", "
      << (this->TangentAxis1ArrayName ? this->TangentAxis1ArrayName : "")
      << "): run vtkSurfelGenerator first.");
    return 0;
  }
  vtkDataArray* radii = this->RadiusArrayName ? pd->GetArray(this->RadiusArrayName) : nullptr;
  const bool hasAlpha = texture->HasAlpha;
  const int components = hasAlpha ? 4 : 3;

  vtkSmartPointer<vtkDataArray> colors;
  colors.TakeReference(vtkDataArray::CreateDataArray(this->OutputScalarType));
  colors->SetName(this->OutputArrayName);
  colors->SetNumberOfComponents(components);
  colors->SetNumberOfTuples(n);
  output->GetPointData()->AddArray(colors);
  output->GetPointData()->SetActiveScalars(this->OutputArrayName);
  if (n == 0)
  {
    return 1;
  }

  std::vector<Surfel> surfels(n);
  vtkPoints* inPoints = input->GetPoints();
  vtkSMPTools::For(0, n, [&](vtkIdType first, vtkIdType last) {
    for (vtkIdType k = first; k < last; ++k)
    {
      Surfel& s = surfels[k];
      double p[3], t[3];
      inPoints->GetPoint(k, p);
      s.P = { p[0], p[1], p[2] };
      tcoords->GetTuple(k, t);
      s.S = { t[0], t[1] };
      if (axis0)
      {
        axis0->GetTuple(k, p);
        s.A0 = { p[0], p[1], p[2] };
        axis1->GetTuple(k, p);
        s.A1 = { p[0], p[1], p[2] };
      }
      else
      {
        double normal[3], u[3], v[3];
        normals->GetTuple(k, normal);
        const double length = vtkMath::Normalize(normal);
        const double r = radii ? radii->GetComponent(k, 0) : this->Radius;
        if (!(length > 0.0) || !std::isfinite(length) || !(r > 0.0) || !std::isfinite(r))
        {
          continue;
        }
        vtkMath::Perpendiculars(normal, u, v, 0.0);
        s.A0 = { r * u[0], r * u[1], r * u[2] };
        s.A1 = { r * v[0], r * v[1], r * v[2] };
      }
      double a0[3] = { s.A0[0], s.A0[1], s.A0[2] }, a1[3] = { s.A1[0], s.A1[1], s.A1[2] }, c[3];
      vtkMath::Cross(a0, a1, c);
      s.Area = vtkMath::Norm(c);
      bool finite = std::isfinite(s.S[0]) && std::isfinite(s.S[1]) && std::isfinite(s.Area);
      for (int i = 0; i < 3; ++i)
      {
        finite = finite && std::isfinite(s.P[i]);
      }
      if (!finite || !(s.Area > 0.0))
      {
        continue;
      }
      s.N = { c[0] / s.Area, c[1] / s.Area, c[2] / s.Area };
      s.Valid = true;
    }
  });

  // The valid surfels in a locator.
  std::vector<vtkIdType> validIds;
  validIds.reserve(n);
  for (vtkIdType k = 0; k < n; ++k)
  {
    if (surfels[k].Valid)
    {
      validIds.push_back(k);
    }
  }
  this->NumberOfSkippedPoints = n - static_cast<vtkIdType>(validIds.size());
  const auto valid = static_cast<vtkIdType>(validIds.size());
  vtkNew<vtkPoints> validPoints;
  validPoints->SetDataTypeToDouble();
  validPoints->SetNumberOfPoints(valid);
  double maxRadius = 0.0;
  for (vtkIdType v = 0; v < valid; ++v)
  {
    const Surfel& s = surfels[validIds[v]];
    validPoints->SetPoint(v, s.P.data());
    maxRadius = std::max(
      { maxRadius, std::sqrt(Dot(s.A0, s.A0)), std::sqrt(Dot(s.A1, s.A1)) });
  }
  vtkNew<vtkPolyData> validSet;
  validSet->SetPoints(validPoints);
  vtkNew<vtkStaticPointLocator> locator;
  if (valid > 0)
  {
    locator->SetDataSet(validSet);
    locator->BuildLocator();
  }
  this->UpdateProgress(0.1);

  // Affine maps: the least-squares fit of the neighbors' texture-coordinate differences to their
  // axis-unit offsets, M = (sum ds d^T) (sum d d^T)^-1. With repeating textures the differences
  // are taken modulo 1 (the nearest copy), so that seams of a wrapped parameterization fit.
  const int neighbors = std::min<vtkIdType>(this->NumberOfNeighbors + 1, valid);
  const bool repeat = this->Repeat && image != nullptr;
  vtkSMPThreadLocalObject<vtkIdList> localIds;
  vtkSMPThreadLocal<vtkIdType> localDegenerate;
  vtkSMPTools::For(0, valid, [&](vtkIdType first, vtkIdType last) {
    vtkIdList* ids = localIds.Local();
    vtkIdType& degenerate = localDegenerate.Local();
    for (vtkIdType v = first; v < last; ++v)
    {
      Surfel& s = surfels[validIds[v]];
      locator->FindClosestNPoints(neighbors, s.P.data(), ids);
      double dd[3] = { 0, 0, 0 };     // sum d d^T (xx, xy, yy)
      double sd[4] = { 0, 0, 0, 0 };  // sum ds d^T, column-major
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        const Surfel& o = surfels[validIds[ids->GetId(i)]];
        Vec2 u;
        const Vec3 d = { o.P[0] - s.P[0], o.P[1] - s.P[1], o.P[2] - s.P[2] };
        if (&o == &s || !AxisCoordinates(s, d, u))
        {
          continue;
        }
        double ds[2] = { o.S[0] - s.S[0], o.S[1] - s.S[1] };
        if (repeat)
        {
          ds[0] -= std::round(ds[0]);
          ds[1] -= std::round(ds[1]);
        }
        dd[0] += u[0] * u[0];
        dd[1] += u[0] * u[1];
        dd[2] += u[1] * u[1];
        sd[0] += ds[0] * u[0];
        sd[1] += ds[1] * u[0];
        sd[2] += ds[0] * u[1];
        sd[3] += ds[1] * u[1];
      }
      const double det = dd[0] * dd[2] - dd[1] * dd[1];
      const double trace = dd[0] + dd[2];
      if (!(det > 1e-8 * trace * trace) || !(trace > 0.0))
      {
        ++degenerate;
        continue;
      }
      const double i00 = dd[2] / det, i01 = -dd[1] / det, i11 = dd[0] / det;
      s.M[0] = sd[0] * i00 + sd[2] * i01;
      s.M[1] = sd[1] * i00 + sd[3] * i01;
      s.M[2] = sd[0] * i01 + sd[2] * i11;
      s.M[3] = sd[1] * i01 + sd[3] * i11;
      s.MapValid = std::isfinite(s.M[0]) && std::isfinite(s.M[1]) && std::isfinite(s.M[2]) &&
        std::isfinite(s.M[3]);
      if (!s.MapValid)
      {
        ++degenerate;
        std::fill(s.M, s.M + 4, 0.0);
      }
    }
  });
  for (vtkIdType d : localDegenerate)
  {
    this->NumberOfDegenerateMaps += d;
  }
  this->UpdateProgress(0.3);

  // Point sampling or the view-independent EWA prefilter (also the optimal fit's start).
  const int mode = this->Mode;
  std::vector<Color> w(valid);
  vtkSMPTools::For(0, valid, [&](vtkIdType first, vtkIdType last) {
    for (vtkIdType v = first; v < last; ++v)
    {
      const Surfel& s = surfels[validIds[v]];
      if (mode == POINT_SAMPLING || !s.MapValid)
      {
        texture->Sample(s.S, w[v]);
      }
      else
      {
        texture->Filter(s.S, MapCovariance(s.M, 0.5), w[v]);
      }
    }
  });
  this->UpdateProgress(0.5);

  if (mode == OPTIMAL && valid > 0 && !this->GetAbortExecute())
  {
    OptimalSettings settings{ this->Cutoff, this->QuadratureResolution, this->Regularization,
      this->MaximumNumberOfIterations, this->Tolerance, components, this->ProceduralSamples };
    OptimalStatistics statistics;
    SolveOptimal(surfels, validIds, locator, maxRadius, *texture, settings, w, statistics,
      [this](double fraction) {
        this->UpdateProgress(0.5 + 0.5 * fraction);
        return !this->GetAbortExecute();
      });
    this->NumberOfUnknowns = statistics.Unknowns;
    this->NumberOfNonZeros = statistics.NonZeros;
    this->NumberOfIterations = statistics.Iterations;
    this->SolverError = statistics.Error;
  }

  // The output, clamped to [0, 1]; invalid surfels black.
  std::vector<vtkIdType> validIndex(n, -1);
  for (vtkIdType v = 0; v < valid; ++v)
  {
    validIndex[validIds[v]] = v;
  }
  vtkSMPThreadLocal<vtkIdType> localClamped;
  const bool bytes = this->OutputScalarType == VTK_UNSIGNED_CHAR;
  vtkSMPTools::For(0, n, [&](vtkIdType first, vtkIdType last) {
    vtkIdType& clamped = localClamped.Local();
    for (vtkIdType k = first; k < last; ++k)
    {
      const vtkIdType v = validIndex[k];
      Color c = v >= 0 ? w[v] : Color{ 0, 0, 0, 1 };
      for (int i = 0; i < components; ++i)
      {
        double value = std::isfinite(c[i]) ? c[i] : 0.0;
        if (value < 0.0 || value > 1.0)
        {
          ++clamped;
          value = std::min(1.0, std::max(0.0, value));
        }
        colors->SetComponent(k, i, bytes ? std::round(255.0 * value) : value);
      }
    }
  });
  for (vtkIdType c : localClamped)
  {
    this->NumberOfClampedValues += c;
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSurfelTextureAcquisition::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << GetModeAsString(this->Mode) << "\n";
  os << indent << "Repeat: " << this->Repeat << "\n";
  os << indent << "RadiusArrayName: " << (this->RadiusArrayName ? this->RadiusArrayName : "(none)")
     << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "TangentAxis0ArrayName: "
     << (this->TangentAxis0ArrayName ? this->TangentAxis0ArrayName : "(none)") << "\n";
  os << indent << "TangentAxis1ArrayName: "
     << (this->TangentAxis1ArrayName ? this->TangentAxis1ArrayName : "(none)") << "\n";
  os << indent << "TextureCoordinatesArrayName: "
     << (this->TextureCoordinatesArrayName ? this->TextureCoordinatesArrayName : "(active TCoords)")
     << "\n";
  os << indent << "ImplicitTexture: " << this->ImplicitTexture.GetPointer() << "\n";
  os << indent << "ImplicitTextureColors: " << this->ImplicitTextureColors.GetPointer() << "\n";
  os << indent << "TextureFunction: " << (this->Function->Function ? "set" : "(none)") << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "Cutoff: " << this->Cutoff << "\n";
  os << indent << "QuadratureResolution: " << this->QuadratureResolution << "\n";
  os << indent << "ProceduralSamples: " << this->ProceduralSamples << "\n";
  os << indent << "Regularization: " << this->Regularization << "\n";
  os << indent << "MaximumNumberOfIterations: " << this->MaximumNumberOfIterations << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "OutputArrayName: " << (this->OutputArrayName ? this->OutputArrayName : "(none)")
     << "\n";
  os << indent << "OutputScalarType: " << this->OutputScalarType << "\n";
  os << indent << "NumberOfSkippedPoints: " << this->NumberOfSkippedPoints << "\n";
  os << indent << "NumberOfDegenerateMaps: " << this->NumberOfDegenerateMaps << "\n";
  os << indent << "NumberOfClampedValues: " << this->NumberOfClampedValues << "\n";
  os << indent << "NumberOfUnknowns: " << this->NumberOfUnknowns << "\n";
  os << indent << "NumberOfNonZeros: " << this->NumberOfNonZeros << "\n";
  os << indent << "NumberOfIterations: " << this->NumberOfIterations << "\n";
  os << indent << "SolverError: " << this->SolverError << "\n";
}
