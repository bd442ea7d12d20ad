// SPDX-License-Identifier: BSD-3-Clause
// The local geometry of differential points (Kalaiah and Varshney 2003) for
// vtkDifferentialPointGenerator: the quadric fit that gives a point's normal, principal directions
// and curvatures, the error-bounded extents, the normal a point predicts at a nearby position
// (eq. 10) and the tangent-plane rectangle tests of the simplification. Eigen, no VTK.
#ifndef SplatDifferentialPointGeometry_h
#define SplatDifferentialPointGeometry_h

#include "SplatDifferentialPointNormal.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace splat
{
struct DifferentialPoint
{
  Eigen::Vector3d Position = Eigen::Vector3d::Zero();
  Eigen::Vector3d Normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d U = Eigen::Vector3d::UnitX(); // direction of maximum |curvature|
  Eigen::Vector3d V = Eigen::Vector3d::UnitY(); // Normal x U
  double CurvatureU = 0.0;                      // lambda_u, |lambda_u| >= |lambda_v|
  double CurvatureV = 0.0;
  double ExtentU = 0.0; // half-widths of the rectangle along U and V
  double ExtentV = 0.0;

  // (u, v) coordinates of the orthographic projection of x onto the tangent plane.
  Eigen::Vector2d Local(const Eigen::Vector3d& x) const
  {
    const Eigen::Vector3d d = x - this->Position;
    return { d.dot(this->U), d.dot(this->V) };
  }
  Eigen::Vector3d Global(const Eigen::Vector2d& uv) const
  {
    return this->Position + uv.x() * this->U + uv.y() * this->V;
  }
};

// The tangent direction the paper takes at umbilic and flat points: the longest projection of
// the x, y or z axis onto the plane of normal n.
inline Eigen::Vector3d AxisTangent(const Eigen::Vector3d& n)
{
  Eigen::Index axis;
  n.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d t = Eigen::Vector3d::Unit(axis) - n[axis] * n;
  return t.normalized();
}

// Fits z = a x^2 + b xy + c y^2 + d x + e y to the neighbors in the frame of normal n0 at
// point.Position and sets point's normal, directions and curvatures from the fitted graph's
// shape operator (II v = lambda I v). Coordinates are scaled by the neighbors' RMS distance so
// that the least-squares problem is conditioned alike at every scale. With too few or collinear
// neighbors only a, b, c are fitted (normal n0), then none (a flat point). Points whose
// curvatures differ by less than UmbilicTolerance times the larger of them and flatCurvature
// are umbilic or flat for the purpose (see below).
constexpr double UmbilicTolerance = 0.05;
inline void FitDifferentialPoint(const std::vector<Eigen::Vector3d>& neighbors,
  const Eigen::Vector3d& n0, double flatCurvature, DifferentialPoint& point)
{
  const Eigen::Vector3d t1 = AxisTangent(n0);
  const Eigen::Vector3d t2 = n0.cross(t1);
  std::vector<Eigen::Vector3d> local;
  local.reserve(neighbors.size());
  double sumSquares = 0.0;
  for (const Eigen::Vector3d& q : neighbors)
  {
    const Eigen::Vector3d d = q - point.Position;
    const Eigen::Vector3d l(d.dot(t1), d.dot(t2), d.dot(n0));
    if (l.head<2>().squaredNorm() > 0.0)
    {
      local.push_back(l);
      sumSquares += l.squaredNorm();
    }
  }
  double coefficients[5] = { 0.0, 0.0, 0.0, 0.0, 0.0 };
  const int rows = static_cast<int>(local.size());
  if (rows >= 3)
  {
    const double scale = std::sqrt(sumSquares / rows);
    for (int unknowns : { 5, 3 })
    {
      if (rows < unknowns)
      {
        continue;
      }
      Eigen::MatrixXd a(rows, unknowns);
      Eigen::VectorXd z(rows);
      for (int i = 0; i < rows; ++i)
      {
        const double x = local[i].x() / scale;
        const double y = local[i].y() / scale;
        const double row[5] = { x * x, x * y, y * y, x, y };
        for (int j = 0; j < unknowns; ++j)
        {
          a(i, j) = row[j];
        }
        z[i] = local[i].z() / scale;
      }
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
      qr.setThreshold(1e-6);
      if (qr.rank() == unknowns)
      {
        const Eigen::VectorXd solution = qr.solve(z);
        if (solution.allFinite())
        {
          for (int j = 0; j < unknowns; ++j)
          {
            // Second-order terms scale back by 1/scale, first-order ones are dimensionless.
            coefficients[j] = j < 3 ? solution[j] / scale : solution[j];
          }
          break;
        }
      }
    }
  }

  // The graph's fundamental forms at the origin: I = [1+d^2, de; de, 1+e^2],
  // II = [2a, b; b, 2c] / |(-d, -e, 1)|, and its normal (-d, -e, 1) normalized.
  const double a = coefficients[0], b = coefficients[1], c = coefficients[2];
  const double d = coefficients[3], e = coefficients[4];
  const double w = std::sqrt(1.0 + d * d + e * e);
  Eigen::Matrix2d first, second;
  first << 1.0 + d * d, d * e, d * e, 1.0 + e * e;
  second << 2.0 * a, b, b, 2.0 * c;
  second /= w;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> solver(second, first);
  Eigen::Vector2d lambda = solver.eigenvalues();
  Eigen::Matrix2d vectors = solver.eigenvectors();
  const Eigen::Vector3d normal = ((-d) * t1 + (-e) * t2 + n0).normalized();
  const int major = std::abs(lambda[1]) >= std::abs(lambda[0]) ? 1 : 0;
  const Eigen::Vector2d uv = vectors.col(major);
  // The direction's tangent vector on the graph: u X_x + v X_y with X_x = (1, 0, d), X_y = (0, 1,
  // e).
  Eigen::Vector3d u = uv.x() * (t1 + d * n0) + uv.y() * (t2 + e * n0);
  point.CurvatureU = lambda[major];
  point.CurvatureV = lambda[1 - major];
  point.Normal = normal;
  // Umbilic and flat points have no principal directions: those the fit gives them follow
  // its noise, so that neighboring rectangles would turn every which way (and dense samples
  // of a sphere or a plane could not cover each other in the simplification). They take the
  // paper's axis rule, which varies smoothly; the curvatures being equal within the tolerance,
  // so are the error bounds along any direction.
  const double scale = std::max({ std::abs(lambda[0]), std::abs(lambda[1]), flatCurvature });
  if (solver.info() != Eigen::Success || !u.allFinite() || u.norm() == 0.0 ||
    std::abs(lambda[1] - lambda[0]) <= UmbilicTolerance * scale)
  {
    u = AxisTangent(normal);
  }
  point.U = (u - u.dot(normal) * normal).normalized();
  point.V = normal.cross(point.U);
  if (!point.U.allFinite() || !std::isfinite(point.CurvatureU) || !std::isfinite(point.CurvatureV))
  {
    point.Normal = n0;
    point.U = t1;
    point.V = t2;
    point.CurvatureU = point.CurvatureV = 0.0;
  }
}

// The paper's half-width along a principal direction: min(delta, sqrt(2 eps - eps^2) / |lambda|),
// delta where lambda is 0.
inline double ErrorBoundedExtent(double lambda, double epsilon, double delta)
{
  const double bound = std::sqrt(2.0 * epsilon - epsilon * epsilon);
  const double k = std::abs(lambda);
  return k * delta > bound ? bound / k : delta;
}

// The unit normal point predicts at the projection of x onto its tangent plane (eq. 10,
// SplatDifferentialPointNormal.h).
inline Eigen::Vector3d PredictedNormal(const DifferentialPoint& point, const Eigen::Vector3d& x)
{
  const Eigen::Vector2d uv = point.Local(x);
  const double g = DifferentialNormalScale(point.CurvatureU, point.CurvatureV, uv.x(), uv.y());
  const Eigen::Vector3d n = point.Normal -
    g * (point.CurvatureU * uv.x() * point.U + point.CurvatureV * uv.y() * point.V);
  return n.normalized();
}

// Liang-Barsky: the parameter interval [t0, t1] of the segment a + t (b - a), t in [0, 1], inside
// the rectangle |x| <= h.x(), |y| <= h.y(); false when it misses.
inline bool ClipSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
  const Eigen::Vector2d& h, double& t0, double& t1)
{
  t0 = 0.0;
  t1 = 1.0;
  const Eigen::Vector2d delta = b - a;
  for (int axis = 0; axis < 2; ++axis)
  {
    for (double side : { -1.0, 1.0 })
    {
      // Inside: side * (a + t delta) <= h.
      const double p = side * delta[axis];
      const double q = h[axis] - side * a[axis];
      if (p == 0.0)
      {
        if (q < 0.0)
        {
          return false;
        }
      }
      else if (p > 0.0)
      {
        t1 = std::min(t1, q / p);
      }
      else
      {
        t0 = std::max(t0, q / p);
      }
    }
  }
  return t0 <= t1;
}

inline bool InRectangle(const Eigen::Vector2d& x, const Eigen::Vector2d& h)
{
  return std::abs(x.x()) <= h.x() && std::abs(x.y()) <= h.y();
}

// The paper's OverlapTest(p, q) with rectangles of half-widths scale * extents: p's center,
// corners or edges, projected orthographically onto q's tangent plane, meet q's rectangle.
inline bool OverlapTest(const DifferentialPoint& p, const DifferentialPoint& q, double scale)
{
  const Eigen::Vector2d hp(scale * p.ExtentU, scale * p.ExtentV);
  const Eigen::Vector2d hq(scale * q.ExtentU, scale * q.ExtentV);
  if (InRectangle(q.Local(p.Position), hq))
  {
    return true;
  }
  const Eigen::Vector2d corners[4] = { { hp.x(), hp.y() }, { -hp.x(), hp.y() },
    { -hp.x(), -hp.y() }, { hp.x(), -hp.y() } };
  Eigen::Vector2d projected[4];
  for (int i = 0; i < 4; ++i)
  {
    projected[i] = q.Local(p.Global(corners[i]));
    if (InRectangle(projected[i], hq))
    {
      return true;
    }
  }
  for (int i = 0; i < 4; ++i)
  {
    double t0, t1;
    if (ClipSegment(projected[i], projected[(i + 1) % 4], hq, t0, t1))
    {
      return true;
    }
  }
  return false;
}

inline bool Overlaps(const DifferentialPoint& p, const DifferentialPoint& q, double scale)
{
  // Each test needs the centers' distance along the plane within the rectangles' circumradii.
  const double reach = scale *
    (std::sqrt(p.ExtentU * p.ExtentU + p.ExtentV * p.ExtentV) +
      std::sqrt(q.ExtentU * q.ExtentU + q.ExtentV * q.ExtentV));
  const Eigen::Vector3d d = q.Position - p.Position;
  const double distance2 = d.squaredNorm(), reach2 = reach * reach;
  if (distance2 - std::pow(d.dot(p.Normal), 2) > reach2 &&
    distance2 - std::pow(d.dot(q.Normal), 2) > reach2)
  {
    return false;
  }
  return OverlapTest(p, q, scale) || OverlapTest(q, p, scale);
}
}

#endif
