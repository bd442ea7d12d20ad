// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfaceSplatRasterizer.h"

#include "SplatSurfelKernel.h"

#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkSurfaceSplatRasterizer);

namespace
{
enum CullReason
{
  Kept = 0,
  OutsideFrustum,
  BackFacing,
  Negligible
};

// Rows per band: small enough to balance the threads, large enough that few kernels straddle bands.
constexpr int BandHeight = 16;

// One surfel after setup, in the single precision the per-pixel loop uses.
struct ScreenSplat
{
  float CenterX, CenterY;
  float ConicXX, ConicXY, ConicYY; // 1/2 M^-1, so that beta = d^T C d
  float Amplitude;
  float Threshold; // eye-space z threshold
  int X0, X1, Y0, Y1; // inclusive pixel bounds
  int Culled;         // why the splat is left out, Kept when it is not
  float DepthNumerator[3];
  float DepthDenominator[3];
  float Normal[3]; // eye space, facing the viewer
  float Color[3];
};
}

struct vtkSurfaceSplatRasterizer::Internals
{
  std::vector<ScreenSplat> Splats;
  std::vector<vtkIdType> BandOffsets; // per band, into BandSplats
  std::vector<vtkIdType> BandSplats;  // splat indices, band by band, in input order
};

//------------------------------------------------------------------------------
vtkSurfaceSplatRasterizer::vtkSurfaceSplatRasterizer()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkSurfaceSplatRasterizer::~vtkSurfaceSplatRasterizer()
{
  delete this->Internal;
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::Render(const Surfels& surfels, const Camera& camera,
  const std::vector<splat::Light>& lights, const splat::Material& material)
{
  this->Splat(surfels, camera);
  this->Resolve(camera, lights, material);
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::Splat(const Surfels& surfels, const Camera& camera)
{
  const int width = camera.Viewport.x;
  const int height = camera.Viewport.y;
  const std::size_t pixels = static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0);
  this->Weights.assign(pixels, 0.0f);
  this->WeightedColors.assign(3 * pixels, 0.0f);
  this->WeightedNormals.assign(3 * pixels, 0.0f);
  this->EyeDepths.assign(pixels, std::numeric_limits<float>::infinity());
  this->SplattedCount = this->FrustumCulledCount = this->BackfaceCulledCount = 0;
  this->NegligibleCount = this->FragmentCount = 0;
  if (pixels == 0)
  {
    this->FrustumCulledCount = static_cast<vtkIdType>(surfels.Count);
    return;
  }

  const glm::dmat4 modelToClip = camera.EyeToClip * camera.ModelToEye;
  const glm::dmat4 clipToModel = glm::inverse(modelToClip);
  const glm::dmat4 clipToEye = glm::inverse(camera.EyeToClip);
  const glm::dmat3 normalToEye = glm::transpose(glm::inverse(glm::dmat3(camera.ModelToEye)));
  const glm::dvec2 viewport(width, height);
  const bool perspective = camera.EyeToClip[3][3] == 0.0;
  const double cutoff = this->Cutoff;
  const double depthThreshold = this->DepthThreshold;
  const splat::KernelFilter filter = this->Filter;
  const bool backfaceCulling = this->BackfaceCulling;

  // 1. Setup.
  std::vector<ScreenSplat>& splats = this->Internal->Splats;
  splats.resize(surfels.Count);
  vtkSMPTools::For(0, static_cast<vtkIdType>(surfels.Count),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        ScreenSplat& s = splats[i];
        s.Culled = OutsideFrustum;
        const glm::dvec3 p(surfels.Positions[3 * i], surfels.Positions[3 * i + 1],
          surfels.Positions[3 * i + 2]);
        const glm::dvec3 n(
          surfels.Normals[3 * i], surfels.Normals[3 * i + 1], surfels.Normals[3 * i + 2]);
        const glm::dvec3 a0(
          surfels.Axes0[3 * i], surfels.Axes0[3 * i + 1], surfels.Axes0[3 * i + 2]);
        const glm::dvec3 a1(
          surfels.Axes1[3 * i], surfels.Axes1[3 * i + 1], surfels.Axes1[3 * i + 2]);

        const glm::dvec4 clip = modelToClip * glm::dvec4(p, 1.0);
        splat::SurfelProjection projection;
        if (clip.z < -clip.w || clip.z > clip.w ||
          !splat::ProjectSurfel(modelToClip, viewport, p, a0, a1, projection))
        {
          continue;
        }
        const glm::dvec3 eye(camera.ModelToEye * glm::dvec4(p, 1.0));
        glm::dvec3 normal = glm::normalize(normalToEye * n);
        const glm::dvec3 view = perspective ? eye : glm::dvec3(0.0, 0.0, -1.0);
        const bool backFacing = glm::dot(normal, view) > 0.0;
        if (backFacing && backfaceCulling)
        {
          s.Culled = BackFacing;
          continue;
        }
        const splat::ResamplingKernel kernel =
          splat::MakeResamplingKernel(projection, cutoff, filter);
        if (!(kernel.Amplitude >= splat::NegligibleAmplitude))
        {
          s.Culled = Negligible;
          continue;
        }
        const glm::dvec2 lo = kernel.Center - kernel.HalfExtent - 0.5;
        const glm::dvec2 hi = kernel.Center + kernel.HalfExtent - 0.5;
        if (!(hi.x >= 0.0 && hi.y >= 0.0 && lo.x <= width - 1 && lo.y <= height - 1))
        {
          continue;
        }
        s.X0 = static_cast<int>(std::ceil(std::max(lo.x, 0.0)));
        s.X1 = static_cast<int>(std::floor(std::min(hi.x, width - 1.0)));
        s.Y0 = static_cast<int>(std::ceil(std::max(lo.y, 0.0)));
        s.Y1 = static_cast<int>(std::floor(std::min(hi.y, height - 1.0)));
        if (s.X0 > s.X1 || s.Y0 > s.Y1)
        {
          continue; // the box holds no pixel center
        }
        s.Culled = Kept;

        s.CenterX = static_cast<float>(kernel.Center.x);
        s.CenterY = static_cast<float>(kernel.Center.y);
        s.ConicXX = static_cast<float>(0.5 * kernel.Conic[0][0]);
        s.ConicXY = static_cast<float>(kernel.Conic[1][0]);
        s.ConicYY = static_cast<float>(0.5 * kernel.Conic[1][1]);
        s.Amplitude = static_cast<float>(kernel.Amplitude);

        splat::PlaneDepth depth;
        if (!splat::MakePlaneDepth(clipToModel, clipToEye, viewport, p, n, depth))
        {
          depth.Numerator = glm::dvec3(0.0, 0.0, -eye.z);
          depth.Denominator = glm::dvec3(0.0, 0.0, 1.0);
        }
        for (int c = 0; c < 3; ++c)
        {
          s.DepthNumerator[c] = static_cast<float>(depth.Numerator[c]);
          s.DepthDenominator[c] = static_cast<float>(depth.Denominator[c]);
        }
        const double eyeRadius =
          std::max(glm::length(glm::dvec3(camera.ModelToEye * glm::dvec4(a0, 0.0))),
            glm::length(glm::dvec3(camera.ModelToEye * glm::dvec4(a1, 0.0))));
        s.Threshold = static_cast<float>(depthThreshold * eyeRadius);

        // Two-sided lighting: turn every normal towards the viewer before it is filtered.
        if (backFacing)
        {
          normal = -normal;
        }
        for (int c = 0; c < 3; ++c)
        {
          s.Normal[c] = static_cast<float>(normal[c]);
          s.Color[c] = surfels.Colors[3 * i + c];
        }
      }
    });

  // Binning into bands, serially and in input order: this order is the accumulation order of
  // every pixel, whatever the number of threads.
  const int bands = (height + BandHeight - 1) / BandHeight;
  std::vector<vtkIdType>& offsets = this->Internal->BandOffsets;
  std::vector<vtkIdType>& bandSplats = this->Internal->BandSplats;
  offsets.assign(bands + 1, 0);
  vtkIdType culled[4] = { 0, 0, 0, 0 };
  for (const ScreenSplat& s : splats)
  {
    ++culled[s.Culled];
    if (s.Culled != Kept)
    {
      continue;
    }
    ++this->SplattedCount;
    for (int b = s.Y0 / BandHeight; b <= s.Y1 / BandHeight; ++b)
    {
      ++offsets[b + 1];
    }
  }
  this->FrustumCulledCount = culled[OutsideFrustum];
  this->BackfaceCulledCount = culled[BackFacing];
  this->NegligibleCount = culled[Negligible];
  for (int b = 0; b < bands; ++b)
  {
    offsets[b + 1] += offsets[b];
  }
  bandSplats.resize(offsets[bands]);
  {
    std::vector<vtkIdType> fill(offsets.begin(), offsets.end() - 1);
    for (std::size_t i = 0; i < splats.size(); ++i)
    {
      const ScreenSplat& s = splats[i];
      if (s.Culled != Kept)
      {
        continue;
      }
      for (int b = s.Y0 / BandHeight; b <= s.Y1 / BandHeight; ++b)
      {
        bandSplats[fill[b]++] = static_cast<vtkIdType>(i);
      }
    }
  }

  // 2. Splatting, band by band.
  const float cutoffF = static_cast<float>(cutoff);
  std::vector<vtkIdType> fragments(bands, 0);
  vtkSMPTools::For(0, bands, 1,
    [&](vtkIdType bandBegin, vtkIdType bandEnd)
    {
      for (vtkIdType b = bandBegin; b < bandEnd; ++b)
      {
        const int rowBegin = static_cast<int>(b) * BandHeight;
        const int rowEnd = std::min(rowBegin + BandHeight, height) - 1;
        vtkIdType written = 0;
        for (vtkIdType k = offsets[b]; k < offsets[b + 1]; ++k)
        {
          const ScreenSplat& s = splats[bandSplats[k]];
          const int y0 = std::max(s.Y0, rowBegin);
          const int y1 = std::min(s.Y1, rowEnd);
          for (int y = y0; y <= y1; ++y)
          {
            const float py = y + 0.5f;
            const float dy = py - s.CenterY;
            // The row's span inside the ellipse: roots of XX dx^2 + XY dy dx + YY dy^2 = cutoff.
            const float b = s.ConicXY * dy;
            const float discriminant = b * b - 4.0f * s.ConicXX * (s.ConicYY * dy * dy - cutoffF);
            if (!(discriminant > 0.0f))
            {
              continue;
            }
            const float root = std::sqrt(discriminant);
            const float inverse = 0.5f / s.ConicXX;
            const int xBegin =
              std::max(s.X0, static_cast<int>(std::ceil(s.CenterX + (-b - root) * inverse - 0.5f)));
            const int xEnd =
              std::min(s.X1, static_cast<int>(std::floor(s.CenterX + (-b + root) * inverse - 0.5f)));
            const float rowNum = s.DepthNumerator[1] * py + s.DepthNumerator[2];
            const float rowDen = s.DepthDenominator[1] * py + s.DepthDenominator[2];
            std::size_t pixel = static_cast<std::size_t>(y) * width + xBegin;
            for (int x = xBegin; x <= xEnd; ++x, ++pixel)
            {
              const float px = x + 0.5f;
              const float dx = px - s.CenterX;
              const float beta = s.ConicXX * dx * dx + s.ConicXY * dx * dy + s.ConicYY * dy * dy;
              if (beta >= cutoffF)
              {
                continue;
              }
              const float z = (s.DepthNumerator[0] * px + rowNum) /
                (s.DepthDenominator[0] * px + rowDen);
              float& zPixel = this->EyeDepths[pixel];
              if (z > zPixel + s.Threshold)
              {
                continue; // behind the pixel's surface
              }
              const float w = s.Amplitude * std::exp(-beta);
              float* color = &this->WeightedColors[3 * pixel];
              float* normal = &this->WeightedNormals[3 * pixel];
              if (z < zPixel - s.Threshold)
              {
                // A new, nearer surface replaces what the pixel held.
                zPixel = z;
                this->Weights[pixel] = w;
                for (int c = 0; c < 3; ++c)
                {
                  color[c] = w * s.Color[c];
                  normal[c] = w * s.Normal[c];
                }
              }
              else
              {
                zPixel = std::min(zPixel, z);
                this->Weights[pixel] += w;
                for (int c = 0; c < 3; ++c)
                {
                  color[c] += w * s.Color[c];
                  normal[c] += w * s.Normal[c];
                }
              }
              ++written;
            }
          }
        }
        fragments[b] = written;
      }
    });
  for (vtkIdType f : fragments)
  {
    this->FragmentCount += f;
  }
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::Resolve(
  const Camera& camera, const std::vector<splat::Light>& lights, const splat::Material& material)
{
  const int width = camera.Viewport.x;
  const int height = camera.Viewport.y;
  const std::size_t pixels = this->Weights.size();
  this->Colors.assign(4 * pixels, 0);
  this->Depths.assign(pixels, 1.0f);
  const glm::dmat4& P = camera.EyeToClip;
  const glm::dmat4 clipToEye = glm::inverse(P);

  vtkSMPTools::For(0, height,
    [&](vtkIdType rowBegin, vtkIdType rowEnd)
    {
      for (vtkIdType y = rowBegin; y < rowEnd; ++y)
      {
        for (int x = 0; x < width; ++x)
        {
          const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
          const float w = this->Weights[pixel];
          if (!(w > 0.0f))
          {
            continue;
          }
          // Eye position of the pixel's surface: from the linear depth to NDC z, then unproject.
          const double zEye = -static_cast<double>(this->EyeDepths[pixel]);
          const double zNdc = (P[2][2] * zEye + P[3][2]) / (P[2][3] * zEye + P[3][3]);
          const glm::dvec4 ndc(2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0,
            zNdc, 1.0);
          const glm::dvec4 eye = clipToEye * ndc;
          const glm::vec3 position(glm::dvec3(eye) / eye.w);

          const float* wn = &this->WeightedNormals[3 * pixel];
          glm::vec3 normal(wn[0], wn[1], wn[2]);
          const float length = glm::length(normal);
          normal = length > 0.0f ? normal / length : glm::vec3(0.0f, 0.0f, 1.0f);
          const float* wc = &this->WeightedColors[3 * pixel];
          const glm::vec3 color = glm::vec3(wc[0], wc[1], wc[2]) / w;

          const glm::vec3 shaded = splat::Shade(lights, material, color, position, normal);
          std::uint8_t* rgba = &this->Colors[4 * pixel];
          for (int c = 0; c < 3; ++c)
          {
            rgba[c] = static_cast<std::uint8_t>(
              std::lround(255.0f * std::min(std::max(shaded[c], 0.0f), 1.0f)));
          }
          rgba[3] = 255;
          this->Depths[pixel] =
            static_cast<float>(std::min(std::max(0.5 * zNdc + 0.5, 0.0), 1.0));
        }
      }
    });
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Cutoff: " << this->Cutoff << "\n";
  os << indent << "DepthThreshold: " << this->DepthThreshold << "\n";
  os << indent << "Filter: " << static_cast<int>(this->Filter) << "\n";
  os << indent << "BackfaceCulling: " << this->BackfaceCulling << "\n";
  os << indent << "SplattedCount: " << this->SplattedCount << "\n";
  os << indent << "FrustumCulledCount: " << this->FrustumCulledCount << "\n";
  os << indent << "BackfaceCulledCount: " << this->BackfaceCulledCount << "\n";
  os << indent << "NegligibleCount: " << this->NegligibleCount << "\n";
  os << indent << "FragmentCount: " << this->FragmentCount << "\n";
}
